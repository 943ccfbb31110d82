#!/usr/bin/env bash
# Another architecture: builds the renderer and the tests for aarch64 in build-arm/ (Debian's
# cross compiler and arm64 libraries, cmake/aarch64-linux-gnu.cmake), runs the golden-hash and
# bit-identity tests under qemu-aarch64, with the golden hashes recorded on x86-64, and renders
# the same inputs with the x86-64 build (build/ssrt) and the aarch64 build, at the default
# preset and at ultra, whose EXR files must be the same bytes. CI runs it after
# scripts/test.sh (which leaves build/ built; else the x86-64 `ssrt` is built first).
#
# The aarch64 tests hold the scalar and NEON kernels, on 1, 2 and 8 threads, to the scalar
# copy and to the x86-64 golden hashes; the renders compare x86-64's best ISA with NEON (auto
# on each), so with each build's own tests every ISA of both architectures is covered.
#
# Skips with one line (`test-arm: SKIPPED: ...`, exit 0) only where the arm64 packages cannot
# be installed (`install-deps.sh arm`: no arm64 archive, or apt would remove a package to
# install them); every other failure fails. The renders stay in build-arm/compare/ (x86/ and
# arm/), for a look when they differ.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${SSRT_BUILD_JOBS:-$(nproc)}"

bash scripts/install-deps.sh
if ! log=$(bash scripts/install-deps.sh arm 2>&1); then
    echo "test-arm: SKIPPED: the arm64 packages cannot be installed: $(tail -n 1 <<<"$log")"
    exit 0
fi
[ -z "$log" ] || echo "$log" >&2
aarch64-linux-gnu-g++ --version | head -n 1
qemu-aarch64 --version | head -n 1

# The x86-64 build's command, up to date (nothing to do after scripts/test.sh).
bash scripts/build.sh --render

# Under emulation, about 30 times slower than natively: only the cases that hold bits. Golden
# hashes (built-in scenes, denoised camera paths), the same bits for every ISA and thread
# count (renderer, rasterizer, ray generation, SSGI, marching, layouts, denoiser, truth), and
# the lane math (transcendentals, division, sqrt) against the scalar copy. A doctest filter
# (comma-separated, * any text); the files that hold them are the only ones compiled.
cases='*keep their golden hashes*,every ISA and thread count*,*the same bits*,lane math: every ISA returns the scalar bits'
# (a NaN's bits in image comparison, in a file that needs OpenImageIO, which this build leaves out)
not_here='image compare:*'

# The aarch64 build: the command and those tests, nothing else; its libraries a unity build
# (scripts/lib/second-build.sh).
source scripts/lib/second-build.sh
test_files=$(test_files_for "$cases")
[ -n "$test_files" ] || { echo "test-arm: no test file holds the cases '$cases'" >&2; exit 1; }
t0=$SECONDS
cmake -S . -B build-arm -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
    -DSSRT_BUILD_TESTS=ON -DSSRT_BUILD_PERF=OFF -DSSRT_BUILD_PYTHON=OFF \
    "-DSSRT_TEST_FILES=$test_files" \
    "${second_build[@]}" >/dev/null
cmake --build build-arm --target ssrt_cli ssrt_tests --parallel "$jobs"
echo "test-arm: built build-arm/ in $((SECONDS - t0)) s" >&2

same_cases test-arm -tc="$cases" -tce="$not_here" -- qemu-aarch64 build-arm/tests/ssrt_tests
t0=$SECONDS
# One thread count per case (tests/thread_counts.h): under qemu-user the threads run on this
# machine's cores in its memory order, so more of them prove nothing the native runs do not.
SSRT_TEST_THREADS=single run_cases test-arm -tc="$cases" -tce="$not_here" -- \
    qemu-aarch64 build-arm/tests/ssrt_tests
echo "test-arm: tests under qemu-aarch64 in $((SECONDS - t0)) s" >&2

# The same EXR bytes from both architectures (scripts/lib/compare-renders.sh lists the inputs).
source scripts/lib/compare-renders.sh
x86=(build/ssrt)
arm=(qemu-aarch64 build-arm/ssrt)
t0=$SECONDS
compare_renders test-arm build-arm/compare x86 arm default ultra
echo "test-arm: renders in $((SECONDS - t0)) s" >&2
