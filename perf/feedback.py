#!/usr/bin/python3
"""Multi-bounce SSGI feedback against all the light (issue 29, item 5), charted.

For every built-in scene and a real glTF (assimp's 2CylinderEngine at its own scale), runs
`ssrt sweep` with the default preset's settings (Hi-Z, the default layouts), feedback off and
on (`--ssgi-feedback off,on`), on frame 30 of a still camera (`--warmup-frames 29`: feedback
adds a bounce per frame, and a single frame has none to add) at 640x360, against the 64-spp
reference of all the light (`--reference-bounces full`, compare's default), and writes one
CSV (the sweep's columns) and a chart of colour relMSE against the frame's time, one panel
per scene, an arrow from each scene's point without feedback to its point with it. The times
are the sweep's medians over the frames before the last: on a shared machine they are noisy,
so quote a speed ratio from alternated whole runs. Run with Debian's /usr/bin/python3:

    perf/feedback.py build/ssrt perf/charts/feedback.csv perf/charts/feedback.png
"""
import csv
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

SCENES = ("cornell", "spheres", "thin", "corridor", "offscreen", "occluded", "bunny", "fence",
          "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb")


def sweep(ssrt, scene, out):
    subprocess.run([ssrt, "sweep", "-q", "--scene", scene, "--marchers", "hiz",
                    "--ssgi-feedback", "off,on", "--warmup-frames", "29",
                    "--reference-bounces", "full", "-o", out], check=True)
    with open(out, newline="") as f:
        return list(csv.DictReader(f))


def chart(rows, png):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    cols = 3
    fig, axes = plt.subplots((len(scenes) + cols - 1) // cols, cols, figsize=(13, 11), dpi=110)
    for ax, scene in zip(axes.flat, scenes):
        pts = {r["ssgi_feedback"]: (float(r["frame_ms"]), float(r["relmse"]))
               for r in rows if r["scene"] == scene}
        if set(pts) != {"0", "1"}:
            continue
        (x0, y0), (x1, y1) = pts["0"], pts["1"]
        ax.scatter([x0], [y0], marker="o", color="tab:blue", label="one bounce")
        ax.scatter([x1], [y1], marker="D", color="tab:red", label="feedback")
        ax.annotate("", (x1, y1), (x0, y0),
                    arrowprops={"arrowstyle": "->", "color": "tab:gray", "alpha": 0.6})
        ax.set_title(f"{os.path.basename(scene)}: {y0:.4f} -> {y1:.4f}", fontsize=9)
        ax.set_xlabel("frame (ms)", fontsize=8)
        ax.set_ylabel("colour relMSE", fontsize=8)
        ax.grid(True, alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    fig.suptitle("SSGI feedback on frame 30 of a still camera against all the light (640x360, "
                 "default preset, 64-spp reference of all bounces)", fontsize=10)
    fig.tight_layout()
    tmp = png + ".tmp.png"
    fig.savefig(tmp)  # whole or not at all
    os.replace(tmp, png)
    plt.close(fig)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    ssrt, out_csv, out_png = sys.argv[1:]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for i, scene in enumerate(SCENES):
            print(f"feedback.py: {scene} ({i + 1}/{len(SCENES)})", file=sys.stderr)
            rows += sweep(ssrt, scene, os.path.join(d, f"{i}.csv"))
    with open(out_csv + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    os.replace(out_csv + ".tmp", out_csv)
    chart(rows, out_png)


if __name__ == "__main__":
    main()
