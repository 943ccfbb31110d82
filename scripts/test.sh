#!/usr/bin/env bash
# README command 2: build, then run the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure --parallel "${SSRT_TEST_JOBS:-$(nproc)}" --timeout 900
bash ../scripts/check-doc-blocks.sh .   # the docs' runnable blocks and the flags they name
