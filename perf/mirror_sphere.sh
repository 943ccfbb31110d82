#!/bin/bash
# Cornell's mirror sphere at 1280x720, SSR and SSGI traced on screen, mixed and in world space,
# beside the Embree reference: a crop of each (rows 430-670, columns 700-960, sRGB), side by side.
# The sphere's lower third reflects the floor behind it, which no pixel shows: the screen
# shows the environment there, mixed and world the lit floor. Uses oiiotool (OpenImageIO).
#
#   perf/mirror_sphere.sh build/ssrt perf/charts/mirror_sphere.png
set -euo pipefail
[ $# -eq 2 ] || { sed -n '2,7p' "$0" >&2; exit 2; }
ssrt=$1 out=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
crop=(--cut 260x240+700+430 --colorconvert linear sRGB --resize 390x360)
panels=()
for mode in screen mixed world; do
    "$ssrt" render --scene cornell --width 1280 --height 720 --ssr-trace "$mode" \
        --ssgi-trace "$mode" --quiet --layers color -o "$dir/$mode.exr"
    oiiotool "$dir/$mode.exr" --ch color.R,color.G,color.B "${crop[@]}" -o "$dir/$mode.png"
    panels+=("$dir/$mode.png")
done
"$ssrt" reference --scene cornell --width 1280 --height 720 --quiet -o "$dir/reference.exr"
oiiotool "$dir/reference.exr" --ch ref.color.R,ref.color.G,ref.color.B "${crop[@]}" \
    -o "$dir/reference.png"
panels+=("$dir/reference.png")
oiiotool "${panels[@]}" --mosaic:pad=4 4x1 -o "$dir/out.png"
mv "$dir/out.png" "$out"
echo "wrote $out (screen, mixed, world, reference)"
