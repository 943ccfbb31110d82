#!/usr/bin/env bash
# Two `ssrt reference` processes filling one reference cache entry at once (a Slurm array's
# tasks on a shared cache folder): both succeed with the same output, the cache holds one
# entry and no temporary, and a third run takes that entry without a warning. Three rounds.
# Usage: check_reference_cache_race.sh SSRT (ctest passes it).
set -uo pipefail
ssrt="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "check_reference_cache_race: $*" >&2; exit 1; }
reference() {  # reference OUTPUT: a small reference, cached in $dir/cache
    "$ssrt" reference --scene cornell --width 48 --height 27 --reference-spp 2 \
        --shadow-map-size 128 -j 1 --cache-dir "$dir/cache" -o "$1"
}
for round in 1 2 3; do
    rm -rf "$dir/cache"
    reference "$dir/a.exr" 2>"$dir/a.err" &
    a=$!
    reference "$dir/b.exr" 2>"$dir/b.err" &
    b=$!
    wait "$a" || fail "round $round: the first writer failed: $(cat "$dir/a.err")"
    wait "$b" || fail "round $round: the second writer failed: $(cat "$dir/b.err")"
    cmp -s "$dir/a.exr" "$dir/b.exr" || fail "round $round: the two outputs differ"
    entries=$(ls -A "$dir/cache")
    [ "$(echo "$entries" | wc -l)" = 1 ] && [[ "$entries" == ref-*.exr ]] ||
        fail "round $round: the cache holds not one entry: $entries"
    reference "$dir/c.exr" 2>"$dir/c.err" || fail "round $round: $(cat "$dir/c.err")"
    grep -q "^reference: from the cache" "$dir/c.err" ||
        fail "round $round: the entry was not taken: $(cat "$dir/c.err")"
    ! grep -q warning "$dir/c.err" || fail "round $round: $(cat "$dir/c.err")"
    cmp -s "$dir/a.exr" "$dir/c.exr" || fail "round $round: the cached reference differs"
done
echo "check_reference_cache_race: 3 rounds of two writers, one whole entry each"
