#!/usr/bin/env bash
# Installs every Debian 12 package ssrt needs to build, test, benchmark and chart.
# Idempotent: packages already present are skipped, so both README commands can
# call it on every run at the cost of one dpkg query.
set -euo pipefail

packages=(
    # Build
    g++ cmake ninja-build pkg-config
    # Core library
    libglm-dev libxsimd-dev libtbb-dev
    # Edges: image files, world-space truth, glTF, shot files (JSON), command line
    libopenimageio-dev openimageio-tools libembree-dev libtinygltf-dev nlohmann-json3-dev
    libcli11-dev
    # Tests and benchmarks
    doctest-dev libbenchmark-dev
    # perf/peers: Mesa llvmpipe through EGL surfaceless
    libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
    # Charts (Debian's interpreter: /usr/bin/python3)
    python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
        missing+=("$p")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
