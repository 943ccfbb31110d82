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
import os

import scene_sweeps

ARGS = ("--marchers", "hiz", "--ssgi-feedback", "off,on", "--warmup-frames", "29",
        "--reference-bounces", "full")


def chart(rows, png):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = scene_sweeps.panels(len(scenes))
    for ax, scene in zip(axes, scenes):
        pts = {r["ssgi_feedback"]: (float(r["frame_ms"]), float(r["relmse"]))
               for r in rows if r["scene"] == scene}
        if set(pts) != {"0", "1"}:
            continue
        (x0, y0), (x1, y1) = pts["0"], pts["1"]
        ax.scatter([x0], [y0], marker="o", color="tab:blue", label="one bounce")
        ax.scatter([x1], [y1], marker="D", color="tab:red", label="feedback")
        ax.annotate("", (x1, y1), (x0, y0),
                    arrowprops={"arrowstyle": "->", "color": "tab:gray", "alpha": 0.6})
        scene_sweeps.label_panel(ax, f"{os.path.basename(scene)}: {y0:.4f} -> {y1:.4f}")
    scene_sweeps.save(fig, axes, len(scenes),
                      "SSGI feedback on frame 30 of a still camera against all the light "
                      "(640x360, default preset, 64-spp reference of all bounces)", png)


if __name__ == "__main__":
    scene_sweeps.run("feedback.py", __doc__, ARGS, chart)
