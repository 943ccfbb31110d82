#!/usr/bin/env bash
# `ssrt render` inside a real cgroup with a 400 MB memory limit (v2 memory.max, else v1's
# memory.limit_in_bytes): a 4096 x 4096 frame is refused before any work in one line naming the
# cgroup's limit file, exit 3, nothing written; a 64 x 36 frame renders. Where no cgroup can be
# made (not root, no memory controller, a read-only cgroup file system) it says why and exits
# 77, which ctest shows as skipped.
# Usage: check_cgroup_limit.sh SSRT (ctest passes it).
set -uo pipefail
ssrt="$1"
skip() { echo "check_cgroup_limit: skipped: $*"; exit 77; }
fail() { echo "check_cgroup_limit: $*" >&2; exit 1; }
limit=400000000

# The memory controller's mount: cgroup2 where it offers memory to its children, else v1's.
v2=$(awk '$(NF-2) == "cgroup2" {print $5; exit}' /proc/self/mountinfo)
v1=$(awk '$(NF-2) == "cgroup" && ("," $NF ",") ~ /,memory,/ {print $5; exit}' /proc/self/mountinfo)
if [ -n "$v2" ] && grep -qw memory "$v2/cgroup.subtree_control" 2>/dev/null; then
    parent=$v2 limit_file=memory.max
elif [ -n "$v1" ]; then
    parent=$v1 limit_file=memory.limit_in_bytes
else
    skip "no cgroup memory controller is mounted"
fi
group="$parent/ssrt-test-$$"
mkdir "$group" 2>/dev/null || skip "cannot make a cgroup in $parent (not root, or read-only)"
dir=$(mktemp -d)
trap 'rmdir "$group" 2>/dev/null; rm -rf "$dir"' EXIT
echo "$limit" >"$group/$limit_file" 2>/dev/null || skip "cannot set $group/$limit_file"

# Runs ssrt in the cgroup (the shell moves itself in, then becomes ssrt).
in_group() {
    sh -c 'echo $$ >"$1/cgroup.procs" && shift && exec "$@"' sh "$group" "$ssrt" "$@"
}
in_group render --width 4096 --height 4096 -o "$dir/big.exr" 2>"$dir/err"
code=$?
[ "$code" = 3 ] || fail "exit $code, not 3: $(cat "$dir/err")"
[ "$(wc -l <"$dir/err")" = 1 ] || fail "not one line: $(cat "$dir/err")"
grep -q "^ssrt: error: --width, --height: a 4096 x 4096 frame needs about .* more than the 0\.[0-4] GB this process may use (cgroup $group/$limit_file)\$" "$dir/err" ||
    fail "not the cgroup's limit: $(cat "$dir/err")"
[ ! -e "$dir/big.exr" ] || fail "big.exr written"
cat "$dir/err"
in_group render --width 64 --height 36 -o "$dir/small.exr" 2>"$dir/err" ||
    fail "a 64 x 36 frame failed in $limit bytes: $(cat "$dir/err")"
[ -s "$dir/small.exr" ] || fail "small.exr not written"
echo "check_cgroup_limit: a 64 x 36 frame rendered in the $limit-byte cgroup"
