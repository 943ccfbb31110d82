#!/usr/bin/env bash
# Installs the built ssrt into a fresh prefix, then builds against it, through
# find_package(ssrt COMPONENTS ...): the core-only example of docs/embedding.md, a tool on every component
# (tool_example.cpp: a glTF file, a sequence with history, an EXR, the Embree truth) and every
# installed header on its own. Runs both examples, and checks that the package refuses a
# component it does not have and a version it is not, and that the ssrt command's completion
# and man page are installed.
# Usage: check_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
# Under the build folder, at the same path every run, so that a compiler cache keyed on paths
# relative to the checkout (scripts/lib/compiler-cache.sh) serves the consumer's units too.
work=$(cd "$build" && pwd)/install-check
rm -rf "$work"
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
# The command's bash completion and man page, where bash-completion and man look for them.
if [ -x "$build/ssrt" ]; then
    for f in share/bash-completion/completions/ssrt share/man/man1/ssrt.1; do
        [ -s "$work/prefix/$f" ] || { echo "FAIL: the install has no $f" >&2; exit 1; }
    done
fi
# The build's compiler cache, if it has one.
launcher=$(sed -n 's/^CMAKE_CXX_COMPILER_LAUNCHER:[A-Z]*=//p' "$build/CMakeCache.txt")
cmake -S "$src/tests/install" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
      "-DCMAKE_CXX_COMPILER_LAUNCHER=$launcher" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/embed_example"
# Each component brings its own libraries and no other's: the core-only tool loads no image,
# glTF or Embree library, the tool on every component loads them.
# (ldd's lists read whole first: `ldd | grep -q` under pipefail fails when grep stops early and
# ldd is killed by the closed pipe, which made this check flaky on a loaded machine.)
core_libs=$(ldd "$work/consumer/embed_example")
all_libs=$(ldd "$work/consumer/tool_example")
for lib in libembree3 libOpenEXR libpng libtinygltf libdraco; do
    if grep -q "$lib" <<<"$core_libs"; then
        echo "FAIL: embed_example (ssrt::core only) loads $lib" >&2
        exit 1
    fi
    grep -q "$lib" <<<"$all_libs" ||
        { echo "FAIL: tool_example (every component) does not load $lib" >&2; exit 1; }
done
"$work/consumer/tool_example" "$src/tests/fuzz/seeds/gltf/material_maps_datauri.gltf" "$work/out.exr"

# What the package must refuse, each with its reason in the message.
refuse() {  # refuse WHAT FIND_PACKAGE_ARGS EXPECTED_MESSAGE
    mkdir -p "$work/refuse"
    printf 'cmake_minimum_required(VERSION 3.25)\nproject(p LANGUAGES CXX)\nfind_package(%s)\n' \
        "$2" >"$work/refuse/CMakeLists.txt"
    if out=$(cmake -S "$work/refuse" -B "$work/refuse/build" -G Ninja \
                   -DCMAKE_PREFIX_PATH="$work/prefix" 2>&1); then
        echo "FAIL: find_package($2) was accepted ($1)" >&2
        exit 1
    fi
    grep -q "$3" <<<"$out" || { echo "FAIL: find_package($2): no '$3' in: $out" >&2; exit 1; }
    rm -rf "$work/refuse"
}
refuse "an unknown component" "ssrt REQUIRED COMPONENTS core nosuch" "no component 'nosuch'"
refuse "a later version" "ssrt 9.0 REQUIRED" "that is compatible"
echo "install: every component found, both examples ran, the package refused what it lacks"
