#!/usr/bin/python3
"""The single frame (issue 28, item 1): what gives the best still image for its cost.

A frame without history (the one image of `ssrt render`, a sequence's first frame, a frame
after a camera cut) has nothing to reproject: every pixel is young, so the denoiser's history
fix, blur and post-blur all run at full width. This script renders such a frame under a set
of variants (denoiser settings, more rays with a lighter filter, the quality presets) on
several scenes and records, per variant and scene, the colour relMSE against the 64-spp
one-bounce Embree reference (`ssrt compare --reference-bounces 1`, 640x360) and the time of
the render call at 1280x720 (`ssrt render --stats`, median of RUNS). Output: a CSV and a
chart of error against time, one panel per scene. relMSE is not the whole answer: look at
the 1280x720 images too (smaller blur radii score lower at 640x360 but leave blotches of
10-20 pixels on cornell's walls at 1280x720, issue 28's closing note). Run with Debian's
/usr/bin/python3:

    perf/single_frame.py build/ssrt perf/charts/single_frame.csv perf/charts/single_frame.png
"""
import csv
import re
import statistics
import subprocess
import sys

SCENES = ("cornell", "corridor", "spheres",
          "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb")
VARIANTS = {
    "default (medium: radius 30)": [],
    "blur radius 10": ["--max-blur-radius", "10"],
    "no history fix": ["--history-fix-frames", "0"],
    "blur radius 15": ["--max-blur-radius", "15"],
    "blur radius 45": ["--max-blur-radius", "45"],
    "blur radius 5": ["--max-blur-radius", "5"],
    "blur radius 20": ["--max-blur-radius", "20"],
    "post-blur only": ["--blur-max-frames", "0"],
    "history-fix stride 7": ["--history-fix-stride", "7"],
    "stride 7, post-blur only": ["--history-fix-stride", "7", "--blur-max-frames", "0"],
    "2 rays each": ["--ssr-spp", "2", "--ssgi-spp", "2"],
    "2 rays each, blur 5": ["--ssr-spp", "2", "--ssgi-spp", "2", "--max-blur-radius", "5"],
    "full SSR, checkerboard SSGI": ["--ssr-layout", "full", "--ssgi-layout", "checkerboard"],
    "no denoiser": ["--no-denoise"],
    "low": ["--quality", "low"],
    "high": ["--quality", "high"],
}
RUNS = 3


def short(scene):
    return scene.rsplit("/", 1)[-1].removesuffix(".glb")


def relmse(ssrt, scene, args):
    out = subprocess.run([ssrt, "compare", "--scene", scene, "--reference-bounces", "1",
                          "--threads", "2", "-q"] + args,
                         capture_output=True, text=True, check=True).stdout
    m = re.search(r"^\s*color \(exposed\)\s+(\S+)", out, re.M)
    if not m:
        raise RuntimeError(f"{scene} {args}: no colour relMSE in compare's output")
    return float(m.group(1))


def render_ms(ssrt, scene, args):
    """The render call's and the denoiser's passes' ms, medians of RUNS."""
    times, denoise = [], []
    for _ in range(RUNS):
        out = subprocess.run([ssrt, "render", "--scene", scene, "--width", "1280", "--height",
                              "720", "--threads", "2", "--stats", "-q", "-o", "/tmp/ssrt_sf.png"]
                             + args, capture_output=True, text=True, check=True).stdout
        m = re.search(r"^\s*render call\s+(\S+)", out, re.M)
        if not m:
            raise RuntimeError(f"{scene} {args}: no render call time in --stats")
        times.append(float(m.group(1)))
        denoise.append(sum(float(v) for v in re.findall(r"^\s*denoise [a-z -]+?\s+(\S+)$", out, re.M)))
    return statistics.median(times), statistics.median(denoise)


def main(ssrt, out_csv, out_png):
    rows = []
    for scene in SCENES:
        for name, args in VARIANTS.items():
            rows.append((short(scene), name, relmse(ssrt, scene, args),
                         *render_ms(ssrt, scene, args)))
            print(*rows[-1], sep=",", flush=True)
    with open(out_csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scene", "variant", "relmse", "render_ms_1280x720", "denoise_ms_1280x720"])
        w.writerows(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(SCENES), figsize=(5 * len(SCENES), 4.5))
    for ax, scene in zip(axes, SCENES):
        pts = [r for r in rows if r[0] == short(scene)]
        for _, name, err, ms, _ in pts:
            ax.scatter(ms, err, s=18, color="black" if name.startswith("default") else None)
            ax.annotate(name, (ms, err), fontsize=6, xytext=(3, 2), textcoords="offset points")
        ax.set_title(short(scene))
        ax.set_xlabel("render call ms, 1280x720")
        ax.set_ylabel("colour relMSE, 640x360, frame 1")
        ax.set_yscale("log")
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)


if __name__ == "__main__":
    main(*sys.argv[1:4])
