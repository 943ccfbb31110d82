#!/usr/bin/env bash
# The glTF loader, shot files, image I/O and command-line tests (issue 4: the loader must run
# clean on malformed files) and the screen-space tracer's tests (marchers, ray generation,
# resolve, SSGI, composite, the renderer's trace passes, the frame's name tables, the settings
# field tables), the material maps and alpha cut-outs (raster and truth), the Embree scene,
# ray checks,
# reference image, image error, the compare and sweep commands and their sequences,
# the image comparison (ssrt diff, render --compare), shards and ssrt merge, the reference
# cache's racing writers, the cgroup memory reader, under AddressSanitizer and
# UndefinedBehaviorSanitizer.
# Then the libFuzzer targets of tests/fuzz (built here too: -DSSRT_BUILD_FUZZ=ON) replay their
# committed seeds (scripts/fuzz.sh replay): a crash, leak or UB report on any fails.
# Builds in build-asan/; CI runs it after scripts/test.sh.
#
# The build is made for these tests and nothing else, which took this stage of CI from 59
# minutes (52 of them building) to 8 on an empty compiler cache (405 s building, 2 cores):
#  - clang 14, not gcc: gcc 12 spends 60-125 s on each of the heaviest kernel files with the
#    sanitizers' instrumentation (the denoiser's kernels, then one file: 124 s at -O2 -g, 90 s
#    at -O2 -g1), clang 4 s; clang's sanitizers are the reference implementation, and clang is
#    already CI's second compiler (test-clang.sh) and the fuzzer's;
#  - -O1 -gline-tables-only: what a sanitizer report needs (file and line of every frame),
#    without the variable locations that cost minutes;
#  - two kernel families, scalar (the oracle the ISA tests compare with) and avx2 (a SIMD
#    family, with its masked and gathered loads), of five: cmake/kernels.cmake's SSRT_ISAS;
#    the other families are the same templates at other widths;
#  - only the ssrt_tests target, no benchmarks, and in it only the test files that hold the
#    cases run here (scripts/lib/second-build.sh's test_files_for);
#  - the libraries as a unity build (scripts/lib/second-build.sh, which configures this build
#    and test-tsan.sh's).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# The cases that run (doctest's filter); only the test files that hold them are compiled.
cases='frame:*,alpha cut-out:*,alpha truth:*,normal map:*,occlusion texture:*,emissive texture:*,tangents:*,settings fields:*,march:*,march keys:*,embree scene:*,ray check:*,image error:*,reference:*,reference bounces:*,compare*,sweep:*,ray generation:*,ssr*,ssgi*,composite:*,renderer: *,shot:*,cli shot:*,sky image io:*,texture*,*gltf*,*glTF*,*GLB*,cli:*,*EXR*,*PNG*,*unwritable*,*extension*,*checkWritable*,*writing over*,cli sequence:*,sweep --frames*,camera path:*,readChannels*,denoise:*,quality:*,trace layouts:*,checkerboard*,half resolution*,cli diff:*,cli render --compare:*,image compare:*,decoders*,shard:*,reference cache:*,image limits:*,command line:*,cli limits:*,cgroup memory:*'
source scripts/lib/second-build.sh
t0=$SECONDS
configure_clang_sanitizer_build build-asan -DSSRT_SANITIZE=ON -DSSRT_BUILD_FUZZ=ON \
    -DSSRT_BUILD_PYTHON=OFF "-DSSRT_TEST_FILES=$(test_files_for "$cases")"
cmake --build build-asan --target ssrt_tests ssrt_fuzz --parallel "${SSRT_BUILD_JOBS:-$(nproc)}"
echo "test-sanitized: built build-asan/ in $((SECONDS - t0)) s" >&2
source scripts/lib/sanitizer-options.sh
same_cases test-sanitized -tc="$cases" -- ./build-asan/tests/ssrt_tests
run_cases test-sanitized -tc="$cases" -- ./build-asan/tests/ssrt_tests
t0=$SECONDS
bash scripts/fuzz.sh replay
echo "test-sanitized: replayed the fuzz seeds in $((SECONDS - t0)) s" >&2
