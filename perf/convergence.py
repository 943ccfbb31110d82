#!/ usr / bin / python3
"""The denoiser's convergence on a still camera (issue 17): colour relMSE against the Embree
reference for frames 1..N of a sequence, per scene, beside the undenoised image at 1, 4, 16
and 64 rays per pixel.

Input: a folder with, per scene, SCENE_seq.csv (ssrt compare --frames N --per-frame) and
SCENE_rawK.log (ssrt compare --quality ultra --no-denoise --ssr-spp K --ssgi-spp K). Output: a
CSV of every curve and a PNG. Run with Debian's /usr/bin/python3 (matplotlib):

    perf/convergence.py DIR perf/charts/convergence.csv perf/charts/convergence.png
"""
import csv
import re
import sys

RAYS = (1, 4, 16, 64)


def read_curve(path):
    with open(path) as f:
        return [float(r["relmse"]) for r in csv.DictReader(f)]


def read_raw(path):
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*color \(exposed\)\s+(\S+)", line)
            if m:
                return float(m.group(1))
    raise ValueError(path + ": no colour relMSE line")


def main(folder, out_csv, out_png, scenes=("cornell", "spheres", "corridor")):
    curves = {s: read_curve(f"{folder}/{s}_seq.csv") for s in scenes}
    raw = {s: {k: read_raw(f"{folder}/{s}_raw{k}.log") for k in RAYS} for s in scenes}
    with open(out_csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scene", "series", "frame", "relmse"])
        for s in scenes:
            for i, v in enumerate(curves[s]):
                w.writerow([s, "denoised", i + 1, f"{v:.6g}"])
            for k in RAYS:
                w.writerow([s, f"undenoised {k} rays", "", f"{raw[s][k]:.6g}"])
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(scenes), figsize=(5 * len(scenes), 4), sharey=False)
    for ax, s in zip(axes, scenes):
        frames = range(1, len(curves[s]) + 1)
        ax.plot(frames, curves[s], label="denoised (default preset)", color="black")
        for k, style in zip(RAYS, (":", "-.", "--", "-")):
            ax.axhline(raw[s][k], linestyle=style, color="tab:red", alpha=0.7,
                       label=f"undenoised, {k} ray{'s' if k > 1 else ''}")
        ax.set_yscale("log")
        ax.set_title(f"{s}, 640x360, still camera")
        ax.set_xlabel("frame")
        ax.set_ylabel("colour relMSE against the 64-spp reference")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
