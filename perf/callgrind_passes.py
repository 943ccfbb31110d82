#!/usr/bin/env python3
"""Instructions per pass of one frame, counted by callgrind: repeatable where wall times are not.

    perf/callgrind_passes.py [--ssrt build/ssrt] [--keep DIR] -- RENDER_ARGS...
    perf/callgrind_passes.py -- --scene cornell --width 640 --height 360 --warmup-frames 4

Runs `ssrt render RENDER_ARGS -q` under `valgrind --tool=callgrind` with SSRT_CALLGRIND_SCOPES
set: each scope the render opens (core/profile.h: the frame, the render call, every pass or
chain of passes the scheduler runs, their set-ups and finishes) then dumps callgrind's counts
at its start and end. A scope's instructions are every thread's between its two marks. Prints,
for the last render call (the timed frame after the warm-ups), each scope directly inside it:
instructions, and instructions per pixel of the image.

Valgrind runs AVX2 code at most (it has no AVX-512), so the counts are the AVX2 kernels', on
any machine; the ISA line says which ran.
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--ssrt", default="build/ssrt", help="the ssrt binary (default build/ssrt)")
    p.add_argument("--keep", help="keep callgrind's dump files in this folder")
    p.add_argument("render_args", nargs=argparse.REMAINDER,
                   help="after --: the arguments of ssrt render")
    a = p.parse_args()
    if a.render_args[:1] == ["--"]:
        a.render_args = a.render_args[1:]
    return a


def dumps(folder):
    """The dumps in the order they were written: (trigger, instructions)."""
    def part(path):
        m = re.search(r"\.(\d+)$", path)
        return int(m.group(1)) if m else 0
    out = []
    for path in sorted(glob.glob(os.path.join(folder, "callgrind.out.*")), key=part):
        trigger, count = "", 0
        with open(path) as f:
            for line in f:
                if line.startswith("desc: Trigger: "):
                    trigger = line[len("desc: Trigger: "):].strip()
                elif line.startswith("summary: "):
                    count = int(line.split()[1])
                    break
        out.append((trigger, count))
    return out


def scopes(marks):
    """Every scope's inclusive instructions, in order: (depth, name, instructions, parent)."""
    request = "Client Request: "
    total, stack, found = 0, [], []
    for trigger, count in marks:
        total += count
        if not trigger.startswith(request):
            continue
        kind, _, name = trigger[len(request):].partition(" ")
        if kind == "begin":
            stack.append((name, total, len(found)))
            found.append(None)  # filled at its end, so that the list keeps the begin order
        elif kind == "end":
            if not stack or stack[-1][0] != name:
                sys.exit(f"callgrind_passes: '{name}' ends, but "
                         f"'{stack[-1][0] if stack else 'nothing'}' is open")
            _, start, slot = stack.pop()
            parent = stack[-1][0] if stack else ""
            found[slot] = (len(stack), name, total - start, parent)
    return [f for f in found if f is not None]


def main():
    a = parse_args()
    size = {"--width": 1280, "--height": 720}
    for i, arg in enumerate(a.render_args[:-1]):
        if arg in size:
            size[arg] = int(a.render_args[i + 1])
    pixels = size["--width"] * size["--height"]
    folder = a.keep or tempfile.mkdtemp(prefix="ssrt-callgrind-")
    os.makedirs(folder, exist_ok=True)
    for old in glob.glob(os.path.join(folder, "callgrind.out.*")):
        os.remove(old)
    image = os.path.join(folder, "frame.png")
    cmd = ["valgrind", "--tool=callgrind", "--dump-instr=no",
           f"--callgrind-out-file={folder}/callgrind.out.%p", os.path.abspath(a.ssrt),
           "render", *a.render_args, "-q", "-o", image]
    env = dict(os.environ, SSRT_CALLGRIND_SCOPES="1")
    run = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        sys.exit(f"callgrind_passes: {' '.join(cmd)} failed:\n{run.stderr[-2000:]}")
    found = scopes(dumps(folder))
    calls = [i for i, f in enumerate(found) if f[1] == "render call"]
    if not calls:
        sys.exit("callgrind_passes: no 'render call' scope was marked (is valgrind's "
                 "callgrind.h installed where ssrt was built?)")
    last = found[calls[-1]]
    inside = [f for f in found[calls[-1] + 1:] if f[0] == last[0] + 1 and f[3] == "render call"]
    print(f"ssrt render {' '.join(a.render_args)}: the last render call, {pixels} pixels, "
          f"callgrind (AVX2 at most)")
    print(f"{'scope':<54}{'instructions':>16}{'per pixel':>12}")
    for _, name, n, _ in inside:
        print(f"  {name:<52}{n:>16,}{n / pixels:>12.1f}")
    print(f"  {'render call':<52}{last[2]:>16,}{last[2] / pixels:>12.1f}")
    if not a.keep:
        for f in glob.glob(os.path.join(folder, "*")):
            os.remove(f)
        os.rmdir(folder)


if __name__ == "__main__":
    main()
