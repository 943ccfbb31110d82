#!/usr/bin/env bash
# Issue 47's interrupts (cli/interrupt.h): SIGINT or SIGTERM during a long `render --frames`,
# `reference`, `compare`, `sweep` or `check` ends it within a second (checked loosely here: under
# $limit_ms on a loaded machine; each run prints the figure), exit 130 or 143, one line
# "ssrt: interrupted after N of M ...", every file written whole (a render's frames
# byte-identical to an uninterrupted run's), no temporary left; a second signal ends at once;
# the Slurm sequence script stops the same way, and `ssrt merge` names a missing part's file.
# Usage: check_interrupts.sh SSRT SOURCE_DIR (ctest passes both).
set -uo pipefail
set -m  # background jobs keep SIGINT (without job control, bash starts them with it ignored)
ssrt="$1"
src="$2"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
limit_ms=5000
size=(--width 320 --height 180)

fail() {
    echo "check_interrupts: FAIL: $*" >&2
    exit 1
}
say() { echo "check_interrupts: $*" >&2; }

# start NAME COMMAND...: in the background, its output in $dir/NAME.out and NAME.err.
start() {
    local name="$1"
    shift
    "$@" >"$dir/$name.out" 2>"$dir/$name.err" &
    pid=$!
    job="$name"
}
# wait_for FILE: until it exists (20 s at most; the process must still be running).
wait_for() {
    for _ in $(seq 400); do
        [ -e "$1" ] && return 0
        kill -0 "$pid" 2>/dev/null || fail "$job ended before $1 appeared: $(cat "$dir/$job.err")"
        sleep 0.05
    done
    fail "$job: no $1 after 20 s"
}
# wait_for_line FILE PATTERN: until a line of FILE matches (20 s at most).
wait_for_line() {
    for _ in $(seq 400); do
        grep -q "$2" "$1" 2>/dev/null && return 0
        kill -0 "$pid" 2>/dev/null || fail "$job ended before '$2': $(cat "$dir/$job.err")"
        sleep 0.05
    done
    fail "$job: no '$2' after 20 s"
}
# stop SIGNAL...: sends the signals at once, waits; sets `code` and `ms` (signal to exit).
stop() {
    local t0
    t0=$(date +%s%N)
    for s in "$@"; do kill -s "$s" "$pid"; done
    while kill -0 "$pid" 2>/dev/null && [ $(($(date +%s%N) - t0)) -lt 15000000000 ]; do
        sleep 0.05
    done
    if kill -0 "$pid" 2>/dev/null; then
        kill -s KILL "$pid"
        fail "$job: still running 15 s after the signal"
    fi
    wait "$pid"
    code=$?
    ms=$((($(date +%s%N) - t0) / 1000000))
}
# expect_stop CODE PATTERN: the exit status, the time, and the last line of stderr.
expect_stop() {
    [ "$code" = "$1" ] || fail "$job: exit $code, not $1 ($(tail -n 3 "$dir/$job.err"))"
    [ "$ms" -lt "$limit_ms" ] || fail "$job: took $ms ms to stop"
    local last
    last=$(tail -n 1 "$dir/$job.err")
    [[ "$last" =~ $2 ]] || fail "$job: last line '$last' does not match '$2'"
    say "$job: exit $code $ms ms after the signal: $last"
}
# no_temporaries FOLDER: no writer's temporary anywhere under it.
no_temporaries() {
    local left
    left=$(find "$1" -name '.*.tmp-*' -o -name '*.tmp')
    [ -z "$left" ] || fail "$job left temporaries: $left"
}

# --- render --frames: SIGINT and SIGTERM after the first frame, each frame kept whole --------
render_stops() {  # render_stops SIGNAL CODE
    local out="$dir/$1"
    mkdir -p "$out"
    start "render-$1" "$ssrt" render --scene cornell "${size[@]}" --frames 200 -o "$out/f.png"
    wait_for "$out/f_0000.png"
    stop "$1"
    expect_stop "$2" "^ssrt: interrupted after [0-9]+ of 200 frames \(.*written whole\)$"
    no_temporaries "$out"
    local n
    n=$(find "$out" -name 'f_*.png' | wc -l)
    [ "$n" -ge 1 ] && [ "$n" -lt 200 ] || fail "render-$1: $n frames written"
    grep -q "after $n of 200 frames" "$dir/render-$1.err" || fail "render-$1: the line's count"
    # The same frames uninterrupted: shard 1/K of the 200 holds at least those n.
    mkdir -p "$out/whole"
    "$ssrt" render --scene cornell "${size[@]}" --frames 200 --shard "1/$((200 / n))" -q \
        -o "$out/whole/f.png" || fail "render-$1: the uninterrupted run failed"
    for f in "$out"/f_*.png; do
        cmp -s "$f" "$out/whole/$(basename "$f")" || fail "render-$1: $f differs"
    done
}
render_stops INT 130
render_stops TERM 143

# A second signal ends at once, by that signal (no line), and removes the temporary being
# written: sent while one is (a 640x360 EXR of every layer, ZIP-compressed, takes longer to
# write than to render). Two signals of one kind sent at once may arrive as one, so the second
# is another: SIGTERM. The two are two kill calls: on a loaded machine the test's shell may lose
# the CPU between them for a scheduler's slice, and a first signal that came as a write was
# ending lets the run stop cleanly before the second arrives (exit 130 and the line). That is
# the test's timing, not ssrt's, so that case is tried again, up to 5 times.
render_twice() {  # sets `stopped_cleanly` to 1 when the run ended before the second signal
    rm -rf "$dir/twice"
    mkdir -p "$dir/twice"
    start render-twice "$ssrt" render --scene cornell --width 640 --height 360 --frames 200 \
        --exr-compression zip -o "$dir/twice/f.exr"
    for _ in $(seq 2000); do
        [ -n "$(find "$dir/twice" -name '.*.tmp-*')" ] && break
        sleep 0.01
    done
    [ -n "$(find "$dir/twice" -name '.*.tmp-*')" ] || fail "render-twice: no write seen under way"
    stop INT TERM
    no_temporaries "$dir/twice"
    stopped_cleanly=0
    if grep -q "interrupted after" "$dir/render-twice.err"; then
        [ "$code" = 130 ] || fail "render-twice: a clean stop with exit $code, not 130"
        stopped_cleanly=1
        return
    fi
    [ "$code" = 130 ] || [ "$code" = 143 ] || fail "render-twice: exit $code, not 130 or 143"
}
for try in 1 2 3 4 5; do
    render_twice
    [ "$stopped_cleanly" = 0 ] && break
    say "render-twice: try $try stopped cleanly before the second signal arrived; again"
done
[ "$stopped_cleanly" = 0 ] || fail "render-twice: stopped cleanly in 5 tries: the second signal never ended a run"
say "render-twice: exit $code $ms ms after the signals"

# --- reference: cancelled mid-frame (between tiles), nothing written or cached --------------
start reference "$ssrt" reference --scene cornell "${size[@]}" --reference-spp 65536 \
    --cache-dir "$dir/cache" -o "$dir/ref.exr"
wait_for_line "$dir/reference.err" "^reference of"
sleep 1
stop INT
expect_stop 130 "^ssrt: interrupted after 0 of 1 reference \(.*ref.exr not written\)$"
[ ! -e "$dir/ref.exr" ] || fail "reference: ref.exr written"
[ ! -e "$dir/cache" ] || [ -z "$(ls -A "$dir/cache")" ] ||
    fail "reference: the cache holds $(ls -A "$dir/cache")"

# --- compare: stopped in its reference; it writes its files when done, so none -------------
start compare "$ssrt" compare --scene cornell --width 160 --height 90 --reference-spp 65536 \
    --no-cache -o "$dir/compare.exr"
wait_for_line "$dir/compare.err" "^comparing"
sleep 1
stop INT
expect_stop 130 "^ssrt: interrupted after part of the comparison \(nothing written: .*\)$"
[ ! -e "$dir/compare.exr" ] || fail "compare: compare.exr written"
no_temporaries "$dir"

# --- sweep: stopped mid-setting; its CSV is written whole at the end, so not at all ---------
start sweep "$ssrt" sweep --scene cornell --width 160 --height 90 --marchers linear,dda,hiz \
    --reference-spp 65536 --no-cache -o "$dir/sweep.csv"
wait_for_line "$dir/sweep.err" "^setting 1/3"
sleep 1
stop TERM
expect_stop 143 "^ssrt: interrupted after 0 of 3 settings \(.*sweep.csv not written: .*\)$"
[ ! -e "$dir/sweep.csv" ] || fail "sweep: sweep.csv written"
no_temporaries "$dir"

# --- check: the signal passed on to the case being rendered, no report ----------------------
mkdir -p "$dir/suite"
cat >"$dir/suite/suite.json" <<'EOF'
{"cases": [
  {"name": "a", "render": ["--frames", "400", "--width", "160", "--height", "90"], "frame": 399,
   "reference": "golden/a.png"},
  {"name": "b", "render": ["--frames", "400", "--width", "160", "--height", "90"], "frame": 399,
   "reference": "golden/b.png"}
]}
EOF
start check "$ssrt" check "$dir/suite/suite.json" -j 1 -o "$dir/suite/out"
wait_for "$dir/suite/out/cases/a/rendered_0000.png"
stop INT
expect_stop 130 "^ssrt: interrupted after 0 of 2 cases \(no report written\)$"
[ ! -e "$dir/suite/out/report.html" ] || fail "check: a report was written"
[ ! -e "$dir/suite/out/cases/b" ] || fail "check: case b started"
grep -q "interrupted after" "$dir/suite/out/cases/a/render.log" ||
    fail "check: case a's render did not stop cleanly: $(tail -n 2 "$dir/suite/out/cases/a/render.log")"
job=check no_temporaries "$dir/suite"

# --- Slurm: the sequence script's task (ssrt in its place) stops on the batch shell's TERM ---
grep -q '^#SBATCH --signal=B:TERM@' "$src/scripts/slurm/sequence.sbatch" ||
    fail "sequence.sbatch asks no --signal"
mkdir -p "$dir/slurm"
start slurm env SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=1 \
    SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_JOB_ID=1 SLURM_CPUS_PER_TASK=0 SSRT_BIN="$ssrt" \
    SSRT_OUT_DIR="$dir/slurm" bash "$src/scripts/slurm/sequence.sbatch" --scene cornell "${size[@]}" --frames 400
wait_for "$dir/slurm/frame_0000.png"
stop TERM
expect_stop 143 "^ssrt: interrupted after [0-9]+ of 200 frames \(.*written whole\)$"
no_temporaries "$dir/slurm"

# `ssrt merge` names the part a stopped task did not write.
touch "$dir/s.shard-1-of-3.csv" "$dir/s.shard-3-of-3.csv"
err=$("$ssrt" merge -o "$dir/s.csv" "$dir/s.shard-1-of-3.csv" "$dir/s.shard-3-of-3.csv" 2>&1)
[ "$err" = "ssrt: error: merge: shard 2 of 3 is missing ($dir/s.shard-2-of-3.csv)" ] ||
    fail "merge: '$err'"
say "all passed"
