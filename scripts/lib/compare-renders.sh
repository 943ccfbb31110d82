# Sourced by the scripts that hold a second build to the first's bytes (test-clang.sh: another
# compiler; test-arm.sh: another architecture): both builds render the same inputs at 160x90
# and every EXR file must be the same bytes.
#
#   compare_renders LABEL OUT A B QUALITY...
#
# A and B name arrays holding each build's command (e.g. a=(build/ssrt),
# b=(qemu-aarch64 build-arm/ssrt)); the renders stay in OUT/<A>/ and OUT/<B>/ for a look when
# they differ. Each QUALITY is `default` (no flag) or a --quality preset; every input is
# rendered at each. The inputs: every built-in scene (as build A lists them), an image sky (a
# shot file), textured glTFs (a data-URI PNG, the same quad as a .glb, the quad with normal,
# occlusion and emissive maps), compressed meshes (the Draco box, the meshopt sphere), and the
# trace layouts (trace/trace_layout.h) on two scenes, in a frame where both phases and the
# half-resolution pick are not frame 0's ("layout:SCENE"), and SSR and SSGI traced in mixed and
# in world mode through Embree ("mixed:SCENE", "world:SCENE"; "pooled:SCENE" mixed with only the
# colour kept, so the frame gives its planes back early). Returns 1 when any file differs.
# (compare_renders' own: waits until fewer than $1 renders run, oldest first, keeping their
# process ids in its `pids` and noting a failed one in its `status`. `wait PID`, not `wait -n`,
# which can miss a job that ended while a command substitution ran.)
_cr_throttle() {
    while [ "${#pids[@]}" -ge "$1" ]; do
        wait "${pids[0]}" || status=1
        pids=("${pids[@]:1}")
    done
}

compare_renders() {
    local label=$1 out=$2 name_a=$3 name_b=$4
    local -n _cr_a=$3 _cr_b=$4  # (names of their own: a nameref must not name itself)
    shift 4
    local inputs=() scene
    for scene in $("${_cr_a[@]}" scenes | awk '{print $1}'); do inputs+=("scene:$scene"); done
    inputs+=(shot:examples/shots/spheres_sky.json
             scene:tests/fuzz/seeds/gltf/textured_quad_datauri.gltf
             scene:tests/fuzz/seeds/gltf/textured_quad.glb
             scene:tests/fuzz/seeds/gltf/material_maps_datauri.gltf
             scene:tests/scenes/data/draco_box.gltf
             scene:tests/fuzz/seeds/gltf/meshopt_sphere.glb)
    [ ${#inputs[@]} -ge 10 ] || { echo "$label: too few inputs: ${inputs[*]}" >&2; return 1; }
    inputs+=(layout:cornell layout:corridor mixed:cornell mixed:fence world:spheres
             pooled:spheres)

    rm -rf "$out"
    mkdir -p "$out/$name_a" "$out/$name_b"
    # Every render first, as many at once as there are cores (one under an emulator is slow and
    # mostly one thread), then every pair of files compared.
    local jobs="${SSRT_BUILD_JOBS:-$(nproc)}" pids=() renders=() status=0 count=0
    local input quality kind what name extra
    for quality in "$@"; do
        for input in "${inputs[@]}"; do
            kind=${input%%:*} what=${input#*:}
            name=$(basename "$what" | tr '.' '_')
            extra=()
            if [ "$kind" = layout ]; then
                kind=scene name="${what}_layouts"
                extra=(--ssr-layout checkerboard --ssgi-layout half --frame 3)
            elif [ "$kind" = mixed ] || [ "$kind" = world ]; then
                extra=(--ssr-trace "$kind" --ssgi-trace "$kind")
                kind=scene name="${what}_$kind"
            elif [ "$kind" = pooled ]; then
                extra=(--ssr-trace mixed --ssgi-trace mixed --layers color)
                kind=scene name="${what}_mixed_colour"
            fi
            if [ "$quality" != default ]; then
                name="${name}_$quality"
                extra+=(--quality "$quality")
            fi
            extra+=(--width 160 --height 90 --quiet)
            renders+=("$name $input ($quality)")
            "${_cr_a[@]}" render "--$kind" "$what" "${extra[@]}" -o "$out/$name_a/$name.exr" &
            pids+=($!)
            _cr_throttle "$jobs"
            "${_cr_b[@]}" render "--$kind" "$what" "${extra[@]}" -o "$out/$name_b/$name.exr" &
            pids+=($!)
            _cr_throttle "$jobs"
        done
    done
    _cr_throttle 1
    [ $status -eq 0 ] || echo "$label: FAIL: a render failed (its error above)" >&2
    local render
    for render in "${renders[@]}"; do
        name=${render%% *}
        count=$((count + 1))
        if cmp "$out/$name_a/$name.exr" "$out/$name_b/$name.exr"; then
            echo "$label: same EXR bytes: ${render#* }"
        else
            echo "$label: FAIL: $name_a and $name_b EXR files differ: ${render#* }" \
                 "($out/$name_a/$name.exr, $out/$name_b/$name.exr)" >&2
            status=1
        fi
    done
    if [ $status -ne 0 ]; then
        echo "$label: FAIL: the $name_b build renders other bytes than the $name_a build" >&2
        return 1
    fi
    echo "$label: $name_a and $name_b agree on $count renders, byte for byte"
}
