#!/usr/bin/env bash
# Checks ssrt's FLIP (io/flip.h) against the values the FLIP authors publish for their example
# pair: the test script of their repository (NVlabs/flip, src/tests/test.py) expects the mean
# 0.159691 for LDR-FLIP of images/test.png against images/reference.png and 0.283478 for
# HDR-FLIP of images/test.exr against images/reference.exr (default settings: 67.02 pixels
# per degree, ACES, exposures from the reference).
#
#   perf/flip_check.sh DIR [SSRT]   DIR holds reference.png, test.png, reference.exr, test.exr
#                                   (their images/ folder); SSRT defaults to build/ssrt
#
# The images are not part of ssrt; a pair that is missing is skipped (exit 0 with a line
# saying so). Their tool prints a mean it sums in float, ssrt sums in double, so the sixth
# digit can differ by one or two units (perf/README.md, "FLIP").
set -uo pipefail
dir=${1:?usage: perf/flip_check.sh DIR [SSRT]}
ssrt=${2:-$(dirname "$0")/../build/ssrt}
status=0
check() {  # kind, extension, expected mean
    local kind=$1 ext=$2 expected=$3
    local ref="$dir/reference.$ext" test="$dir/test.$ext"
    if [ ! -f "$ref" ] || [ ! -f "$test" ]; then
        echo "$kind: skipped, $ref or $test missing"
        return
    fi
    local line
    line=$("$ssrt" diff "$test" "$ref" --flip | grep -- "-FLIP (")
    echo "$line"
    local mean
    mean=$(sed -n 's/.*mean \([0-9.]*\),.*/\1/p' <<<"$line")
    if [ "$mean" = "$expected" ]; then
        echo "$kind: mean $mean, the authors' $expected: the same to 6 digits"
    else
        echo "$kind: mean $mean, the authors' $expected: DIFFERENT"
        status=1
    fi
}
check LDR-FLIP png 0.159691
check HDR-FLIP exr 0.283478
exit $status
