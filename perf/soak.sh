#!/usr/bin/env bash
# The soak (issue 33): a long sequence in one process, checked for what a long run can lose.
# build/perf/ssrt_soak (perf/soak.cpp; scripts/build.sh builds it) renders the cornell scene
# along a camera path with two cuts, its mirror sphere moving, 2000 frames at 320x180, with NaN
# in the history handed to frame 700 (--nan-frame), writing every 100th frame as an EXR; then
# the same run as 2 shards. Bars:
#   RSS        the resident memory after every frame from 10 frames past the NaN frame on within
#              1 % of that frame's (the NaN's one-time paths and the first writes take their
#              memory before: 300 frames at 160x90 stepped 35100 -> 35456 KiB by frame 109, the
#              NaN frame 105, then stayed flat; from frame 10 that read 1.01 % on 35 MB)
#   files      the open file descriptors (/proc/self/fd) after every frame from frame 10 on
#              equal to frame 10's (no descriptor leaked by a frame or a write), and each run's
#              folder holds exactly the frames it was to write, no temporary left; the shards'
#              files are the whole run's, byte for byte
#   finite     no NaN or infinity in any layer of any frame
#   time       the time per frame flat: the medians of blocks of 100 frames within 20 % of each
#              other (max / min - 1), in the process's CPU time (every thread), which measures
#              the renderer's work; the wall time is reported beside it, but on a shared
#              machine it measures the neighbours too (2026-12-03, load 10-12 on 2 cores: wall
#              block medians fell from 33 to 19 ms as the load fell, CPU time stayed 11.5-13.2)
#   shards     shard 1/2's rows then shard 2/2's equal the whole run's, hash for hash
# Exit 0 when every bar holds, 1 otherwise; the figures go to stdout.
#
#   perf/soak.sh [--soak BIN] [--out DIR] [--untimed] [FRAMES [WIDTH HEIGHT]]
# defaults: build/perf/ssrt_soak, build/soak/ (CSVs and frames, emptied first), 2000 320 180.
# --untimed reports the time per frame without its bar: ctest's short soak (perf/CMakeLists.txt)
# runs beside other tests, and no test of the suite times itself.
set -euo pipefail
cd "$(dirname "$0")/.."
soak=build/perf/ssrt_soak out=build/soak timed=1
while [ $# -gt 0 ]; do
    case "$1" in
    --soak) soak="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --untimed) timed=0; shift ;;
    *) break ;;
    esac
done
frames="${1:-2000}" width="${2:-320}" height="${3:-180}"
[ -x "$soak" ] || { echo "soak: no $soak (run scripts/build.sh)" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out"/frames-whole "$out"/frames-shard-1 "$out"/frames-shard-2
nan=$((frames * 7 / 20))
every=$(((frames + 19) / 20))  # 20 frames written by the whole run
args=(--frames "$frames" --width "$width" --height "$height" --nan-frame "$nan" --write-every "$every")
t0=$SECONDS
"$soak" "${args[@]}" --csv "$out/whole.csv" --out "$out/frames-whole"
echo "soak: $frames frames in $((SECONDS - t0)) s" >&2
for k in 1 2; do
    "$soak" "${args[@]}" --shard "$k/2" --csv "$out/shard-$k.csv" --out "$out/frames-shard-$k"
done
/usr/bin/python3 - "$out" "$timed" "$every" "$((nan + 10))" <<'PY'
import csv, filecmp, os, statistics, sys
out, timed, every, base = sys.argv[1], sys.argv[2] == "1", int(sys.argv[3]), int(sys.argv[4])
rows = lambda name: list(csv.DictReader(open(f"{out}/{name}.csv")))
whole, shards = rows("whole"), rows("shard-1") + rows("shard-2")
rss = [int(r["rss_kib"]) for r in whole]
base = min(base, len(rss) - 1)
growth = (max(rss[base:]) - rss[base]) / rss[base] * 100
nonfinite = sum(int(r["nonfinite"]) for r in whole + shards)
def spread_of(key):
    values = [float(r[key]) for r in whole]
    blocks = [statistics.median(values[i:i + 100]) for i in range(0, len(values) - 99, 100)]
    return values, blocks, (max(blocks) / min(blocks) - 1) * 100 if blocks else 0.0
ms, blocks, spread = spread_of("ms")
cpu, cpu_blocks, cpu_spread = spread_of("cpu_ms")
same = [r["hash"] for r in whole] == [r["hash"] for r in shards] and \
    [r["frame"] for r in whole] == [r["frame"] for r in shards]
# Descriptors: flat from frame 10 on, in every run.
fds = {name: [int(r["fds"]) for r in rows(name)] for name in ("whole", "shard-1", "shard-2")}
fds_flat = all(max(v[10:] or v) == min(v[10:] or v) for v in fds.values())
# Files: each run's folder holds the frames it wrote (i % every == 0 of its rows), nothing else.
def expected(name):
    return sorted(f"frame_{int(r['frame']):05d}.exr" for r in rows(name) if int(r["frame"]) % every == 0)
listings = {name: sorted(os.listdir(f"{out}/frames-{name}")) for name in fds}
files_ok = all(listings[name] == expected(name) for name in fds)
shard_files = {f: f"{out}/frames-shard-{k}/{f}" for k in (1, 2) for f in listings[f"shard-{k}"]}
files_same = sorted(shard_files) == listings["whole"] and all(
    filecmp.cmp(f"{out}/frames-whole/{f}", shard_files[f], shallow=False) for f in shard_files)
print(f"frames {len(whole)}; RSS at frame {base} {rss[base]} KiB, max after {max(rss[base:])} "
      f"KiB: growth {growth:.2f} % (bar 1 %; frame 10 {rss[10]} KiB)")
print("open descriptors after each frame from frame 10 on: " +
      ", ".join(f"{n} {min(v[10:] or v)} to {max(v[10:] or v)}" for n, v in fds.items()) +
      f" ({'flat' if fds_flat else 'NOT FLAT'}; bar flat)")
print(f"files written: {', '.join(f'{n} {len(l)}' for n, l in listings.items())}, "
      f"{'as expected' if files_ok else 'NOT AS EXPECTED'} (one frame in {every}, nothing else); "
      f"the shards' files the whole run's, byte for byte: {'yes' if files_same else 'NO'}")
print(f"non-finite values {nonfinite} (bar 0)")
time_bar = "(bar 20 %)" if timed else "(no bar: --untimed)"
print(f"CPU time per frame (every thread): median {statistics.median(cpu):.1f} ms; medians of "
      f"{len(cpu_blocks)} blocks of 100 from {min(cpu_blocks or [0]):.1f} to "
      f"{max(cpu_blocks or [0]):.1f} ms: spread {cpu_spread:.1f} % {time_bar}")
print(f"wall time per frame: median {statistics.median(ms):.1f} ms, p5 {sorted(ms)[len(ms) // 20]:.1f}, "
      f"p95 {sorted(ms)[len(ms) * 19 // 20]:.1f}; block medians from {min(blocks or [0]):.1f} to "
      f"{max(blocks or [0]):.1f} ms: spread {spread:.1f} % (no bar: the machine's load)")
print(f"2 shards equal to the whole run: {'yes' if same else 'NO'} ({len(shards)} rows)")
ok = growth < 1 and fds_flat and files_ok and files_same and nonfinite == 0 and same
sys.exit(0 if ok and (cpu_spread < 20 or not timed) else 1)
PY
