#!/usr/bin/env python3
"""Each command's --json against its own text: both are run, both are parsed, and every figure
the text prints must be the JSON's, rounded as the text rounds it (docs/cli.md, docs/golden.md,
docs/truth.md give the schemas). Counters and image errors are deterministic, so the two runs
agree exactly; times are not, so for them each output is checked on its own (the march's rays
per second and ns per step against its own pass times and counters).

    check_json_output.py SSRT          (run by ctest: json_output_matches_text)
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

SSRT = os.path.abspath(sys.argv[1])
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args, status=0):
    """stdout of `ssrt ARGS` (its exit status checked), stderr passed through."""
    r = subprocess.run([SSRT, *args], capture_output=True, text=True)
    check(r.returncode == status,
          f"ssrt {' '.join(args)}: exit {r.returncode}, expected {status}: {r.stderr}")
    return r.stdout


def run_json(*args, status=0):
    text = run(*args, "--json", status=status)
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        check(False, f"ssrt {' '.join(args)} --json: not one JSON document ({e}): {text[:200]}")
        return {}


def key(label):
    """cli/json_output.h jsonKey: the JSON key of a text row's label."""
    words = re.findall(r"[a-z0-9]+|%", label.lower())
    return "_".join("percent" if w == "%" else w for w in words)


def same(text, value, what):
    """A text cell against the JSON value: equal as printed (its decimals), '-' for null."""
    if value is None:
        check(text == "-", f"{what}: text {text!r}, JSON null")
        return
    if isinstance(value, bool) or isinstance(value, str):
        check(text == str(value), f"{what}: text {text!r}, JSON {value!r}")
        return
    if isinstance(value, int) and re.fullmatch(r"-?\d+", text):
        check(int(text) == value, f"{what}: text {text}, JSON {value}")
        return
    # A fraction printed with d decimals (or as %e): the JSON value rounds to it.
    m = re.fullmatch(r"-?\d+(?:\.(\d+))?", text)
    if m:
        decimals = len(m.group(1) or "")
        check(f"{value:.{decimals}f}" == text, f"{what}: text {text}, JSON {value}")
        return
    m = re.fullmatch(r"-?\d\.(\d+)e[-+]\d+", text)
    if m:
        check(f"{value:.{len(m.group(1))}e}" == text, f"{what}: text {text}, JSON {value}")
        return
    check(False, f"{what}: text {text!r} is not a number (JSON {value!r})")


def table(lines, title):
    """The rows under a table's title line, up to a blank line: {label: [cells]}."""
    start = next(i for i, l in enumerate(lines) if l.startswith(title))
    rows = {}
    for line in lines[start + 1:]:
        if not line.strip():
            break
        cells = re.split(r" {2,}", line.strip())
        rows[cells[0]] = cells[1:]
    return rows


def near(a, b, rel, what):
    check(abs(a - b) <= rel * max(abs(a), abs(b)) + 1e-9, f"{what}: {a} against {b}")


# ---- ssrt scenes ---------------------------------------------------------------------------
scenes = run_json("scenes")
text = [re.split(r" {2,}", l, maxsplit=1) for l in run("scenes").splitlines()]
check(list(scenes.items()) == [(n, d) for n, d in text], "scenes: the JSON is the text's list")

workdir = tempfile.TemporaryDirectory(prefix="ssrt-json-")  # removed at exit
tmp = workdir.name
os.chdir(tmp)
os.environ["SSRT_CACHE_DIR"] = os.path.join(tmp, "cache")
size = ["--width", "64", "--height", "36"]

# ---- ssrt render --stats -------------------------------------------------------------------
doc = run_json("render", *size, "-q", "--stats", "-o", "j.exr", "--frames", "2")
out = run("render", *size, "-q", "--stats", "-o", "t.exr", "--frames", "2")
check(len(doc.get("frames", [])) == 2, "render: a stats object per frame")
blocks = re.split(r"\n\n(?=frame \d)", out)
check(len(blocks) == 2, "render: a text block per frame")
for f, block in zip(doc.get("frames", []), blocks):
    lines = block.splitlines()
    check(lines[0].startswith(f"frame {f['frame']} "), f"render: frame {f['frame']}'s heading")
    check(lines[1] == f"isa {f['isa']}, {f['threads']} threads", "render: the isa line")
    passes = table(lines, "pass ")
    check([p for p in passes if p not in ("sum of passes", "render call", "image write")] ==
          list(f["pass_times"]), "render: the same passes in the same order")
    check([p for p, cells in passes.items() if cells[1:] == ["in the loop above"]] ==
          f["fused_passes"], "render: the same passes marked as run in the loop above")
    check(f["fused_passes"], "render: a frame runs some passes in one loop")
    raster = table(lines, "raster counter")
    for label, (vis, shadow) in raster.items():
        same(vis, f["raster"]["visibility"][key(label)], f"render: visibility {label}")
        same(shadow, f["raster"]["shadow"][key(label)], f"render: shadow {label}")
    check(len(raster) == len(f["raster"]["visibility"]), "render: every raster counter")
    trace = table(lines, "trace counter")
    timed = ("Mrays per second", "ns per march step")
    for p, pass_name in enumerate(("ssr", "ssgi")):
        t = f["trace"][pass_name]
        check(list(map(key, trace)) == list(t), f"render: {pass_name}'s trace rows")
        for label, cells in trace.items():
            if label not in timed:  # (the counters; the times are another run's)
                same(cells[p], t[key(label)], f"render: {pass_name} {label}")
        # The speed from this output's own figures: rays and steps over the march's time.
        ms = f["pass_times"][f"{pass_name} march"]
        near(t["mrays_per_second"], t["rays_traced"] * 1e-3 / ms, 1e-9,
             f"render JSON: {pass_name} Mrays per second")
        near(t["ns_per_march_step"], ms * 1e6 / t["steps_in_all"], 1e-9,
             f"render JSON: {pass_name} ns per march step")
        text_ms = float(passes[f"{pass_name} march"][0])
        rays, steps = int(trace["rays traced"][p]), int(trace["steps in all"][p])
        # The text's ms has 3 decimals and its rate its own: the rate from the printed ms agrees
        # to both roundings (the rate's half unit of its last place, the ms's relative share).
        for label, rate in (("Mrays per second", rays * 1e-3 / text_ms),
                            ("ns per march step", text_ms * 1e6 / steps)):
            cell = trace[label][p]
            half_unit = 0.5 * 10.0 ** -len(cell.partition(".")[2])
            check(abs(float(cell) - rate) <= half_unit + rate * 0.0005 / text_ms + 1e-9,
                  f"render text: {pass_name} {label}: {cell} against {rate}")
    pixels = 64 * 36
    for title, name in (("memory ", "memory"), ("memory the frame graph declares", "memory_declared")):
        rows = table(lines, title)
        m = f[name]
        check(list(rows)[:-1] == list(m["by_resource"]), f"render: {name}'s rows")
        for label, (per_pixel, mb) in rows.items():
            b = m["in_all"] if label == "in all" else m["by_resource"][label]
            same(per_pixel, b / pixels, f"render: {name} {label} B/pixel")
            same(mb, b / 1e6, f"render: {name} {label} MB")

# The process table, once, with the first frame's block; the JSON's "process" (two processes:
# the same rows and keys, each figure its own process's, so present and positive).
proc = doc.get("process", {})
rows = table(blocks[0].splitlines(), "process ")
check(list(rows) == ["CPU before main", "command line", "scene set-up"],
      f"render: the process table's rows {list(rows)}")
check([k[:-3] for k in list(proc)[:3]] == [key(r) for r in rows], "render: the process keys")
for label, cells in rows.items():
    check(float(cells[0]) > 0 and proc[key(label) + "_ms"] > 0, f"render: process {label}")
faults = re.search(r"\nthe first render call touched (\d+) pages for the first time", blocks[0])
check(faults and int(faults.group(1)) > 0 and proc["first_render_call_page_faults"] > 0,
      "render: the first render call's page faults")
check("\nprocess " not in blocks[1], "render: the process table once")

run("render", *size, "-q", "--json", "-o", "x.png", status=2)  # neither --stats nor --compare

# ---- ssrt diff and render --compare --------------------------------------------------------
run("render", *size, "-q", "-o", "a.exr")
run("render", *size, "-q", "-o", "b.exr", "--frame", "1")


def check_diff(d, out, what):
    lines = out.splitlines()
    rows = [re.split(r" {2,}", l) for l in lines[1:1 + len(d["layers"])]]
    check([r[0] for r in rows] == list(d["layers"]), f"{what}: the same layers in order")
    for r in rows:
        l = d["layers"][r[0]]
        check(r[1] == ",".join(c.rsplit(".", 1)[-1] for c in l["channels"]), f"{what}: channels")
        if not l["present"]:
            continue
        check(r[2] == f"{l['max_error']:.4g}", f"{what}: {r[0]} max error {r[2]}, {l['max_error']}")
        if l["max_error"] > 0:
            x, y, c = l["max_at"]
            check(r[3] == f"({x}, {y}) {c}", f"{what}: {r[0]} at {r[3]}")
        check(r[4] == f"{l['rel_mse']:.4g}", f"{what}: {r[0]} relMSE {r[4]}, {l['rel_mse']}")
        check(int(r[5]) == l["pixels_over"], f"{what}: {r[0]} pixels over")
        check(r[6] == f"{100 * l['share_over']:.4g}%", f"{what}: {r[0]} share {r[6]}")
        verdict = ("bit-identical" if l["identical"] else
                   ("within" if l["max_error"] > 0 else "equal") if l["passed"] else
                   "beyond: " + l["why"])
        check(r[7] == verdict, f"{what}: {r[0]} verdict {r[7]!r}, {verdict!r}")
    check(lines[-1].startswith(d["verdict"] + ":"), f"{what}: the summary line {lines[-1]!r}")
    check(f"({d['width']}x{d['height']}, " in lines[-1], f"{what}: the size")


for args, status in ((["--max-share", "0.5"], 1), (["--layers", "color", "--threshold", "1"], 0),
                     (["--layers", "color,viewZ", "--max-share", "0.5"], 1)):
    check_diff(run_json("diff", "a.exr", "b.exr", *args, status=status),
               run("diff", "a.exr", "b.exr", *args, status=status), f"diff {' '.join(args)}")
d = run_json("diff", "a.exr", "a.exr")
check(d["identical"] and d["passed"] and d["verdict"] == "bit-identical", "diff: identical")
doc = run_json("render", *size, "-q", "-o", "c.exr", "--frame", "1", "--compare", "a.exr",
               "--max-share", "0.5", status=1)
check_diff(doc.get("compare", {}),
           run("render", *size, "-q", "-o", "d.exr", "--frame", "1", "--compare", "a.exr",
               "--max-share", "0.5", status=1).replace("d.exr", "c.exr"), "render --compare")
check("frames" not in doc, "render --compare without --stats: no frames")

# ---- ssrt compare --------------------------------------------------------------------------
truth = size + ["--reference-spp", "2", "--repeats", "1", "-q"]
c = run_json("compare", *truth)
lines = run("compare", *truth).splitlines()
check(lines[0].startswith(f"{c['scene']} {c['width']}x{c['height']}, marcher {c['marcher']}, "
                          f"ssr {c['ssr']['method']} x{c['ssr']['spp']}, ssgi x{c['ssgi']['spp']}"),
      f"compare: the heading {lines[0]!r}")
bvh = c["bvh"]
check(lines[2].startswith(f"BVH (Embree 3): {bvh['triangles']} triangles, {bvh['meshes']} meshes, "
                          f"{bvh['instances']} instances"), "compare: the BVH line")
checks = table(lines, "ray check (Embree)")
for p, pass_name in enumerate(("ssr", "ssgi")):
    check(list(map(key, checks)) == list(c["ray_check"][pass_name]), f"compare: {pass_name} rows")
    for label, cells in checks.items():
        same(cells[p], c["ray_check"][pass_name][key(label)], f"compare: {pass_name} {label}")
errors = table(lines, "image error")
for label, name in (("color (exposed)", "color"), ("direct", "direct"), ("specular", "specular"),
                    ("diffuse", "diffuse")):
    e = c["image_error"][name]
    same(errors[label][0], e["rel_mse"], f"compare: {name} relMSE")
    same(errors[label][1], e["rmse"], f"compare: {name} RMSE")
    same(errors[label][2], e["non_finite"], f"compare: {name} non-finite")
model = table(lines, "one-bounce model")
same(model["color (exposed)"][0], c["one_bounce"]["method"]["color"]["rel_mse"], "compare: method")
same(model["color (exposed)"][1], c["one_bounce"]["model"]["color"]["rel_mse"], "compare: model")
passes = table(lines, "pass (median)")
check(list(passes)[:-1] == list(c["pass_times"]), "compare: the same passes")
near(c["march_vs_embree"], c["march_mrays_per_second"] / c["embree_mrays_per_second"], 1e-9,
     "compare: march / Embree")
seq = run_json("compare", *truth, "--frames", "3")
out = run("compare", *truth, "--frames", "3")
rows = [r for r in (re.split(r" +", l.strip()) for l in out.split("per frame\n")[1].splitlines()[1:])
        if r[0].isdigit()]
check(len(rows) == len(seq["per_frame"]) == 3, "compare --frames 3: a row per frame")
for r, f in zip(rows, seq["per_frame"]):
    check(int(r[0]) == f["frame"] and int(r[1]) == f["frame_index"], "compare: frame numbers")
    same(r[2], f["rel_mse"], f"compare: frame {f['frame']} relMSE")
    same(r[3], f["flicker"], f"compare: frame {f['frame']} flicker")

# ---- ssrt check ----------------------------------------------------------------------------
os.makedirs("suite")
with open("suite/suite.json", "w") as s:
    json.dump({"cases": [
        {"name": "same", "render": size + ["--layers", "color"], "reference": "same.exr"},
        {"name": "other", "render": size + ["--frame", "1", "--layers", "color"],
         "reference": "same.exr"},
        {"name": "new", "render": size + ["--layers", "color"], "reference": "none.exr"}]}, s)
run("render", *size, "-q", "--layers", "color", "-o", "suite/same.exr")
# (one --out for both runs: the messages name the files in it)
lines = run("check", "suite/suite.json", "--out", "cases", status=1).splitlines()
k = run_json("check", "suite/suite.json", "--out", "cases", status=1)
check(len(lines) == len(k["cases"]) + 1, "check: a line per case and the summary")
for line, case in zip(lines, k["cases"]):
    status, name, message = re.split(r" {2,}", line, maxsplit=2)
    check((status, name) == (case["status"], case["name"]), f"check: {line!r}")
    check(message == case["message"], f"check: {name}'s message {message!r}")
check(lines[-1].startswith(f"check: {k['summary']} ("), "check: the summary line")
counts = re.match(r"(\d+) cases: (\d+) passed, (\d+) failed, (\d+) stale, (\d+) new, (\d+) error",
                  k["summary"])
check(counts and [int(g) for g in counts.groups()] ==
      [len(k["cases"]), k["counts"]["pass"], k["counts"]["fail"], k["counts"]["stale"],
       k["counts"]["new"], k["counts"]["error"]], "check: the counts are the summary's")
check([c["status"] for c in k["cases"]] == ["PASS", "FAIL", "NEW"], "check: the statuses")

os.chdir("/")
if failures:
    print(f"check_json_output: {len(failures)} failures")
    sys.exit(1)
print("check_json_output: every --json agrees with its text")
