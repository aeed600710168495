#!/usr/bin/env python3
"""Plots of out/sweep/sweep.csv (docs/benchmarks.md). Per block family and per cost, one
PNG with a panel per scene: the colour error (RMSE against the golden model) of every run
against the cost, each point labelled with its configuration, the scene's Pareto front a
staircase through its points (filled) with the dominated runs open. The costs: wall time
(median, bars over the middle half of the runs), simulated cycles, operations, and the bytes the texture units
read (the families that read any). Also OUT_DIR/index.html, one self-contained page with
every plot and every run, and, printed, the Markdown tables of the Pareto-optimal
configurations per scene against wall time and against cycles.

Usage: scripts/plot.py SWEEP_CSV OUT_DIR
Exit 2, one line on stderr and nothing drawn: a CSV that cannot be read or is not a
sweep's, no gnuplot, an OUT_DIR that cannot be made."""
import base64
import csv
import html
import math
import os
import shutil
import subprocess
import sys

OPS = ["add", "mul", "div", "sqrt", "rsqrt", "lut", "fetch"]  # `line` is a cost, not an operation
ERR_FLOOR = 1e-9  # a run equal to the golden model still needs a place on a log axis


PROGRAM = "plot"  # the name its refusals start with (a script that imports it sets its own)


def fail(message):
    print(PROGRAM + ": " + message, file=sys.stderr)
    sys.exit(2)


def load(path):
    """The sweep's rows, their figures as numbers; exits 2 naming the first that is not one."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
    except (OSError, csv.Error, ValueError) as e:  # ValueError: bytes that are not text
        fail("%s: cannot read it: %s" % (path, e.strerror if isinstance(e, OSError) else e))
    lacking = [c for c in ["family", "scene", "configuration", "wall_s", "frame_cycles"] + OPS +
               ["line", "err_rmse", "err_psnr"] if c not in (reader.fieldnames or [])]
    if lacking:
        fail("%s: no column %s: not a CSV of scripts/sweep.py" % (path, ", ".join(lacking)))
    if not rows:
        fail("%s: no runs" % path)

    for k, r in enumerate(rows, 1):
        def number(key, kind=float, default=None):
            """The field as a finite number, not negative (err_psnr: any)."""
            text = r.get(key) or default
            try:
                x = kind(text)
            except (TypeError, ValueError):
                x = None
            if x is None or key != "err_psnr" and (x < 0 or not math.isfinite(x)):
                fail("%s: row %d: %s is %r, not a count or a figure" % (path, k, key, text))
            return x

        if None in r.values():
            fail("%s: row %d has fewer fields than the header" % (path, k))
        r["wall_s"], r["frame_cycles"] = number("wall_s"), number("frame_cycles")
        # CSVs from before the timing pass have one wall time a run and no spread.
        for key in ["wall_q1_s", "wall_q3_s", "wall_min_s", "wall_max_s"]:
            r[key] = number(key, default=r["wall_s"])
        r["wall_runs"] = number("wall_runs", int, 1)
        # The silicon (docs/silicon.md): 0 where the CSV has none (older sweeps, a block
        # not priced), and a family with a 0 gets no such plot.
        r["area_mm2"], r["energy_nj"] = number("area_mm2", default=0), number("energy_nj_per_pixel", default=0)
        r["ops"] = sum(number(op, int) for op in OPS)
        r["bytes"] = 64 * number("line", int)  # 64-byte lines (docs/pipeline.md)
        r["err_rmse"] = max(number("err_rmse"), ERR_FLOOR)
        r["err_psnr"] = float("inf") if r["err_psnr"] == "nan" else number("err_psnr")
        try:
            r["label"] = label(r)
        except (KeyError, ValueError):
            fail("%s: row %d: %r is not a configuration of the %s family" % (path, k, r["configuration"], r["family"]))
    check_labels(rows, path)
    return rows


# Each cost: its name in file names, its axis, and its value for a run.
COSTS = [
    ("time", "wall time (ms): median of the runs, bars their quartiles", lambda r: 1000 * r["wall_s"]),
    ("cycles", "simulated cycles per frame", lambda r: r["frame_cycles"]),
    ("ops", "operations per frame (add, mul, div, sqrt, rsqrt, lut, fetch)", lambda r: r["ops"]),
    ("bytes", "bytes the texture unit reads per frame (64-byte lines, a line buffer per pixel)",
     lambda r: r["bytes"]),
    ("area", "area of the blocks' arithmetic (mm², OSU 0.18 um)", lambda r: r["area_mm2"]),
    ("energy", "energy of the blocks' arithmetic per shaded pixel (nJ, OSU 0.18 um)", lambda r: r["energy_nj"]),
]
COST = {name: value for name, _, value in COSTS}
AXIS = {name: axis.split(" (")[0].split(":")[0] for name, axis, _ in COSTS}

# Short names of configuration values, so that a label fits beside its point.
SHORT = {"perspective": "P", "affine": "A", "forward-difference": "fwd-diff", "nearest": "near",
         "bilinear": "bilin", "trilinear": "trilin", "anisotropic": "aniso", "texture-object": "object"}


def label(r):
    """The run's configuration in a few characters: the values of its family's axes,
    abbreviated, then any other setting it was given (the number format only when not
    float32), so that two configurations never share a label."""
    c = {key.rsplit(".", 1)[-1] if "interp" not in key else "interp": v
         for key, v in (kv.split("=", 1) for kv in r["configuration"].split(";"))}
    used = {"number_format"}
    if r["family"] == "normal":
        text, used = "%s %s" % (SHORT[c["interp"]], SHORT.get(c["mode"], c["mode"])), used | {"interp", "mode"}
    elif r["family"] == "bump":
        text, used = "%s %s" % (c["path"].replace("bump-", ""), SHORT.get(c["filter"], c["filter"])), used | {"path", "filter"}
    elif r["family"] == "texture":  # texture-object has no filter axis
        text, used = SHORT.get(c.get("filter", c["path"]), c.get("filter", c["path"])), used | {"filter", "path"}
    elif r["family"] == "parallax":
        tracer = c["map"] if "map" in c else c.get("method", "refined")
        if "cones" in c:  # classic or relaxed cones: one tracer each
            tracer = "%s %s" % (c["cones"], tracer)
        used |= {"map", "method", "cones", "max_iterations", "steps"}
        text = tracer if tracer == "offset" else "%s %s" % (tracer, c.get("max_iterations", c.get("steps")))
    else:
        text = ",".join(v for k, v in c.items() if k != "number_format")
        used = set(c)
    extra = ["%s=%s" % (k, v) for k, v in c.items() if k not in used]
    if c.get("number_format", "float32") != "float32":
        extra.append(c["number_format"])
    return " ".join([text] + extra)


def check_labels(rows, path):
    """Exits 2 when two configurations of a family and scene would share a label."""
    seen = {}
    for k, r in enumerate(rows, 1):
        other = seen.setdefault((r["family"], r["scene"], r["label"]), (k, r["configuration"]))
        if other[1] != r["configuration"]:
            fail("%s: rows %d and %d: configurations %r and %r would share the label %r" %
                 (path, other[0], k, other[1], r["configuration"], r["label"]))


def front(runs, cost):
    """The runs no other run beats: none as cheap and as exact, and better in one."""
    def beats(a, b):
        return (cost(a) <= cost(b) and a["err_rmse"] <= b["err_rmse"] and
                (cost(a) < cost(b) or a["err_rmse"] < b["err_rmse"]))
    return sorted([b for b in runs if not any(beats(a, b) for a in runs)], key=lambda r: (cost(r), r["err_rmse"]))


def short(scene):
    return scene.replace("golden/", "").replace("/scene.json", "").replace("scenes/", "").replace(".json", "")


# ---- Axes: log ranges and tick labels that read as numbers ----

def log_range(values, pad):
    """A log10 range around the values, pad of its span on each side, at least 0.15 decade."""
    lo, hi = math.log10(min(values)), math.log10(max(values))
    span = max(hi - lo, 0.15)
    mid = (lo + hi) / 2
    return mid - span * (0.5 + pad), mid + span * (0.5 + pad)


def tick_text(v, power):
    """10^{-7} and 2·10^{-7} on the error axis; 20, 500k, 2M on the cost axes."""
    k = math.floor(math.log10(v) + 1e-9)
    m = float("%.2g" % (v / 10 ** k))
    if power:
        return "10^{%d}" % k if m == 1 else "%g·10^{%d}" % (m, k)
    for div, suffix in [(1e9, "G"), (1e6, "M"), (1e3, "k")]:
        if v >= div:
            return "%g%s" % (float("%.3g" % (v / div)), suffix)
    return "%g" % float("%.3g" % v)


# Tick mantissas, coarse to fine: an axis takes the finest set whose ticks stay apart.
MANTISSAS = [[1], [1, 2, 5], [1, 2, 3, 5, 7], [1, 1.5, 2, 2.5, 3, 4, 5, 6, 7, 8],
             [1, 1.2, 1.4, 1.6, 1.8, 2, 2.5, 3, 3.5, 4, 4.5, 5, 6, 7, 8, 9]]


def ticks(lo, hi, power, pixels, gap):
    """Ticks inside log10 range lo..hi, an axis `pixels` long, at least `gap` pixels
    apart, as a gnuplot tick list."""
    chosen = []
    for mantissas in MANTISSAS:
        values = sorted(m * 10.0 ** k for k in range(math.floor(lo), math.ceil(hi) + 1) for m in mantissas)
        inside = [v for v in values if lo <= math.log10(v) <= hi]
        steps = [math.log10(b / a) / (hi - lo) * pixels for a, b in zip(inside, inside[1:])]
        if chosen and steps and min(steps) < gap:
            break
        chosen = inside
    return "(%s)" % ", ".join('"%s" %.10g' % (tick_text(v, power), v) for v in chosen)


# ---- Figure geometry, in pixels from the bottom left, so labels can be placed ----

PANEL_W, PANEL_H = 640, 470  # a panel of a 2 × N grid
SINGLE_W, SINGLE_H = 900, 620  # a figure's one panel: one scene, up to 20 labels
LEFT, RIGHT, TOP, BOTTOM = 40, 20, 46, 62       # around the panels: shared labels, title, caption
INSET_L, INSET_R, INSET_T, INSET_B = 74, 12, 30, 30  # inside a panel: its tick labels and title
FONT, CHAR_W, CHAR_H = 9, 6.6, 13  # Sans 9 on pngcairo: about 6.6 px a character, 13 px a line


def figure_size(panel, rows):
    cols = 1 if panel == (SINGLE_W, SINGLE_H) else 2
    return LEFT + cols * panel[0] + RIGHT, BOTTOM + rows * panel[1] + TOP


class Panel:
    """One scene's plot area: maps a (cost, error) point to pixels, and back to screen fractions."""
    def __init__(self, col, row, rows, size, xr, yr):
        (self.w, self.h), (pw, ph) = figure_size(size, rows), size
        self.x0 = LEFT + col * pw + INSET_L
        self.x1 = LEFT + (col + 1) * pw - INSET_R
        self.y0 = BOTTOM + (rows - 1 - row) * ph + INSET_B
        self.y1 = BOTTOM + (rows - row) * ph - INSET_T
        self.xr, self.yr = xr, yr

    def pixel(self, x, y):
        fx = (math.log10(x) - self.xr[0]) / (self.xr[1] - self.xr[0])
        fy = (math.log10(y) - self.yr[0]) / (self.yr[1] - self.yr[0])
        return self.x0 + fx * (self.x1 - self.x0), self.y0 + fy * (self.y1 - self.y0)

    def margins(self):
        return ["set lmargin at screen %.5f" % (self.x0 / self.w), "set rmargin at screen %.5f" % (self.x1 / self.w),
                "set bmargin at screen %.5f" % (self.y0 / self.h), "set tmargin at screen %.5f" % (self.y1 / self.h)]


# ---- Labels: each beside its point, where it overlaps no other label or point ----

def overlap(a, b):
    return max(0, min(a[2], b[2]) - max(a[0], b[0])) * max(0, min(a[3], b[3]) - max(a[1], b[1]))


def candidates(px, py, text):
    """Boxes (x0, y0, x1, y1) for the text around the point, nearest first, with the
    gnuplot alignment and anchor of each."""
    w, h, g = len(text) * CHAR_W, CHAR_H, 7
    near = [(px + g, py - h / 2, "left"), (px - g - w, py - h / 2, "right"),
            (px - w / 2, py + g, "center"), (px - w / 2, py - g - h, "center"),
            (px + g / 2, py + g / 2, "left"), (px + g / 2, py - g / 2 - h, "left"),
            (px - g / 2 - w, py + g / 2, "right"), (px - g / 2 - w, py - g / 2 - h, "right")]
    far = [(x, y + dy * h, a) for dy in (1, -1, 2, -2, 3, -3) for x, y, a in near[:2]]
    for x, y, align in near + far:
        anchor = {"left": x, "right": x + w, "center": x + w / 2}[align]
        yield (x, y, x + w, y + h), align, (anchor, y + h / 2)


def place(points, panel, lines):
    """Labels for points [(px, py, text, is_front)]: front points first (they matter most),
    each at the candidate box that covers least: other labels and points count fully, the
    thin lines (staircase, bars) two thirds, the plot's edge a hundredfold, and each step
    further from the point a little, so that a label stays by its point unless it must
    move. Returns [(text, align, anchor, point, is_front)]."""
    taken = [(px - 4, py - 4, px + 4, py + 4) for px, py, _, _ in points]
    placed = []
    for px, py, text, is_front in sorted(points, key=lambda p: not p[3]):
        def badness(k, box):
            inside = overlap(box, (panel.x0, panel.y0, panel.x1, panel.y1))
            outside = (box[2] - box[0]) * (box[3] - box[1]) - inside
            return (sum(overlap(box, t) for t in taken) + sum(overlap(box, l) for l in lines) * 2 / 3 +
                    100 * outside + 12 * k)
        scored = [(badness(k, box), box, align, anchor)
                  for k, (box, align, anchor) in enumerate(candidates(px, py, text))]
        _, box, align, anchor = min(scored, key=lambda c: c[0])
        taken.append(box)
        placed.append((text, align, anchor, (px, py), is_front))
    return placed


def segments(panel, stairs):
    """The staircase's segments as boxes 3 px thick, for the labels to keep off."""
    pts = [panel.pixel(x, y) for x, y in stairs]
    boxes = []
    for (ax, ay), (bx, by) in zip(pts, pts[1:]):
        boxes.append((min(ax, bx), ay - 1.5, max(ax, bx), ay + 1.5))  # across at the old error
        boxes.append((bx - 1.5, min(ay, by), bx + 1.5, max(ay, by)))  # then down at the new cost
    return boxes


def merge_coincident(runs, panel, cost):
    """Runs drawn on the same spot share one label ("pom 64, 256" rather than two on top
    of each other)."""
    groups = []
    for r in runs:
        px, py = panel.pixel(cost(r), r["err_rmse"])
        for g in groups:
            if abs(g[0] - px) < 3 and abs(g[1] - py) < 3:
                g[2].append(r)
                break
        else:
            groups.append((px, py, [r]))
    return groups


def bars(panel, runs):
    """The wall times' bars as boxes 3 px thick, for the labels to keep off."""
    boxes = []
    for r in runs:
        x0, y = panel.pixel(1000 * r["wall_q1_s"], r["err_rmse"])
        x1, _ = panel.pixel(1000 * r["wall_q3_s"], r["err_rmse"])
        boxes.append((x0, y - 1.5, x1, y + 1.5))
    return boxes


def group_text(runs, panel_runs):
    """One label for runs on one spot. Labels are "axis1 axis2" (e.g. "classic bilin"):
    a group that is every combination of some first and some second words is written
    once ("classic,tangent bilin"; "all bilin" when the first words are all there are)."""
    words = [r["label"].rsplit(" ", 1) for r in runs]
    if len(runs) == 1 or any(len(w) != 2 for w in words):
        return " = ".join(r["label"] for r in runs)
    heads, tails = unique(w[0] for w in words), unique(w[1] for w in words)
    if len(runs) != len(heads) * len(tails):
        return " = ".join(r["label"] for r in runs)
    every = unique(r["label"].rsplit(" ", 1)[0] for r in panel_runs)
    return "%s %s" % ("all" if len(heads) > 1 and heads == every else ",".join(heads), ",".join(tails))


def unique(items):
    out = []
    for x in items:
        if x not in out:
            out.append(x)
    return out


# ---- One figure: a panel per scene ----

FRONT_COLOUR, OTHER_COLOUR = "#1f5fa8", "#8c8c8c"


def datablock(name, lines):
    return ["$%s << EOD" % name] + lines + ["EOD"]


def panel_script(panel, scene, runs, cost_name, fr, stairs):
    """gnuplot commands for one scene's panel: points, error bars, staircase, labels."""
    cost = COST[cost_name]
    on_front = set(id(r) for r in fr)
    xr, yr = panel.xr, panel.yr
    out = ["unset label", "unset arrow"] + panel.margins()
    out += ["set title %s noenhanced offset 0,-0.6" % gp_str(short(scene)),
            "set xrange [%.6g:%.6g]" % (10 ** xr[0], 10 ** xr[1]),
            "set yrange [%.6g:%.6g]" % (10 ** yr[0], 10 ** yr[1]),
            "set xtics %s" % ticks(*xr, False, panel.x1 - panel.x0, 45),
            "set ytics %s" % ticks(*yr, True, panel.y1 - panel.y0, 28)]
    points = []
    for px, py, group in merge_coincident(runs, panel, cost):
        points.append((px, py, group_text(group, runs), any(id(r) in on_front for r in group)))
    lines = segments(panel, stairs) + (bars(panel, runs) if cost_name == "time" else [])
    for text, align, (ax, ay), (px, py), is_front in place(points, panel, lines):
        colour = "black" if is_front else "#505050"
        font = "Sans:Bold,%d" % FONT if is_front else "Sans,%d" % FONT
        out.append("set label %s at screen %.5f,%.5f %s noenhanced font '%s' tc rgb '%s' front boxed" % (
            gp_str(text), ax / panel.w, ay / panel.h, align, font, colour))
        if abs(ay - py) > 1.5 * CHAR_H:  # far from its point: a leader line says whose it is
            out.append("set arrow from screen %.5f,%.5f to screen %.5f,%.5f nohead lc rgb '#b0b0b0' lw 0.8" % (
                px / panel.w, py / panel.h, ax / panel.w, ay / panel.h))
    return out


def gp_str(s):
    return '"%s"' % s.replace("\\", "\\\\").replace('"', '\\"')


def panel_data(k, runs, cost_name, fr, stairs):
    """Datablocks of a panel: dominated runs, front runs (x, y, xlow, xhigh), the staircase."""
    cost = COST[cost_name]
    on_front = set(id(r) for r in fr)

    def rows(sel):
        out = []
        for r in sel:
            x = cost(r)
            lo, hi = (1000 * r["wall_q1_s"], 1000 * r["wall_q3_s"]) if cost_name == "time" else (x, x)
            out.append("%.8g %.8g %.8g %.8g" % (x, r["err_rmse"], lo, hi))
        return out or ["nan nan nan nan"]
    return (datablock("other%d" % k, rows([r for r in runs if id(r) not in on_front])) +
            datablock("front%d" % k, rows(fr)) + datablock("stairs%d" % k, ["%.8g %.8g" % p for p in stairs]))


def staircase(fr, cost, xr):
    """The front's staircase: across at each front point's error to the next one's cost,
    then down to its error; after the last, on to the right edge. Everything above and
    right of it is dominated."""
    return [(cost(r), r["err_rmse"]) for r in fr] + [(10 ** xr[1], fr[-1]["err_rmse"])]


def plot_commands(k, cost_name):
    timed = cost_name == "time"  # the wall times have their spread: bars over the quartiles
    style = "xerrorbars" if timed else "points"
    using = "1:2:3:4" if timed else "1:2"
    return ("plot $stairs{k} with steps lw 2 lc rgb '{f}' notitle, "
            "$other{k} using {u} with {s} pt 6 ps 1.1 lw 1 lc rgb '{o}' notitle, "
            "$front{k} using {u} with {s} pt 7 ps 1.4 lw 1.2 lc rgb '{f}' notitle").format(
                k=k, f=FRONT_COLOUR, o=OTHER_COLOUR, u=using, s=style)


def figure(family, runs, cost_name, axis, path):
    """One PNG: the family's error against one cost, a panel per scene."""
    cost = COST[cost_name]
    scenes = sorted(set(r["scene"] for r in runs))
    cols = 1 if len(scenes) == 1 else 2
    rows = (len(scenes) + cols - 1) // cols
    size = (SINGLE_W, SINGLE_H) if cols == 1 else (PANEL_W, PANEL_H)
    width, height = figure_size(size, rows)
    script = ["set terminal pngcairo size %d,%d font 'Sans,%d'" % (width, height, FONT + 1),
              "set encoding utf8", "set output %s" % gp_str(path), "set multiplot",
              "set logscale xy", "set grid xtics ytics lc rgb '#dddddd'", "set errorbars small", "unset key",
              "set xtics nomirror out", "set ytics nomirror out", "set border 3",
              # Labels on a white ground: one that has to sit on a line or a bar stays legible.
              "set style textbox opaque noborder margins 0.5,0.5"]
    # One title, one y label and one x label for the figure, not one per panel: drawn
    # with the first panel (each panel unsets the labels of the one before).
    shared = ["set label %s at screen 0.5,%.5f center font 'Sans,12' noenhanced" % (
        gp_str("%s: error against %s" % (family, AXIS[cost_name])),
        1 - 18 / height),
        "set label 'RMSE (covered pixels, R, G, B) against the golden model' at screen %.5f,0.5 center rotate"
        " noenhanced" % (14 / width),
        "set label %s at screen 0.5,%.5f center noenhanced" % (gp_str(axis), 34 / height),
        "set label %s at screen 0.5,%.5f center noenhanced tc rgb '#505050'" % (gp_str(
            "filled: the Pareto front (the staircase: what it dominates lies above and right of it);"
            " open: dominated"), 12 / height)]
    for k, scene in enumerate(scenes):
        sruns = [r for r in runs if r["scene"] == scene]
        fr = front(sruns, cost)
        # Ranges of its own for each panel: the scenes' costs differ, and a shared range
        # would crowd each scene's points (and labels) into a corner.
        xs = [cost(r) for r in sruns]
        if cost_name == "time":
            xs += [1000 * r["wall_q1_s"] for r in sruns] + [1000 * r["wall_q3_s"] for r in sruns]
        xr, yr = log_range(xs, 0.08), log_range([r["err_rmse"] for r in sruns], 0.08)
        panel = Panel(k % cols, k // cols, rows, size, xr, yr)
        stairs = staircase(fr, cost, xr)
        script += panel_data(k, sruns, cost_name, fr, stairs)
        script += panel_script(panel, scene, sruns, cost_name, fr, stairs) + (shared if k == 0 else [])
        script.append(plot_commands(k, cost_name))
    script.append("unset multiplot")
    if subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True).returncode != 0:
        print("plot: gnuplot failed drawing %s (its message is above)" % path, file=sys.stderr)
        sys.exit(1)


# ---- Tables: Markdown (printed, for docs/benchmarks.md) and HTML (index.html) ----

def wall_text(r, low="wall_q1_s", high="wall_q3_s"):
    """The median wall time in ms, and its spread: quartiles, or other columns."""
    if r["wall_runs"] < 2:
        return "%.2f" % (1000 * r["wall_s"])
    return "%.2f (%.2f–%.2f)" % (1000 * r["wall_s"], 1000 * r[low], 1000 * r[high])


def config_text(r):
    return r["configuration"].replace(";number_format=float32", "").replace(";", ", ")


def pareto_table(rows, cost_name):
    """Markdown: per family and scene, the runs on the Pareto front against the cost."""
    out = ["| family | scene | configuration | wall time (ms): median (quartiles) | cycles | operations | RMSE | "
           "PSNR (dB) |",
           "|---|---|---|---|---|---|---|---|"]
    for family in sorted(set(r["family"] for r in rows)):
        runs = [r for r in rows if r["family"] == family]
        for scene in sorted(set(r["scene"] for r in runs)):
            for p in front([r for r in runs if r["scene"] == scene], COST[cost_name]):
                out.append("| %s | %s | %s | %s | %d | %d | %.2e | %.1f |" % (
                    family, short(scene), config_text(p), wall_text(p), p["frame_cycles"], p["ops"],
                    p["err_rmse"], p["err_psnr"]))
    return "\n".join(out)


def html_runs(runs, costs):
    """HTML table of a family's runs, per scene from the most exact, with the costs each
    is Pareto-optimal in; the runs optimal in none are greyed."""
    fronts = {c: set(id(r) for s in set(r["scene"] for r in runs)
                     for r in front([q for q in runs if q["scene"] == s], COST[c])) for c in costs}
    head = ["scene", "label", "configuration", "wall time (ms): median (quartiles)", "min–max", "cycles",
            "operations", "bytes read", "RMSE", "PSNR (dB)", "Pareto-optimal against"]
    out = ["<table><tr>%s</tr>" % "".join("<th>%s</th>" % h for h in head)]
    for r in sorted(runs, key=lambda r: (r["scene"], r["err_rmse"])):
        on = [c for c in costs if id(r) in fronts[c]]
        cells = [short(r["scene"]), r["label"], config_text(r), wall_text(r),
                 "%.2f–%.2f" % (1000 * r["wall_min_s"], 1000 * r["wall_max_s"]), "%d" % r["frame_cycles"],
                 "%d" % r["ops"], "%d" % r["bytes"], "%.2e" % r["err_rmse"], "%.1f" % r["err_psnr"], ", ".join(on)]
        out.append("<tr%s>%s</tr>" % ("" if on else ' class="dominated"',
                                       "".join("<td>%s</td>" % html.escape(c) for c in cells)))
    return "\n".join(out + ["</table>"])


def html_page(rows, plots, path, source):
    """One page, no network: the PNGs inline as data URIs, so it can be mailed or moved alone."""
    style = ("body{font-family:sans-serif;margin:2em;max-width:1400px} img{max-width:100%;border:1px solid #ddd}"
             "table{border-collapse:collapse;font-size:13px;margin:1em 0} td,th{border:1px solid #ccc;padding:2px 6px}"
             "th{background:#eee} tr.dominated td{color:#999} nav a{margin-right:1em}")
    families = sorted(set(r["family"] for r in rows))
    repeats = sorted(set(r["wall_runs"] for r in rows))
    out = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>sweep</title><style>%s</style></head><body>"
           % style, "<h1>Sweep: error against cost</h1>",
           "<p>%s: %d runs; wall time the median of %s runs of each, with its quartiles (the bars of the plots) "
           "and extremes. Cycles, operations and "
           "bytes are the model's counts (no noise). Operations: add, mul, div, sqrt, rsqrt, lut and fetch, each "
           "counted once. Bytes: the 64-byte lines the texture units read (a line buffer per pixel, no cache, "
           "ideal memory); the normal family reads no texels and the parallax tracer's reads are counted only "
           "under the DRAM model, so neither has that plot. Rows greyed: Pareto-optimal against no cost.</p>" % (
               html.escape(source), len(rows), " or ".join(str(n) for n in repeats)),
           "<nav>%s</nav>" % "".join("<a href='#%s'>%s</a>" % (f, f) for f in families)]
    for family in families:
        out.append("<h2 id='%s'>%s</h2>" % (family, family))
        for cost_name, png in plots[family]:
            with open(png, "rb") as f:
                data = base64.b64encode(f.read()).decode()
            out.append("<h3>against %s</h3><img alt='%s: error against %s' src='data:image/png;base64,%s'>" % (
                AXIS[cost_name], family, AXIS[cost_name], data))
        out.append("<h3>runs</h3>")
        out.append(html_runs([r for r in rows if r["family"] == family], [c for c, _ in plots[family]]))
    out.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 3:
        fail("usage: scripts/plot.py SWEEP_CSV OUT_DIR")
    source, out_dir = sys.argv[1], sys.argv[2]
    rows = load(source)
    if not shutil.which("gnuplot"):
        fail("no gnuplot on the PATH (scripts/setup.sh gnuplot-nox installs it)")
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as e:
        fail("%s: the plots' folder cannot be made: %s" % (out_dir, e.strerror or e))
    plots = {}
    for family in sorted(set(r["family"] for r in rows)):
        runs = [r for r in rows if r["family"] == family]
        plots[family] = []
        for cost_name, axis, cost in COSTS:
            if not all(cost(r) > 0 for r in runs):  # bytes: the families whose units read no texels
                continue
            png = os.path.join(out_dir, "%s-%s.png" % (family, cost_name))
            figure(family, runs, cost_name, axis, png)
            plots[family].append((cost_name, png))
    html_page(rows, plots, os.path.join(out_dir, "index.html"), source)
    print("Pareto-optimal configurations per scene, against wall time:\n")
    print(pareto_table(rows, "time"))
    print("\nAgainst simulated cycles:\n")
    print(pareto_table(rows, "cycles"))
    print("\n%s: every plot and every run" % os.path.join(out_dir, "index.html"), file=sys.stderr)


if __name__ == "__main__":  # (importable: the scripts test reads its labels)
    main()
