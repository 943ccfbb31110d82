#!/usr/bin/python3
"""The tracing modes (issue 45) charted: screen, mixed and world on every scene.

For every built-in scene and a real glTF (assimp's 2CylinderEngine at its own scale), runs
`ssrt sweep` with the Hi-Z marcher, once per mode with both signals in it (`--ssr-trace M
--ssgi-trace M`), on the default preset's layouts at 640x360, each a still camera's 30th frame (29 warm-up frames, so the
denoiser has converged and the figure is the method's error rather than one frame's noise),
against the full-light Embree reference, and writes one CSV (the sweep's columns) and a chart
of colour relMSE against the frame's time, one panel per scene, an arrow from screen to mixed
to world. The times come from the sweep's one frame each: on a shared machine they are
noisy, so quote the error from here and a speed ratio from alternated whole runs. Run with
Debian's /usr/bin/python3:

    perf/trace_modes.py build/ssrt perf/charts/trace_modes.csv perf/charts/trace_modes.png
"""
import os

import scene_sweeps

MODES = (("screen", "o", "tab:blue"), ("mixed", "D", "tab:green"), ("world", "s", "tab:red"))
ARGS = [("--marchers", "hiz", "--ssr-trace", m, "--ssgi-trace", m, "--warmup-frames", "29")
        for m, _, _ in MODES]


def chart(rows, png):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = scene_sweeps.panels(len(scenes))
    for ax, scene in zip(axes, scenes):
        pts = [(float(r["frame_ms"]), float(r["relmse"]), r) for m, _, _ in MODES
               for r in rows if r["scene"] == scene and r["ssr_trace"] == m]
        for (x, y, r), (mode, marker, colour) in zip(pts, MODES):
            ssr = float(r["ssr_world_rays"] or 0) * 100
            ssgi = float(r["ssgi_world_rays"] or 0) * 100
            ax.scatter([x], [y], marker=marker, color=colour,
                       label=f"{mode} (world rays: SSR {ssr:.0f} %, SSGI {ssgi:.0f} %)")
        for (x0, y0, _), (x1, y1, _) in zip(pts, pts[1:]):
            ax.annotate("", (x1, y1), (x0, y0),
                        arrowprops={"arrowstyle": "->", "color": "0.5", "alpha": 0.6})
        scene_sweeps.label_panel(ax, os.path.basename(scene))
    scene_sweeps.save(fig, axes, len(scenes),
                      "SSR and SSGI traced on screen, mixed and in world space (640x360, default "
                      "layouts, 30th frame of a still camera, full-light reference)", png)


if __name__ == "__main__":
    scene_sweeps.run("trace_modes.py", __doc__, ARGS, chart)
