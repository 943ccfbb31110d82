"""What perf/back_faces.py, perf/feedback.py and perf/trace_modes.py share: the scenes they
chart (every built-in scene and a real glTF, assimp's 2CylinderEngine at its own scale), one
`ssrt sweep` per scene into one CSV, and a chart of one panel per scene written whole or not
at all."""
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


def sweep(ssrt, scene, args, out):
    """One `ssrt sweep -q --scene SCENE ARGS -o OUT`, its rows as dicts."""
    subprocess.run([ssrt, "sweep", "-q", "--scene", scene, *args, "-o", out], check=True)
    with open(out, newline="") as f:
        return list(csv.DictReader(f))


def panels(count):
    """A figure of `count` panels, three to a row, and the panels in order."""
    cols = 3
    fig, axes = plt.subplots((count + cols - 1) // cols, cols, figsize=(13, 11), dpi=110)
    return fig, list(axes.flat)


def label_panel(ax, title):
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("frame (ms)", fontsize=8)
    ax.set_ylabel("colour relMSE", fontsize=8)
    ax.grid(True, alpha=0.3)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6)


def save(fig, axes, used, title, png):
    for ax in axes[used:]:
        ax.axis("off")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    tmp = png + ".tmp.png"
    fig.savefig(tmp)  # whole or not at all
    os.replace(tmp, png)
    plt.close(fig)


def run(name, doc, args, chart):
    """The scripts' main: `NAME SSRT OUT.csv OUT.png`, a sweep with ARGS per scene (a list of
    argument tuples: one sweep with each, their rows together)."""
    if len(sys.argv) != 4:
        sys.exit(doc)
    ssrt, out_csv, out_png = sys.argv[1:]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for i, scene in enumerate(SCENES):
            print(f"{name}: {scene} ({i + 1}/{len(SCENES)})", file=sys.stderr)
            for j, a in enumerate(args if isinstance(args, list) else [args]):
                rows += sweep(ssrt, scene, a, os.path.join(d, f"{i}_{j}.csv"))
    with open(out_csv + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    os.replace(out_csv + ".tmp", out_csv)
    chart(rows, out_png)
