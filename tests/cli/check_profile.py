#!/usr/bin/env python3
"""`ssrt render --profile FILE` against the same run's `--stats --json`: the file is a Chrome
trace-event document; every pass `--stats` times is a slice on a named thread (the half frame's
denoiser passes under their own names, which --stats folds into the frame's); each thread's
slices nest (none starts inside another and ends after it); every frame has its "frame I" slice
with its index, a render call and an image write, and the march's counters; and a path that is
not a .json file, or is in no folder, is refused before anything renders; and the profiled
image is the plain one's, byte for byte.

    check_profile.py SSRT          (run by ctest: render_profile_nests)
"""
import json
import os
import subprocess
import sys
import tempfile

SSRT = os.path.abspath(sys.argv[1])
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def render(tmp, *extra, frames=1):
    profile = os.path.join(tmp, "p.json")
    args = [SSRT, "render", "-s", "cornell", "--width", "192", "--height", "108",
            "--frames", str(frames), "-o", os.path.join(tmp, "x.png"), "--profile", profile,
            "--stats", "--json", *extra]
    r = subprocess.run(args, capture_output=True, text=True)
    check(r.returncode == 0, f"{' '.join(args)}: exit {r.returncode}: {r.stderr}")
    return json.loads(r.stdout), json.load(open(profile))


def nests(slices):
    """The first pair of one thread's slices that overlap without one holding the other."""
    # As a viewer stacks them: by start, the longer first.
    stack = []
    for s in sorted(slices, key=lambda s: (s["ts"], -s["dur"])):
        end = s["ts"] + s["dur"]
        while stack and stack[-1][1] <= s["ts"]:
            stack.pop()
        # (times are microseconds as doubles: a nanosecond of rounding is not an overlap)
        if stack and end > stack[-1][1] + 1e-3:
            return (stack[-1][0], s["name"])
        stack.append((s["name"], end))
    return None


def check_run(stats, trace, frames, what):
    events = trace["traceEvents"]
    slices = [e for e in events if e["ph"] == "X"]
    names = {e["name"].replace(" (half)", "") for e in slices}
    threads = {e["tid"]: e["args"]["name"] for e in events
               if e["ph"] == "M" and e["name"] == "thread_name"}
    check(threads.get(1) == "main", f"{what}: thread 1 is {threads.get(1)}, not main")
    for e in slices:
        check(e["tid"] in threads, f"{what}: slice {e['name']} on unnamed thread {e['tid']}")
        check(e["dur"] >= 0, f"{what}: slice {e['name']} lasts {e['dur']}")
    for frame in stats["frames"]:
        for name in frame["pass_times"]:
            check(name in names, f"{what}: --stats pass '{name}' has no slice")
    for tid in threads:
        bad = nests([e for e in slices if e["tid"] == tid])
        check(bad is None, f"{what}: on thread {tid}, '{bad and bad[1]}' overlaps '{bad and bad[0]}'")
    framed = sorted(e["args"]["frame"] for e in slices if e["name"].startswith("frame "))
    check(framed == list(range(frames)), f"{what}: frame slices {framed}")
    for name in ("render call", "image write"):
        check(sum(e["name"] == name for e in slices) == frames, f"{what}: {name} slices")
    counters = [e for e in events if e["ph"] == "C" and e["name"] == "ssr march"]
    check(len(counters) == frames and all(c["args"]["steps"] > 0 for c in counters),
          f"{what}: ssr march counters {counters}")


with tempfile.TemporaryDirectory() as tmp:
    stats, trace = render(tmp)
    check_run(stats, trace, 1, "one image")
    # A sequence: history, the temporal pass, SSGI at full resolution with its checkerboard.
    stats, trace = render(tmp, "--quality", "high", frames=3)
    check_run(stats, trace, 3, "three frames, --quality high")
    # Warm-up frames: their slices too, their indices counting back from 2^32 - 1.
    stats, trace = render(tmp, "--warmup-frames", "2", frames=1)
    framed = [e["args"]["frame"] for e in trace["traceEvents"]
              if e["ph"] == "X" and e["name"].startswith("frame ")]
    check(sorted(framed) == [0, 2**32 - 2, 2**32 - 1], f"warm-up frames: frame slices {framed}")
    # Only clocks are read: the image is the same bytes without the profile.
    with open(os.path.join(tmp, "x_0002.png"), "rb") as f:
        profiled = f.read()
    plain = os.path.join(tmp, "plain.png")
    subprocess.run([SSRT, "render", "-s", "cornell", "--width", "192", "--height", "108",
                    "--frames", "3", "--quality", "high", "-o", plain, "-q"], check=True)
    with open(os.path.join(tmp, "plain_0002.png"), "rb") as f:
        check(f.read() == profiled, "the profiled render's last frame differs from the plain one's")
    for path, expected in ((os.path.join(tmp, "p.txt"), "must end in .json"),
                           (os.path.join(tmp, "none", "p.json"), "does not exist")):
        r = subprocess.run([SSRT, "render", "--width", "32", "--height", "18", "-o",
                            os.path.join(tmp, "y.png"), "--profile", path],
                           capture_output=True, text=True)
        check(r.returncode != 0 and expected in r.stderr,
              f"--profile {path}: exit {r.returncode}, {r.stderr!r}")
        check(not os.path.exists(os.path.join(tmp, "y.png")), f"--profile {path}: an image was written")

if failures:
    print(f"{len(failures)} failed")
    sys.exit(1)
print("profile: every --stats pass a slice, slices nest on every thread")
