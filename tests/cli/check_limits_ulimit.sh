#!/usr/bin/env bash
# Under `ulimit -v 4000000` (4 GB of address space), issue 33's limits still end in one line
# naming the file or the flags and the limit, exit 3, nothing written: the 68-byte PNG that
# claims 60000 x 60000 pixels as an environment image, and an 8192 x 8192 frame.
# Usage: check_limits_ulimit.sh SSRT SOURCE_DIR (ctest passes both).
set -uo pipefail
ssrt="$1"
png="$2/tests/io/data/oversized/big.png"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '{"scene": "spheres", "environment": {"type": "image", "file": "%s"}}' "$png" \
    >"$dir/shot.json"
fail() { echo "check_limits_ulimit: $*" >&2; exit 1; }
expect() {  # expect PATTERN ARGS...: exit 3, one line matching PATTERN, no output file
    local pattern="$1"
    shift
    (ulimit -v 4000000 && "$ssrt" "$@" -o "$dir/out.png" 2>"$dir/err")
    local code=$?
    [ "$code" = 3 ] || fail "exit $code, not 3: $* ($(cat "$dir/err"))"
    [ "$(wc -l <"$dir/err")" = 1 ] || fail "not one line: $(cat "$dir/err")"
    grep -q "$pattern" "$dir/err" || fail "no '$pattern' in: $(cat "$dir/err")"
    [ ! -e "$dir/out.png" ] || fail "out.png written: $*"
    cat "$dir/err"
}
expect "^ssrt: error: cannot read '$png': the image is 60000 x 60000 pixels, over the limit of 134217728 pixels" \
    render --shot "$dir/shot.json"
expect "^ssrt: error: --width, --height: a 8192 x 8192 frame needs about .* this process may use (ulimit -v)$" \
    render --width 8192 --height 8192
