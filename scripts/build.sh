#!/usr/bin/env bash
# Installs the dependencies (if missing), configures and builds ssrt in build/ (Release).
#
#   scripts/build.sh            # every target: the renderer, the tests, the benchmarks
#   scripts/build.sh --render   # only the `ssrt` command (build/ssrt) and what it links
#
# --render installs only the render's packages and, on a build/ not configured yet,
# configures it without the tests and benchmarks (their packages may be missing). It never
# changes the options of a build/ that exists, and the full build turns the tests and
# benchmarks on explicitly, so the two share build/ without undoing each other.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${SSRT_BUILD_JOBS:-$(nproc)}"

if [ "${1:-}" = "--render" ]; then
    bash scripts/install-deps.sh render
    options=()
    [ -f build/CMakeCache.txt ] || options=(-DSSRT_BUILD_TESTS=OFF -DSSRT_BUILD_PERF=OFF)
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
    cmake --build build --target ssrt_cli --parallel "$jobs"
else
    bash scripts/install-deps.sh
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSSRT_BUILD_TESTS=ON \
          -DSSRT_BUILD_PERF=ON >/dev/null
    cmake --build build --parallel "$jobs"
fi
