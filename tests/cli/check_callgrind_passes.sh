#!/usr/bin/env bash
# perf/callgrind_passes.py on a small frame: the scopes' marks are paired and nested (it exits
# non-zero where one ends that is not the innermost open), the frame's passes are all there,
# and they hold nearly all of the render call's instructions (the rest is the call's own work
# between passes: checks, the graph, the stats).
# Usage: check_callgrind_passes.sh SSRT SOURCE_DIR (ctest passes both).
set -euo pipefail
ssrt="$1"
src="$2"
fail() {
    echo "check_callgrind_passes: FAIL: $*" >&2
    exit 1
}
out=$(python3 "$src/perf/callgrind_passes.py" --ssrt "$ssrt" -- --scene cornell --width 64 \
    --height 36 --warmup-frames 1 -j 2) || fail "the script failed"
echo "$out"
for pass in shadow visibility "resolve + shading" hi-z ssr "denoise post-blur + composite"; do
    grep -q "^  $pass  " <<<"$out" || fail "no row for '$pass'"
done
# Instructions: the rows inside the call (every line but the header lines and the call's).
read -r parts call < <(awk '/^  / { n = $(NF - 1); gsub(",", "", n);
    if ($0 ~ /^  render call /) call = n; else parts += n }
    END { print parts, call }' <<<"$out")
[ "$call" -gt 0 ] || fail "no render call's instructions"
awk -v p="$parts" -v c="$call" 'BEGIN { exit !(p <= c && p >= 0.9 * c) }' ||
    fail "the passes hold $parts of the render call's $call instructions"
echo "check_callgrind_passes: ok: the passes hold $parts of the render call's $call instructions"
