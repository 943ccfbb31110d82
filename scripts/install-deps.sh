#!/usr/bin/env bash
# Installs the Debian 12 packages ssrt needs (if missing).
#
#   scripts/install-deps.sh          # everything: build, render, test, benchmark and chart
#   scripts/install-deps.sh render   # only what building and running `ssrt` needs
#   scripts/install-deps.sh ci       # everything, and CI's compiler cache and debootstrap
#   scripts/install-deps.sh arm      # the aarch64 cross build's (scripts/test-arm.sh), below
#   scripts/install-deps.sh download # only downloads what `all` installs, into apt's archive
#                                    # cache (scripts/test-fresh.sh --prepare, in its fresh root)
#
# Idempotent: packages already present are skipped, so the README commands can call it on
# every run at the cost of one dpkg query.
set -euo pipefail

# The `ssrt` command: its build and every library it links.
render_packages=(
    # Build
    g++ cmake ninja-build pkg-config
    # Core library
    libglm-dev libxsimd-dev libtbb-dev
    # Edges: image files (PNG, JPEG, Radiance HDR, EXR; OpenImageIO for any other format, in a
    # module loaded on first need), world-space truth, glTF (and its Draco and meshopt
    # compressed meshes), shot files (JSON), command line
    libpng-dev libjpeg62-turbo-dev libstb-dev libopenexr-dev libopenimageio-dev
    libembree-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev nlohmann-json3-dev libcli11-dev
)
# Tests, benchmarks, peers and charts, on top of the render's.
test_packages=(
    # Tests and benchmarks; OpenImageIO's tools (idiff) for comparing images by hand
    doctest-dev libbenchmark-dev openimageio-tools
    # Real glTF 2.0 files the loader is tested on (/usr/share/assimp/models/glTF2)
    assimp-testmodels
    # A second compiler (scripts/test-clang.sh), its sanitizers' run-time libraries
    # (scripts/test-sanitized.sh) and the formatter (scripts/check-format.sh)
    clang libclang-rt-14-dev clang-format
    # perf/peers: Mesa llvmpipe through EGL surfaceless (glvnd's libOpenGL and libEGL)
    libopengl-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
    # Charts (Debian's interpreter: /usr/bin/python3)
    python3-matplotlib
    # Graphviz's dot, which draws `ssrt graph --dot` (its test checks that dot accepts it)
    graphviz
    # man, which formats `ssrt man` (its test checks the page formats without a warning)
    man-db
    # The Python module (python/: pybind11, built for /usr/bin/python3) and its pytest suite
    pybind11-dev python3-dev python3-numpy python3-pytest
)

# CI's own tools, on top of the tests': a compiler cache for its builds (kept outside the
# checkout, so a second run on the machine reuses it), debootstrap for the fresh Debian root
# of scripts/test-fresh.sh, and headless Chromium, which loads `ssrt check`'s HTML report
# (tests/io/check_report_browser.sh; about 100 MB with its libraries, so a newcomer's test
# command does not fetch it and that test says it is skipped). Neither README command needs them.
ci_packages=(ccache debootstrap wget chromium valgrind)

# The aarch64 cross build of scripts/test-arm.sh (cmake/aarch64-linux-gnu.cmake): Debian's cross
# compiler, qemu's user-mode emulator, and the arm64 copies of the libraries the test binary
# and `ssrt` link, installed beside the amd64 ones (multiarch: this adds the arm64 architecture
# to dpkg). OpenEXR comes as its run-time library only and OpenImageIO not at all: their -dev
# packages are not co-installable with the amd64 ones (see the toolchain file). Nothing is
# installed if apt would remove a package to do it: that fails with the package named.
arm_host_packages=(g++-aarch64-linux-gnu qemu-user)
arm64_packages=(libxsimd-dev libtbb-dev libpng-dev libjpeg62-turbo-dev libstb-dev
                libopenexr-3-1-30 libimath-dev libembree-dev libtinygltf-dev libdraco-dev
                libmeshoptimizer-dev)

case "${1:-all}" in
    render) packages=("${render_packages[@]}") ;;
    all) packages=("${render_packages[@]}" "${test_packages[@]}") ;;
    ci) packages=("${render_packages[@]}" "${test_packages[@]}" "${ci_packages[@]}") ;;
    arm) packages=("${render_packages[@]}" "${test_packages[@]}" "${arm_host_packages[@]}"
                   "${arm64_packages[@]/%/:arm64}") ;;
    download) packages=("${render_packages[@]}" "${test_packages[@]}") ;;
    *) echo "usage: $0 [render|all|ci|arm|download]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
        missing+=("$p")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: $([ "${1:-}" = download ] && echo downloading || echo installing) ${missing[*]}" >&2
t0=$SECONDS
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
if [ "${1:-}" = arm ] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    $sudo dpkg --add-architecture arm64
fi
$sudo apt-get update -qq
if [ "${1:-}" = arm ]; then
    # An arm64 package that is not Multi-Arch: same would replace its amd64 copy: refuse.
    removed=$(apt-get -s install --no-install-recommends "${missing[@]}" |
              awk '/^Remv /{print $2}' | tr '\n' ' ')
    if [ -n "$removed" ]; then
        echo "install-deps: installing the arm64 packages would remove ${removed% }" >&2
        exit 1
    fi
fi
if [ "${1:-}" = download ]; then
    $sudo apt-get install -y -qq --no-install-recommends --download-only "${missing[@]}" >/dev/null
    echo "install-deps: downloaded ${#missing[@]} packages and their dependencies in $((SECONDS - t0)) s" >&2
    exit 0
fi
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
# (scripts/test-fresh.sh reads this line for the README's times.)
echo "install-deps: installed ${#missing[@]} packages and their dependencies in $((SECONDS - t0)) s" >&2
