#!/usr/bin/python3
"""Error against time from an `ssrt sweep` CSV: one point per setting, the Pareto front drawn.

    /usr/bin/python3 perf/plot.py sweep.csv -o chart.png
    /usr/bin/python3 perf/plot.py sweep.csv -o chart.png --x ms_ssr_march --y relmse_specular

Runs with Debian's python3-matplotlib (/usr/bin/python3; the python3 on PATH may lack it).
A setting is on the Pareto front when no other setting is at least as fast and at least as
accurate and strictly better in one of the two. `--self-test` checks the front and the CSV
reading on made-up rows and draws them to a temporary file.
"""
import argparse
import csv
import math
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

MARKERS = {"off": "x", "linear": "s", "dda": "^", "hiz": "o", "embree": "*", "preset": "P"}


def group(row):
    """The legend entry: a quality preset's rows are 'preset', others their marcher (and
    'back faces' where the depth intervals came from them, and each signal's tracing mode where it
    is not the screen's)."""
    if row.get("quality"):
        return "preset"
    name = row.get("marcher", "")
    if row.get("back_faces") == "1":
        name += " + back faces"
    for signal in ("ssr", "ssgi"):
        if row.get(signal + "_trace") not in (None, "", "screen"):
            name += f", {signal} " + row[signal + "_trace"]
    return name


def read_rows(path, x, y):
    """Rows with finite x and y, as dicts; a missing column is an error naming it."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        for column in (x, y):
            if column not in (reader.fieldnames or []):
                raise SystemExit(f"plot.py: {path} has no column '{column}'")
        rows = []
        for row in reader:
            try:
                xv, yv = float(row[x]), float(row[y])
            except ValueError:
                continue  # an empty cell: that setting has no such figure
            if math.isfinite(xv) and math.isfinite(yv):
                row["_x"], row["_y"] = xv, yv
                rows.append(row)
    if not rows:
        raise SystemExit(f"plot.py: {path} has no row with both '{x}' and '{y}'")
    return rows


def pareto_front(points):
    """Indices of the non-dominated (x, y) points (both minimised), by increasing x."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def label(row):
    if row.get("quality"):
        return row["quality"]
    if row.get("marcher") == "off":
        return "off"
    if row.get("marcher") == "embree":
        return f"embree {row.get('ssr_spp', '')} spp"
    parts = [row.get("marcher", "")]
    for column, suffix in (("max_steps", " st"), ("ssr_spp", " spp")):
        if row.get(column):
            parts.append(row[column] + suffix)
    if row.get("back_faces") == "1":
        parts.append("back faces")
    for signal in ("ssr", "ssgi"):
        if row.get(signal + "_trace") not in (None, "", "screen"):
            parts.append(f"{signal} " + row[signal + "_trace"])
    return ", ".join(parts)


def plot(rows, x, y, out, title):
    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=120)
    for name in sorted({group(r) for r in rows}):
        members = [r for r in rows if group(r) == name]
        ax.scatter([r["_x"] for r in members], [r["_y"] for r in members],
                   marker=MARKERS.get(name, "D"), s=70 if name == "embree" else 40,
                   label=name or "setting")
    front = pareto_front([(r["_x"], r["_y"]) for r in rows])
    # Labels where they are read: the front, and the points that are not grid settings (the
    # others crowd together; their markers say the marcher).
    for i, r in enumerate(rows):
        if i in front or group(r) in ("off", "embree", "preset"):
            ax.annotate(label(r), (r["_x"], r["_y"]), textcoords="offset points",
                        xytext=(4, 4), fontsize=7, color="0.35")
    fx = [rows[i]["_x"] for i in front]
    fy = [rows[i]["_y"] for i in front]
    ax.step(fx, fy, where="post", color="crimson", linewidth=1.2, label="Pareto front")
    if all(r["_y"] > 0 for r in rows):
        ax.set_yscale("log")
    xs = [r["_x"] for r in rows]
    if min(xs) > 0 and max(xs) > 20 * min(xs):  # e.g. Embree's points beside the marchers
        ax.set_xscale("log")
    ax.set_xlabel(x + (" (ms)" if x.endswith("_ms") or x.startswith("ms_") else ""))
    ax.set_ylabel(y)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp)  # whole or not at all
    os.replace(tmp, out)
    plt.close(fig)


def self_test():
    assert pareto_front([(1, 5), (2, 3), (3, 4), (4, 1), (2, 6)]) == [0, 1, 3]
    assert pareto_front([(1, 1), (1, 1)]) == [0]
    assert pareto_front([(3, 1), (1, 3), (2, 2)]) == [1, 2, 0]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "s.csv")
        with open(path, "w") as f:
            f.write("scene,marcher,quality,max_steps,ssr_spp,frame_ms,relmse\n")
            f.write("cornell,off,,,,10,0.5\ncornell,hiz,,64,1,20,0.1\n")
            f.write("cornell,linear,,512,1,80,0.2\ncornell,dda,,,1,,0.3\n")
            f.write("cornell,embree,,,4,300,0.05\ncornell,hiz,low,48,1,15,0.09\n")
        rows = read_rows(path, "frame_ms", "relmse")
        assert [r["marcher"] for r in rows] == ["off", "hiz", "linear", "embree", "hiz"], rows
        assert [group(r) for r in rows] == ["off", "hiz", "linear", "embree", "preset"]
        assert [label(r) for r in rows][3:] == ["embree 4 spp", "low"]
        assert [label(rows[i]) for i in pareto_front([(r["_x"], r["_y"]) for r in rows])] == [
            "off", "low", "embree 4 spp"]
        mixed = dict(rows[1], ssr_trace="mixed", back_faces="1")
        assert group(mixed) == "hiz + back faces, ssr mixed", group(mixed)
        assert label(mixed) == "hiz, 64 st, 1 spp, back faces, ssr mixed", label(mixed)
        assert group(dict(rows[1], ssr_trace="screen")) == "hiz"
        both = dict(rows[1], ssr_trace="world", ssgi_trace="world")
        assert group(both) == "hiz, ssr world, ssgi world", group(both)
        png = os.path.join(d, "chart.png")
        plot(rows, "frame_ms", "relmse", png, "self test")
        assert os.path.getsize(png) > 1000
    print("plot.py: self test passed")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("csv", nargs="?", help="CSV from ssrt sweep")
    p.add_argument("-o", "--output", default="sweep.png", help="PNG to write (default sweep.png)")
    p.add_argument("--x", default="frame_ms", help="time column (default frame_ms)")
    p.add_argument("--y", default="relmse", help="error column (default relmse)")
    p.add_argument("--title", help="chart title (default: scene and size from the CSV)")
    p.add_argument("--self-test", action="store_true", help="check this script and exit")
    a = p.parse_args()
    if a.self_test:
        self_test()
        return
    if not a.csv:
        p.error("a CSV file is required")
    rows = read_rows(a.csv, a.x, a.y)
    r0 = rows[0]
    title = a.title or f"{r0.get('scene', '')} {r0.get('width', '')}x{r0.get('height', '')}: " \
                       f"{a.y} against {a.x}"
    plot(rows, a.x, a.y, a.output, title)
    print(f"wrote {a.output} ({len(rows)} settings)")


if __name__ == "__main__":
    main()
