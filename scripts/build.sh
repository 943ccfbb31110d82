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
    targets=(--target ssrt_cli)
    what="the ssrt command"
else
    bash scripts/install-deps.sh
    options=(-DSSRT_BUILD_TESTS=ON -DSSRT_BUILD_PERF=ON -DSSRT_BUILD_PYTHON=ON)
    targets=()
    what="every target"
fi
source scripts/lib/compiler-cache.sh
t0=$SECONDS
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${compiler_cache[@]}" "${options[@]}" \
      >/dev/null
cmake --build build "${targets[@]}" --parallel "$jobs"
# (scripts/test-fresh.sh reads this line for the README's times.)
echo "build: $what in build/ in $((SECONDS - t0)) s" >&2
