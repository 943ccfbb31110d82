#!/usr/bin/env bash
# The glTF loader, shot files, image I/O and command-line tests (issue 4: the loader must run
# clean on malformed files) and the screen-space tracer's tests (marchers, ray generation,
# resolve, SSGI, composite, the renderer's trace passes, the frame's name tables, the settings
# field tables), the material maps and alpha cut-outs (raster and truth), the Embree scene,
# ray checks,
# reference image, image error, the compare and sweep commands and their sequences,
# the image comparison (ssrt diff, render --compare), shards and ssrt merge, the reference
# cache's racing writers, under AddressSanitizer and UndefinedBehaviorSanitizer.
# Builds in build-asan/; CI runs it after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSSRT_SANITIZE=ON \
      -DSSRT_BUILD_PERF=OFF >/dev/null
cmake --build build-asan --target ssrt_tests --parallel "${SSRT_BUILD_JOBS:-$(nproc)}"
# tinygltf is a system library built without ASan: containers it fills trip ASan's
# container-overflow annotations falsely, so that one check is off.
export ASAN_OPTIONS=detect_container_overflow=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# One known leak inside OpenImageIO on corrupt PNGs (see the file).
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp
./build-asan/tests/ssrt_tests -tc='frame:*,alpha cut-out:*,alpha truth:*,normal map:*,occlusion texture:*,emissive texture:*,tangents:*,settings fields:*,march:*,march keys:*,embree scene:*,ray check:*,image error:*,reference:*,reference bounces:*,compare*,sweep:*,ray generation:*,ssr*,ssgi*,composite:*,renderer: *,shot:*,cli shot:*,sky image io:*,texture*,*gltf*,*glTF*,*GLB*,cli:*,*EXR*,*PNG*,*unwritable*,*extension*,*checkWritable*,*writing over*,cli sequence:*,sweep --frames*,camera path:*,readChannels*,denoise:*,quality:*,trace layouts:*,checkerboard*,half resolution*,cli diff:*,cli render --compare:*,image compare:*,shard:*,reference cache:*'
