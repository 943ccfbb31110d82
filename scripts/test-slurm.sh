#!/usr/bin/env bash
# The Slurm test, against a real Slurm: starts the single-node cluster of
# scripts/slurm/local-cluster.sh (installing slurm-wlm and munge if missing), runs a small
# sweep, a reference and a short sequence unsharded, then the same as 2-task job arrays, all
# four at once: the sweep through scripts/slurm/sweep.sbatch (which passes --shard K/N) and as
# a bare `ssrt sweep` in an array (which reads the array's variables itself), the reference and
# the sequence through their batch files. It merges each array's parts with `ssrt merge` and
# checks the merged CSVs (the sweep's and the per-frame one) equal the unsharded ones on every
# column but the timings, and the merged reference EXR and the frames byte for byte.
#
#   scripts/test-slurm.sh
#
# It stops the cluster if it started it. Where Slurm cannot start here (no packages, a daemon
# that dies) it prints "test-slurm: SKIPPED: <reason>" and exits 0; SSRT_SLURM_REQUIRED=1 makes
# that a failure. SSRT_BIN runs another ssrt than build/ssrt (built when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
t_start=$SECONDS
limit_s="${SSRT_SLURM_TEST_WAIT_S:-300}"
passed=0
failed=0
say() { echo "test-slurm: $*" >&2; }
pass() {
    say "ok: $*"
    passed=$((passed + 1))
}
fail() {
    say "FAIL: $*"
    failed=$((failed + 1))
}
started=0
cleanup() { [ "$started" = 0 ] || bash "$repo/$cluster" stop || true; }
# The cluster is stopped first, so that the count is the script's last line (CI reads it).
finish() {
    cleanup
    started=0
    say "took $((SECONDS - t_start)) s"
    say "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

# The cluster: started here (and stopped at the end) unless it already runs.
cluster=scripts/slurm/local-cluster.sh
if ! bash "$cluster" status >/dev/null 2>&1; then
    rc=0
    start_log="$(mktemp)"
    bash "$cluster" start 2>"$start_log" || rc=$?
    cat "$start_log" >&2
    reason="$(sed -n 's/^local-cluster: CANNOT START: //p' "$start_log" | tail -n 1)"
    rm -f "$start_log"
    if [ "$rc" -eq 3 ]; then
        if [ "${SSRT_SLURM_REQUIRED:-0}" = 1 ]; then
            fail "Slurm could not start ($reason) and SSRT_SLURM_REQUIRED=1"
            finish
        fi
        say "SKIPPED: Slurm could not start here ($reason)"
        exit 0
    fi
    [ "$rc" -eq 0 ] || {
        fail "scripts/slurm/local-cluster.sh start failed (exit $rc)"
        finish
    }
    started=1
fi
trap cleanup EXIT
eval "$(bash "$cluster" env)"
say "cluster up after $((SECONDS - t_start)) s ($SLURM_CONF)"

bin="${SSRT_BIN:-$repo/build/ssrt}"
if [ ! -x "$bin" ]; then
    say "building ssrt (scripts/build.sh --render)"
    bash scripts/build.sh --render
fi

# The sharding interface this test is about: --shard and `ssrt merge`.
if ! "$bin" --help 2>/dev/null | grep -q '^  merge ' || ! "$bin" sweep --help | grep -q -- --shard; then
    fail "$bin has no 'merge' command or no 'sweep --shard' (an ssrt from before them)"
    finish
fi

work="$repo/build/test-slurm"
rm -rf "$work"
mkdir -p "$work/logs" "$work/full-frames" "$work/bare"
scene=(--scene cornell --width 160 --height 90 --quiet)
args=("${scene[@]}" --marchers off,hiz --max-steps 16,32 --reference-spp 4 --frames 2)
ref_args=("${scene[@]}" --reference-spp 4)
seq_args=("${scene[@]}" --frames 4)

# Unsharded, with the one thread each array task gets (the CSV's `threads` column is the flag).
t0=$SECONDS
unsharded() { # what, ssrt arguments...
    local what="$1"
    shift
    timeout "$limit_s" "$bin" "$@" --threads 1 >>"$work/full.log" 2>&1 && return 0
    cat "$work/full.log" >&2
    fail "the unsharded $what failed"
    finish
}
unsharded sweep sweep "${args[@]}" --cache-dir "$work/cache" -o "$work/full.csv" \
    --per-frame "$work/full-frames.csv"
unsharded reference reference "${ref_args[@]}" --no-cache -o "$work/full-ref.exr"
unsharded sequence render "${seq_args[@]}" -o "$work/full-frames/frame.png"
say "unsharded sweep, reference and sequence: $((SECONDS - t0)) s"

# Four arrays at once, each of 2 tasks with one CPU (the node runs 2 at a time): the sweep
# through its batch file, and ssrt on its own in an array (no --shard: it reads
# SLURM_ARRAY_TASK_ID/_COUNT); the reference and the sequence through theirs. The sweeps share
# a fresh cache, so their tasks render references too; the reference's tasks have an empty
# one, so they render their bands.
submit() { # name, sbatch arguments...: the array job's id in ids[name]
    local name="$1" out
    shift
    if out="$(sbatch --parsable --array=0-1 --cpus-per-task=1 --time=10 \
        --job-name="ssrt-test-$name" --output="$work/logs/%x-%A_%a.out" "$@" 2>&1)"; then
        ids[$name]="${out%%;*}"
    else
        echo "$out" >&2
        fail "sbatch refused the $name array"
    fi
}
declare -A ids=()
t0=$SECONDS
export SSRT_BIN="$bin" SSRT_THREADS=1
SSRT_OUT_DIR="$work/batch" SSRT_CACHE_DIR="$work/array-cache" SSRT_PER_FRAME=1 \
    submit batch scripts/slurm/sweep.sbatch "${args[@]}"
submit bare --wrap "$(printf '%q ' "$bin" sweep "${args[@]}" --threads 1 \
    --cache-dir "$work/array-cache" -o "$work/bare/sweep.csv" \
    --per-frame "$work/bare/sweep-frames.csv")"
SSRT_OUT_DIR="$work/ref" SSRT_CACHE_DIR="$work/ref-cache" \
    submit reference scripts/slurm/reference.sbatch "${ref_args[@]}"
SSRT_OUT_DIR="$work/seq" submit sequence scripts/slurm/sequence.sbatch "${seq_args[@]}"

# Wait (polling squeue each second: sbatch --wait's own polling backs off to tens of
# seconds), bounded; then every task's state and exit code from scontrol (the controller
# keeps finished jobs MinJobAge = 300 s; there is no accounting database to ask).
list="$(IFS=,; echo "${ids[*]}")"
while [ -n "$list" ] && [ -n "$(squeue -h -j "$list" \
    -t PENDING,CONFIGURING,RUNNING,COMPLETING,SUSPENDED -o %i 2>/dev/null)" ]; do
    if [ $((SECONDS - t0)) -ge "$limit_s" ]; then
        say "the arrays did not end within ${limit_s} s; cancelling them"
        scancel "${ids[@]}" 2>/dev/null || true
        break
    fi
    sleep 1
done
say "the arrays ended: $((SECONDS - t0)) s"
for name in batch bare reference sequence; do
    [ -n "${ids[$name]:-}" ] || continue
    states="$(scontrol -o show job "${ids[$name]}" 2>&1 |
        grep -o 'JobState=[A-Z_]* .*ExitCode=[0-9:]*' | sed 's/^JobState=\([A-Z_]*\) .*ExitCode=/\1 /')"
    if [ "$(grep -c '^COMPLETED 0:0$' <<<"$states")" -eq 2 ]; then
        pass "the $name array ran 2 tasks (job ${ids[$name]})"
    else
        cat "$work"/logs/ssrt-test-"$name"-* >&2 2>/dev/null || true
        fail "the $name array (job ${ids[$name]}): tasks ended" $states "(logs above)"
    fi
done

# Merge each array's parts and compare with the unsharded CSVs, timings aside.
compare() { # label, unsharded, merged
    /usr/bin/python3 - "$@" <<'PY'
import csv, sys
label, full_path, merged_path = sys.argv[1:4]
def timing(c):
    return c == "frame_ms" or c.startswith("ms_") or c in (
        "march_mrays_s", "embree_mrays_s", "march_vs_embree")
with open(full_path, newline="") as f:
    full = list(csv.reader(f))
with open(merged_path, newline="") as f:
    merged = list(csv.reader(f))
if full[0] != merged[0]:
    sys.exit(f"{label}: the headers differ:\n  unsharded {full[0]}\n  merged    {merged[0]}")
if len(full) != len(merged):
    sys.exit(f"{label}: {len(full) - 1} unsharded rows, {len(merged) - 1} merged")
header = full[0]
checked = [i for i, c in enumerate(header) if not timing(c)]
for r, (a, b) in enumerate(zip(full[1:], merged[1:]), start=1):
    if len(a) != len(header) or len(b) != len(header):
        sys.exit(f"{label}: row {r} has {len(a)} cells unsharded, {len(b)} merged")
    for i in checked:
        if a[i] != b[i]:
            sys.exit(f"{label}: row {r}, column {header[i]}: unsharded {a[i]!r}, merged {b[i]!r}")
print(f"{label}: {len(full) - 1} rows x {len(checked)} non-timing columns equal "
      f"({len(header) - len(checked)} timing columns not compared)")
PY
}
check_merge() { # label, unsharded, merged, parts...
    local label="$1" full="$2" merged="$3"
    shift 3
    if [ $# -ne 2 ] || [ ! -s "$1" ] || [ ! -s "$2" ]; then
        fail "$label: expected 2 parts, found: $* ($(ls "$(dirname "$merged")" | tr '\n' ' '))"
    elif ! "$bin" merge -o "$merged" "$@" >"$merged.log" 2>&1; then
        cat "$merged.log" >&2
        fail "$label: ssrt merge failed"
    elif out="$(compare "$label" "$full" "$merged" 2>&1)"; then
        pass "$out"
    else
        fail "$out"
    fi
}
for name in batch bare; do
    d="$work/$name"
    check_merge "$name sweep" "$work/full.csv" "$d/merged.csv" "$d"/sweep.shard-*-of-2.csv
    check_merge "$name per-frame" "$work/full-frames.csv" "$d/merged-frames.csv" \
        "$d"/sweep-frames.shard-*-of-2.csv
done

# The reference's bands, merged, and the sequence's frames: the unsharded files, byte for byte.
parts=("$work"/ref/ref.shard-*-of-2.exr)
if [ ${#parts[@]} -ne 2 ] || [ ! -s "${parts[0]}" ]; then
    fail "reference: expected 2 bands, found: ${parts[*]}"
elif ! "$bin" merge -o "$work/ref/merged.exr" "${parts[@]}" >"$work/ref/merged.log" 2>&1; then
    cat "$work/ref/merged.log" >&2
    fail "reference: ssrt merge failed"
elif cmp "$work/full-ref.exr" "$work/ref/merged.exr" >&2; then
    pass "reference: 2 bands merged into the unsharded EXR's bytes"
else
    fail "reference: the merged EXR differs from the unsharded one"
fi
frames_ok=1
for f in "$work"/full-frames/frame_000{0..3}.png; do
    cmp "$f" "$work/seq/${f##*/}" >&2 || frames_ok=0
done
if [ "$frames_ok" = 1 ]; then
    pass "sequence: 4 frames from 2 tasks, the unsharded PNGs' bytes"
else
    fail "sequence: frames missing or different (above)"
fi
finish
