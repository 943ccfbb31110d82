#!/usr/bin/env bash
# Installs the dependencies (if missing), configures and builds ssrt in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --parallel "${SSRT_BUILD_JOBS:-$(nproc)}"
