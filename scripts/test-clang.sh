#!/usr/bin/env bash
# A second compiler: builds the renderer and the tests with clang 14 in build-clang/, runs the
# golden-hash and determinism tests there, and renders the same inputs with the gcc build
# (build/ssrt) and the clang build, whose EXR files must be the same bytes. CI runs it after
# scripts/test.sh (which leaves build/ built; else the gcc `ssrt` is built first).
#
# Each build's tests hold every ISA and thread count to its scalar copy, so comparing the two
# builds at the best ISA the CPU runs covers the others. The renders stay in
# build-clang/compare/ (gcc/ and clang/), for a look when they differ.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${SSRT_BUILD_JOBS:-$(nproc)}"

bash scripts/install-deps.sh
cxx="${SSRT_CLANG_CXX:-clang++-14}"
cc="${SSRT_CLANG_CC:-clang-14}"
"$cxx" --version | head -n 1

# The gcc build's command, up to date (nothing to do after scripts/test.sh).
bash scripts/build.sh --render

# Golden hashes, and the same bits for every ISA and thread count (renderer, rasterizer,
# ray generation, SSGI, marching rays alone or together): the cases this build runs.
cases='built-in scenes keep their golden hashes,every ISA and thread count*,*the same bits*'

# The clang build: the command and the test files that hold those cases (no benchmarks), its
# libraries a unity build (scripts/lib/second-build.sh).
source scripts/lib/second-build.sh
t0=$SECONDS
CC="$cc" CXX="$cxx" cmake -S . -B build-clang -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DSSRT_BUILD_TESTS=ON -DSSRT_BUILD_PERF=OFF "-DSSRT_TEST_FILES=$(test_files_for "$cases")" \
    "${second_build[@]}" >/dev/null
cmake --build build-clang --target ssrt_cli ssrt_tests --parallel "$jobs"
echo "test-clang: built build-clang/ in $((SECONDS - t0)) s" >&2
same_cases test-clang -tc="$cases" -- ./build-clang/tests/ssrt_tests

run_cases test-clang -tc="$cases" -- ./build-clang/tests/ssrt_tests

# The golden-image suite (tests/golden/suite.json, made by the gcc build) rendered by the clang
# build: every case exact. Its report stays in build-clang/golden-report/.
./build-clang/ssrt check tests/golden/suite.json --out build-clang/golden-report

# The same EXR bytes from both compilers (scripts/lib/compare-renders.sh lists the inputs).
source scripts/lib/compare-renders.sh
gcc=(build/ssrt)
clang=(build-clang/ssrt)
compare_renders test-clang build-clang/compare gcc clang default
