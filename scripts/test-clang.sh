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

# The clang build: the command and the tests (no benchmarks).
source scripts/lib/compiler-cache.sh
t0=$SECONDS
CC="$cc" CXX="$cxx" cmake -S . -B build-clang -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DSSRT_BUILD_TESTS=ON -DSSRT_BUILD_PERF=OFF "${compiler_cache[@]}" >/dev/null
cmake --build build-clang --target ssrt_cli ssrt_tests --parallel "$jobs"
echo "test-clang: built build-clang/ in $((SECONDS - t0)) s" >&2

# Golden hashes, and the same bits for every ISA and thread count (renderer, rasterizer,
# ray generation, SSGI, marching rays alone or together).
./build-clang/tests/ssrt_tests \
    -tc='built-in scenes keep their golden hashes,every ISA and thread count*,*the same bits*'

# The golden-image suite (tests/golden/suite.json, made by the gcc build) rendered by the clang
# build: every case exact. Its report stays in build-clang/golden-report/.
./build-clang/ssrt check tests/golden/suite.json --out build-clang/golden-report

# The same EXR bytes from both compilers: every built-in scene, an image sky (a shot file),
# textured glTFs (a data-URI PNG, the same quad as a .glb, and the quad with normal, occlusion
# and emissive maps), and compressed meshes (the Draco box, the meshopt sphere).
out=build-clang/compare
rm -rf "$out"
mkdir -p "$out/gcc" "$out/clang"
inputs=()
for scene in $(./build/ssrt scenes | awk '{print $1}'); do inputs+=("scene:$scene"); done
inputs+=(shot:examples/shots/spheres_sky.json
         scene:tests/fuzz/seeds/gltf/textured_quad_datauri.gltf
         scene:tests/fuzz/seeds/gltf/textured_quad.glb
         scene:tests/fuzz/seeds/gltf/material_maps_datauri.gltf
         scene:tests/scenes/data/draco_box.gltf
         scene:tests/fuzz/seeds/gltf/meshopt_sphere.glb)
[ ${#inputs[@]} -ge 10 ] || { echo "test-clang: too few inputs: ${inputs[*]}" >&2; exit 1; }
# The trace layouts (trace/trace_layout.h) on two scenes, in a frame where both phases and
# the half-resolution pick are not frame 0's: "layout:SCENE".
inputs+=(layout:cornell layout:corridor)

status=0
for input in "${inputs[@]}"; do
    kind=${input%%:*} what=${input#*:}
    name=$(basename "$what" | tr '.' '_')
    extra=()
    if [ "$kind" = layout ]; then
        kind=scene name="${what}_layouts"
        extra=(--ssr-layout checkerboard --ssgi-layout half --frame 3)
    fi
    for build in gcc clang; do
        bin=build/ssrt
        [ $build = clang ] && bin=build-clang/ssrt
        "$bin" render "--$kind" "$what" --width 160 --height 90 --quiet "${extra[@]}" \
            -o "$out/$build/$name.exr"
    done
    if cmp "$out/gcc/$name.exr" "$out/clang/$name.exr"; then
        echo "test-clang: same EXR bytes: $input"
    else
        echo "test-clang: FAIL: gcc and clang EXR files differ: $input" \
             "($out/gcc/$name.exr, $out/clang/$name.exr)" >&2
        status=1
    fi
done
if [ $status -ne 0 ]; then
    echo "test-clang: FAIL: the clang build renders other bytes than the gcc build" >&2
    exit 1
fi
echo "test-clang: gcc and clang agree on ${#inputs[@]} renders, byte for byte"
