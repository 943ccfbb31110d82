#!/usr/bin/env bash
# The soak (issue 33): a long sequence in one process, checked for what a long run can lose.
# build/perf/ssrt_soak (perf/soak.cpp; scripts/build.sh builds it) renders the cornell scene
# along a camera path with two cuts, its mirror sphere moving, 2000 frames at 320x180, with NaN
# in the history handed to frame 700 (--nan-frame); then the same run as 2 shards. Bars:
#   RSS        the resident memory after every frame from frame 10 on within 1 % of frame 10's
#   finite     no NaN or infinity in any layer of any frame
#   time       the time per frame flat: the medians of blocks of 100 frames within 20 % of each
#              other (max / min - 1), in the process's CPU time (every thread), which measures
#              the renderer's work; the wall time is reported beside it, but on a shared
#              machine it measures the neighbours too (2026-12-03, load 10-12 on 2 cores: wall
#              block medians fell from 33 to 19 ms as the load fell, CPU time stayed 11.5-13.2)
#   shards     shard 1/2's rows then shard 2/2's equal the whole run's, hash for hash
# Exit 0 when every bar holds, 1 otherwise; the figures go to stdout.
#
#   perf/soak.sh [FRAMES [WIDTH HEIGHT]]     defaults 2000 320 180; CSVs in build/soak/
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-2000}" width="${2:-320}" height="${3:-180}"
soak=build/perf/ssrt_soak
[ -x "$soak" ] || { echo "soak: no $soak (run scripts/build.sh)" >&2; exit 2; }
out=build/soak
mkdir -p "$out"
nan=$((frames * 7 / 20))
args=(--frames "$frames" --width "$width" --height "$height" --nan-frame "$nan")
t0=$SECONDS
"$soak" "${args[@]}" --csv "$out/whole.csv"
echo "soak: $frames frames in $((SECONDS - t0)) s" >&2
for k in 1 2; do "$soak" "${args[@]}" --shard "$k/2" --csv "$out/shard-$k.csv"; done
/usr/bin/python3 - "$out" <<'PY'
import csv, statistics, sys
out = sys.argv[1]
rows = lambda name: list(csv.DictReader(open(f"{out}/{name}.csv")))
whole, shards = rows("whole"), rows("shard-1") + rows("shard-2")
rss = [int(r["rss_kib"]) for r in whole]
growth = (max(rss[10:]) - rss[10]) / rss[10] * 100
nonfinite = sum(int(r["nonfinite"]) for r in whole + shards)
def spread_of(key):
    values = [float(r[key]) for r in whole]
    blocks = [statistics.median(values[i:i + 100]) for i in range(0, len(values) - 99, 100)]
    return values, blocks, (max(blocks) / min(blocks) - 1) * 100
ms, blocks, spread = spread_of("ms")
cpu, cpu_blocks, cpu_spread = spread_of("cpu_ms")
same = [r["hash"] for r in whole] == [r["hash"] for r in shards] and \
    [r["frame"] for r in whole] == [r["frame"] for r in shards]
print(f"frames {len(whole)}; RSS at frame 10 {rss[10]} KiB, max after {max(rss[10:])} KiB: "
      f"growth {growth:.2f} % (bar 1 %)")
print(f"non-finite values {nonfinite} (bar 0)")
print(f"CPU time per frame (every thread): median {statistics.median(cpu):.1f} ms; medians of "
      f"{len(cpu_blocks)} blocks of 100 from {min(cpu_blocks):.1f} to {max(cpu_blocks):.1f} ms: "
      f"spread {cpu_spread:.1f} % (bar 20 %)")
print(f"wall time per frame: median {statistics.median(ms):.1f} ms, p5 {sorted(ms)[len(ms) // 20]:.1f}, "
      f"p95 {sorted(ms)[len(ms) * 19 // 20]:.1f}; block medians from {min(blocks):.1f} to "
      f"{max(blocks):.1f} ms: spread {spread:.1f} % (no bar: the machine's load)")
print(f"2 shards equal to the whole run: {'yes' if same else 'NO'} ({len(shards)} rows)")
sys.exit(0 if growth < 1 and nonfinite == 0 and cpu_spread < 20 and same else 1)
PY
