#!/usr/bin/python3
"""The back faces' depth intervals (issue 29, item 1) against the thickness guess, charted.

For every built-in scene and a real glTF (assimp's 2CylinderEngine at its own scale), runs
`ssrt sweep` with the Hi-Z and DDA marchers, each with the back-face layer off and on
(`--back-faces off,on`), on the default preset's layouts at 640x360 against the 64-spp
one-bounce Embree reference, and writes one CSV (the sweep's columns) and a chart of colour
relMSE against the frame's time, one panel per scene, an arrow from each marcher's point
without the layer to its point with it. The times come from the sweep's one frame each: on a
shared machine they are noisy, so quote the error from here and a speed ratio from
alternated whole runs. Run with Debian's /usr/bin/python3:

    perf/back_faces.py build/ssrt perf/charts/back_faces.csv perf/charts/back_faces.png
"""
import os

import scene_sweeps

MARCHERS = ("hiz", "dda")
ARGS = ("--marchers", ",".join(MARCHERS), "--back-faces", "off,on", "--reference-bounces", "1")


def chart(rows, png):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = scene_sweeps.panels(len(scenes))
    for ax, scene in zip(axes, scenes):
        for marcher, colour in zip(MARCHERS, ("tab:blue", "tab:orange")):
            pts = {r["back_faces"]: (float(r["frame_ms"]), float(r["relmse"]))
                   for r in rows if r["scene"] == scene and r["marcher"] == marcher}
            if set(pts) != {"0", "1"}:
                continue
            (x0, y0), (x1, y1) = pts["0"], pts["1"]
            ax.scatter([x0], [y0], marker="o", color=colour, label=f"{marcher}: thickness")
            ax.scatter([x1], [y1], marker="D", color=colour, label=f"{marcher}: back faces")
            ax.annotate("", (x1, y1), (x0, y0),
                        arrowprops={"arrowstyle": "->", "color": colour, "alpha": 0.6})
        scene_sweeps.label_panel(ax, os.path.basename(scene))
    scene_sweeps.save(fig, axes, len(scenes),
                      "Back-face depth intervals against the thickness guess (640x360, default "
                      "layouts, one-bounce reference)", png)


if __name__ == "__main__":
    scene_sweeps.run("back_faces.py", __doc__, ARGS, chart)
