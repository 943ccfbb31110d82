#!/usr/bin/python3
"""The Python side of the module's speed bar (README.md, "Python"): one frame rendered and
written through the module, as `ssrt render --scene SCENE --width W --height H -o OUT` does in
C++. Time both as whole processes, alternated, e.g. with /usr/bin/time -v or hyperfine.

Usage: PYTHONPATH=build/python perf/python_render.py OUT.exr [SCENE] [WIDTH] [HEIGHT]
"""

import sys

import ssrt

out = sys.argv[1]
scene = sys.argv[2] if len(sys.argv) > 2 else "cornell"
width, height = (int(v) for v in sys.argv[3:5]) if len(sys.argv) > 4 else (1920, 1080)
frame = ssrt.Renderer(ssrt.RenderSettings(width=width, height=height)).render(ssrt.Scene(scene))
ssrt.write(frame, out)
