#!/usr/bin/env bash
# The libFuzzer targets of tests/fuzz (README.md there), built in build-asan/ by
# scripts/test-sanitized.sh (clang 14, ASan + UBSan, -DSSRT_BUILD_FUZZ=ON).
#
#   scripts/fuzz.sh replay               every target over its committed seeds, once each
#                                        (what CI runs: a crash, leak or UB report fails it)
#   scripts/fuzz.sh run TARGET [ARGS]    a campaign: TARGET (shot, sky_image, texture, merge,
#                                        diff, cli, gltf, suite) from its seeds, its corpus kept in
#                                        build-asan/fuzz/corpus/TARGET; ARGS go to libFuzzer
#                                        (e.g. -runs=1000000); crashes land in
#                                        build-asan/fuzz/artifacts/TARGET/
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/sanitizer-options.sh
bin=build-asan/fuzz
targets=(cli diff gltf merge shot sky_image suite texture)

require() {
    [ -x "$bin/${1}_fuzz" ] || {
        echo "fuzz: no $bin/${1}_fuzz (scripts/test-sanitized.sh builds the targets)" >&2
        exit 2
    }
}

case "${1:-}" in
replay)
    for t in "${targets[@]}"; do
        require "$t"
        t0=$SECONDS
        "$bin/${t}_fuzz" -runs=0 "tests/fuzz/seeds/$t" 2>"$bin/replay-$t.log" || {
            tail -40 "$bin/replay-$t.log" >&2
            echo "fuzz: replaying tests/fuzz/seeds/$t failed (log: $bin/replay-$t.log)" >&2
            exit 1
        }
        echo "fuzz: replayed $(ls "tests/fuzz/seeds/$t" | wc -l) seeds of $t in $((SECONDS - t0)) s" >&2
    done
    ;;
run)
    t="${2:?usage: scripts/fuzz.sh run TARGET [libFuzzer args]}"
    require "$t"
    shift 2
    mkdir -p "$bin/corpus/$t" "$bin/artifacts/$t"
    cp -n tests/fuzz/seeds/"$t"/* "$bin/corpus/$t/"
    # Without allocation stacks in a report (recording one at every malloc cost a third of a
    # merge_fuzz run): rerun a found input with `build-asan/fuzz/TARGET_fuzz FILE` for them.
    export ASAN_OPTIONS="$ASAN_OPTIONS:malloc_context_size=0"
    exec "$bin/${t}_fuzz" "$bin/corpus/$t" -artifact_prefix="$bin/artifacts/$t/" -timeout=10 "$@"
    ;;
*)
    echo "usage: scripts/fuzz.sh replay | run TARGET [libFuzzer args]" >&2
    exit 2
    ;;
esac
