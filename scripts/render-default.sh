#!/usr/bin/env bash
# README command 1: build the `ssrt` command alone (no tests, no benchmarks), then render the
# default built-in scene (cornell) to cornell.png (ssrt names a render after its scene).
# Extra arguments go to `ssrt render` (e.g. --scene spheres -o spheres.exr --stats).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --render
./build/ssrt render "$@"
