#!/usr/bin/env python3
"""Golden-image regression with a report (docs/regression.md): every golden scene under
each of its configurations (golden/<scene>/golden.json) through the SystemC pipeline,
compared per layer with the accepted frame and per block with the accepted cycles, and
against the golden model; writes OUT/index.html: a summary line, failures first (red, each
with the REGEN_GOLDEN=1 command that accepts it), per scene and configuration new (hover or
click: the reference in its place) | reference | |diff|x16 | error heat map with its colour
bar, and the figures.

Usage: scripts/regress.py SHADETLM ROOT OUT [--scene NAME ...]
       scripts/regress.py SHADETLM ROOT OUT --shard I/N [--scene NAME ...]
       scripts/regress.py SHADETLM ROOT OUT --merge
       scripts/regress.py SHADETLM ROOT OUT --list [--scene NAME ...]   the number of configurations
REGEN_GOLDEN=1 rewrites the frames and stats that fail or are missing (never under CI).
--shard I/N measures every N-th configuration from the I-th into OUT/shards/regress-I-of-N.json
(a Slurm array task of scripts/slurm.py, which writes OUT/manifest.json with N); --merge
writes the report (and does what REGEN asks) from all N shards, once all are there (else
it exits 2 naming the missing ones). OUT/rows.json holds every row the report shows.
Exit 0 when every configuration passes, 1 when one fails (a render that fails is a failing
row), 2 with one line on stderr naming it and nothing written: a bad option, a missing
program, checkout or scene, a golden.json or shard that cannot be read."""
import argparse
import html
import json
import math
import os
import shutil
import subprocess
import sys

import shards


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2 (no usage block)
        shards.fail(message)


parser = Parser(description="golden-image regression: see the module's docstring")
parser.add_argument("bin")
parser.add_argument("root")
parser.add_argument("out")
parser.add_argument("--scene", action="append", default=[])
parser.add_argument("--shard")
parser.add_argument("--merge", action="store_true")
parser.add_argument("--list", action="store_true", help="print the number of configurations")
ARGS = parser.parse_args()
BIN, ROOT, OUT, ONLY = ARGS.bin, ARGS.root, ARGS.out, ARGS.scene
REGEN = os.environ.get("REGEN_GOLDEN") == "1" and "CI" not in os.environ
LAYERS = [("RGB", "rgb"), ("A", "rgb"), ("Z", "z"), ("N", "n")]  # A (coverage) at the colour threshold


def run(cmd):
    try:
        return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, errors="replace")
    except OSError as e:
        shards.fail("%s: cannot run it: %s" % (BIN, e.strerror or e))


def figure(x):
    return float(x)  # non-finite figures come as the strings "inf", "-inf", "nan": float() reads them


def cycles_of(stats):
    """The timing a row accepts: the frame's cycles, and per block its busy cycles and its
    last hand-over (a latency that the frame's end hides still moves the block's last)."""
    return {"frame_cycles": stats["frame_cycles"],
            "busy_cycles": {b: v["busy_cycles"] for b, v in stats["blocks"].items()},
            "last_cycle": {b: v["last_cycle"] for b, v in stats["blocks"].items()}}


def within(now, then, tolerance):
    return abs(now - then) <= tolerance * max(1.0, abs(then))


def moved_blocks(now, then, tolerance):
    """(block, accepted, now) for every block whose busy cycles left the tolerance or that is in one only."""
    return [(b, then.get(b), now.get(b)) for b in sorted(set(now) | set(then))
            if b not in now or b not in then or not within(now[b], then[b], tolerance)]


def number(x):
    return type(x) in (int, float)


def check_spec(path, spec):
    """golden.json as measure() reads it; exits 2 naming what it lacks."""
    def gate(a):
        return isinstance(a, dict) and all(number(a[k]) for k in ("rgb_min_psnr", "rgb_max") if k in a)
    try:
        configs = spec.get("configurations", {})
        ok = gate(spec["accuracy"]) and all(number(spec["regression"][k]) for k in ("rgb", "z", "n")) and \
            number(spec["cycles"]["tolerance"]) and isinstance(configs, dict) and \
            all(isinstance(c["set"], list) and all(isinstance(x, str) for x in c["set"]) and gate(c["accuracy"])
                for c in configs.values())
    except (AttributeError, KeyError, TypeError):
        ok = False
    if not ok:
        shards.fail("%s: not a golden.json: it needs accuracy, regression (rgb, z, n), cycles.tolerance and for each "
                    "configuration set (a list) and accuracy, with numbers (docs/regression.md)" % path)


def configurations():
    """(scene, configuration, its --set list, its accuracy gate, the scene's golden.json) in
    order; exits 2 naming a golden.json that cannot be read."""
    out = []
    scenes = sorted(d for d in os.listdir(os.path.join(ROOT, "golden"))
                    if os.path.isfile(os.path.join(ROOT, "golden", d, "golden.json")))
    for scene in scenes:
        if ONLY and scene not in ONLY:
            continue
        path = os.path.join(ROOT, "golden", scene, "golden.json")
        try:
            with open(path) as f:
                spec = json.load(f)
        except (OSError, ValueError) as e:
            shards.fail("%s: cannot read it: %s" % (path, e.strerror if isinstance(e, OSError) else e))
        check_spec(path, spec)
        out.append((scene, "default", [], spec["accuracy"], spec))
        for name, c in spec.get("configurations", {}).items():
            out.append((scene, name, c["set"], c["accuracy"], spec))
    return out


def accepted_paths(scene, config):
    gdir = os.path.join(ROOT, "golden", scene)
    suffix = "" if config == "default" else "." + config
    return os.path.join(gdir, "frame%s.exr" % suffix), os.path.join(gdir, "stats%s.json" % suffix)


def measure(scene, config, sets, accuracy, spec):
    """One configuration rendered and judged: its row of the report (REGEN not applied)."""
    gdir = os.path.join(ROOT, "golden", scene)
    accepted, accepted_stats = accepted_paths(scene, config)
    work = os.path.join(OUT, scene, config)
    os.makedirs(work, exist_ok=True)
    new, new_stats = os.path.join(work, "new.exr"), os.path.join(work, "stats.json")
    cmd = [BIN, "render", os.path.join(gdir, "scene.json"), "-o", new, "--stats", new_stats, "--compare-reference"]
    for s in sets:
        cmd += ["--set", s]
    if not os.path.exists(accepted):  # compare draws no images then: the report still shows the new frame
        cmd += ["--preview", os.path.join(work, "img-new.png")]
    r = run(cmd)
    # Accuracy problems stay failures whatever REGEN does: it cannot fix them.
    row = {"scene": scene, "config": config, "sets": sets, "problems": [], "accuracy_problems": [], "layers": {},
           "tolerance": spec["regression"], "files": []}
    if r.returncode != 0:
        row["accuracy_problems"].append("render failed: " + r.stderr.strip())
        return row
    try:
        with open(new_stats) as f:
            stats = json.load(f)
        # Accuracy against the golden model.
        err = stats["error"]["rgb"]
        row["accuracy"] = {"max": figure(err["max"]), "frame_max": figure(err["frame"]["max"]),
                           "psnr": figure(err["psnr"]), "pixels": int(err["pixels"]),
                           "truth": dict(stats["error"]["truth"]), "gate": accuracy}
        now = cycles_of(stats)
        if not number(now["frame_cycles"]) or not all(number(v) for v in now["busy_cycles"].values()):
            raise TypeError("cycles that are not numbers")
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        row.pop("accuracy", None)
        row["accuracy_problems"].append("render failed: its stats cannot be read (%s: %s): is %s this checkout's "
                                        "shadetlm?" % (type(e).__name__, e, BIN))
        return row
    # Written so that NaN fails.
    if "rgb_min_psnr" in accuracy and not figure(err["psnr"]) >= accuracy["rgb_min_psnr"]:
        row["accuracy_problems"].append("accuracy: PSNR %.1f dB below %.1f" % (figure(err["psnr"]), accuracy["rgb_min_psnr"]))
    # rgb_max holds for every pixel of the frame (as testbenches/test_golden.cpp checks).
    if "rgb_max" in accuracy and not figure(err["frame"]["max"]) <= accuracy["rgb_max"]:
        row["accuracy_problems"].append("accuracy: max error %.3g over %.3g" % (figure(err["frame"]["max"]), accuracy["rgb_max"]))
    # Regression per layer against the accepted frame.
    frame_ok = os.path.exists(accepted)
    if not frame_ok:
        row["problems"].append("no accepted frame " + os.path.relpath(accepted, ROOT))
    else:
        for layer, key in LAYERS:
            args = [BIN, "compare", new, accepted, "--layer", layer, "--fail", str(spec["regression"][key]), "--json"]
            if layer == "RGB":
                args += ["--images", os.path.join(work, "img")]
            c = run(args)
            try:
                result = json.loads(c.stdout)
            except ValueError:
                result = {"problem": c.stderr.strip() or "compare failed"}
            if layer not in result.get("layers", {}):  # another resolution, a channel missing, unreadable
                frame_ok = False
                row["problems"].append("%s: %s" % (layer, result.get("problem", "not comparable")))
                continue
            m = result["layers"][layer]
            row["layers"][layer] = m
            if not m["pass"]:
                frame_ok = False
                row["problems"].append("%s: %.3g %% of the frame's pixels over %g (largest: %.3g)" % (
                    layer, m["over_percent"], spec["regression"][key], figure(m["frame"]["max"])))
    # Cycles against the accepted stats (unreadable ones fail the row, and REGEN_GOLDEN=1 rewrites them).
    row["cycles"] = {"now": now["frame_cycles"], "then": None, "tolerance": spec["cycles"]["tolerance"], "moved": []}
    cycles_ok = os.path.exists(accepted_stats)
    if cycles_ok:
        try:
            with open(accepted_stats) as f:
                then = json.load(f)
            if not number(then["frame_cycles"]) or not all(number(v) for v in then["busy_cycles"].values()) \
                    or not all(number(v) for v in then["last_cycle"].values()):
                raise TypeError("cycles that are not numbers")
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
            cycles_ok = False
            row["problems"].append("unreadable accepted stats %s (%s: %s)" % (
                os.path.relpath(accepted_stats, ROOT), type(e).__name__, e))
    if cycles_ok:
        row["cycles"]["then"] = then["frame_cycles"]
        tol = spec["cycles"]["tolerance"]
        moved_last = moved_blocks(now["last_cycle"], then["last_cycle"], tol)
        cycles_ok = within(now["frame_cycles"], then["frame_cycles"], tol) and \
            set(now["busy_cycles"]) == set(then["busy_cycles"]) and \
            all(within(v, then["busy_cycles"][b], tol) for b, v in now["busy_cycles"].items()) and not moved_last
        row["cycles"]["moved"] = moved_blocks(now["busy_cycles"], then["busy_cycles"], tol)
        if not cycles_ok:
            row["problems"].append("cycles: %d now, %d accepted (tolerance %g)%s" % (
                now["frame_cycles"], then["frame_cycles"], tol,
                "".join("; %s's last hand-over %s now, %s accepted" % (b, n, t) for b, t, n in moved_last)))
    elif not os.path.exists(accepted_stats):
        row["problems"].append("no accepted stats " + os.path.relpath(accepted_stats, ROOT))
    # What REGEN_GOLDEN=1 rewrites for this row (the report's accept commands).
    row["files"] = [os.path.relpath(p, ROOT) for p, ok in ((accepted, frame_ok), (accepted_stats, cycles_ok)) if not ok]
    row["now_cycles"] = now
    return row


def regenerate(row):
    """REGEN_GOLDEN=1: the row's failing frame or cycles accepted, unless it fails its
    accuracy gate (docs/regression.md)."""
    if not (REGEN and row["files"] and not row["accuracy_problems"]):
        return
    accepted, accepted_stats = accepted_paths(row["scene"], row["config"])
    for path in row["files"]:
        if path == os.path.relpath(accepted, ROOT):
            shutil.copyfile(os.path.join(OUT, row["scene"], row["config"], "new.exr"), accepted)
        else:
            with open(accepted_stats, "w") as f:
                json.dump(row["now_cycles"], f, indent=2)
                f.write("\n")
    changed.append("%s/%s: %s" % (row["scene"], row["config"], "; ".join(row["problems"])))
    row["problems"] = ["rewritten (REGEN_GOLDEN=1): " + p for p in row["problems"]]
    row["regenerated"] = True


def tell(row):
    status = {"fail": "FAIL"}.get(state(row), state(row))
    shown = [p.splitlines()[0] if p else p for p in row["accuracy_problems"] + row["problems"]]  # the report has the rest
    print("%-16s %-20s %s%s" % (row["scene"], row["config"], status, "" if not shown else ": " + "; ".join(shown)),
          file=sys.stderr)


def failing(r):
    return bool(r["accuracy_problems"]) or (bool(r["problems"]) and not r.get("regenerated"))


def state(r):
    return "fail" if failing(r) else "rewritten" if r.get("regenerated") else "ok"


def read_shard(path):
    """A shard's rows (measure's); exits 2 naming a shard that is not one."""
    try:
        with open(path) as f:
            measured = json.load(f)
    except (OSError, ValueError) as e:
        shards.fail("%s: cannot read the shard: %s" % (path, e.strerror if isinstance(e, OSError) else e))
    kinds = {"scene": str, "config": str, "sets": list, "problems": list, "accuracy_problems": list, "files": list,
             "layers": dict, "tolerance": dict}
    if not isinstance(measured, list) or not all(isinstance(r, dict) and all(isinstance(r.get(k), t) for k, t in kinds.items())
                                                 for r in measured):
        shards.fail("%s: not a shard of regress.py: a list of rows with %s" % (path, ", ".join(kinds)))
    return measured


rows, changed = [], []
if sum(map(bool, (ARGS.shard, ARGS.merge, ARGS.list))) > 1:
    parser.error("--shard, --merge and --list exclude each other")
if not os.path.isdir(os.path.join(ROOT, "golden")):
    shards.fail("%s: not the checkout (it has no golden/)" % ROOT)
unknown = [s for s in ONLY if not os.path.isfile(os.path.join(ROOT, "golden", s, "golden.json"))]
if unknown:
    shards.fail("no golden scene named %s (golden/<scene>/golden.json)" % ", ".join(unknown))
if ARGS.list:
    print(len(configurations()))
    sys.exit(0)
if ARGS.shard:
    shard, count = shards.parse(ARGS.shard)
if not ARGS.merge:  # the runs need the program, and a folder for the report
    if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
        shards.fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
    run([BIN, "--version"])  # exits 2 when it cannot be run at all, before anything is made
    todo = configurations()
    if os.path.exists(OUT) and not os.path.isdir(OUT):
        shards.fail("%s: not a folder (the report's)" % OUT)
    try:
        os.makedirs(OUT, exist_ok=True)
    except OSError as e:
        shards.fail("%s: the report's folder cannot be made: %s" % (OUT, e.strerror or e))
if ARGS.shard:
    measured = [measure(*c) for c in shards.mine(todo, shard, count)]
    shards.write_atomically(shards.shard_path(OUT, "regress", shard, count, "json"), json.dumps(measured))
    sys.exit(0)
if ARGS.merge:
    if shards.manifest(OUT)["kind"] != "regress":
        shards.fail("%s holds a sweep, not a regression" % OUT)
    for path in shards.collect(OUT, "regress", "json"):
        rows += read_shard(path)
    order = {(c[0], c[1]): k for k, c in enumerate(configurations())}  # a local run's order
    rows.sort(key=lambda r: order.get((r["scene"], r["config"]), len(order)))
    for r in rows:
        regenerate(r)
        tell(r)
else:
    for c in todo:
        rows.append(measure(*c))
        regenerate(rows[-1])
        tell(rows[-1])

if ONLY and not rows:
    shards.fail("no golden scene named " + ", ".join(ONLY))
# The report (docs/regression.md, "The report"): failures first, then rewritten rows, then the
# rest, each scene's configurations in golden.json's order.
failed = [r for r in rows if failing(r)]
rows.sort(key=lambda r: (["fail", "rewritten", "ok"].index(state(r)), r["scene"]))
esc = html.escape


def fig(x):
    """A figure as core::figure prints it: 4 significant digits, integers whole, ∞ for infinity."""
    if isinstance(x, int):
        return str(x)
    x = figure(x)
    return "nan" if math.isnan(x) else ("∞" if x > 0 else "−∞") if math.isinf(x) else "%.4g" % x


def db(x):
    # PSNR to 0.1 dB: the gates are whole dB and docs' tables print one decimal; 4 significant
    # digits would put 130.0 beside 42.53 in one column.
    x = figure(x)
    return fig(x) if not math.isfinite(x) else "%.1f" % x


# The heat map's ramp, as src/shadetlm/core/compare.cpp (add_comparison_images) draws it: these colours at
# 1e-6, 1e-5, …, 1e-1, linear in log10 of the error between them; red above 1e-1 (and for
# non-finite differences); black below 1e-6 unless the pixel is over the colour tolerance.
RAMP = ["#000080", "#0000ff", "#00ffff", "#00ff00", "#ffff00", "#ff0000"]


def at_scale(error):
    """Where an error sits on the colour bar, in % of its length."""
    return (math.log10(error) + 6) * 20


def decade(d):
    return "%s10<sup>−%d</sup>" % ("≥" if d == 1 else "", d)


def legend(marks=(), labels=range(6, 0, -1)):
    """The colour bar: a black swatch for < 1e-6, the gradient with a tick per decade (labelled
    when in `labels`: a narrow bar has room for fewer), and a dashed mark per colour tolerance."""
    stops = ", ".join("%s %.4g%%" % (c, at_scale(10.0 ** d)) for c, d in zip(RAMP, range(-6, 0)))
    ticks = "".join('<span style="left:%.4g%%">%s</span>' % (at_scale(10.0 ** -d), decade(d) if d in labels else "")
                    for d in range(6, 0, -1))
    lines = "".join('<i style="left:%.1f%%" title="colour tolerance %s"></i>' % (at_scale(m), fig(m))
                    for m in marks if 1e-6 <= m <= 1e-1)
    return ('<div class="legend"><div class="zero"><b></b><span>&lt;10<sup>−6</sup></span></div>'
            '<div class="scale"><div class="bar" style="background:linear-gradient(to right, %s)">%s</div>'
            '<div class="ticks">%s</div></div></div>' % (stops, lines, ticks))


def image(r, kind):
    """The PNG's path relative to the report, or None when it was not drawn."""
    path = "%s/%s/img-%s.png" % (r["scene"], r["config"], kind)
    return path if os.path.exists(os.path.join(OUT, path)) else None


def picture(r, kind):
    path = image(r, kind)
    return '<div class="pic">%s</div>' % ('<img src="%s" alt="%s">' % (esc(path), kind) if path else
                                           "<p>— (none accepted)</p>" if kind == "reference" and r["files"] else "<p>—</p>")


def flip(r):
    """The new frame; hover shows the reference in its place, a click keeps it there (pure CSS)."""
    new, ref = image(r, "new"), image(r, "reference")
    if not (new and ref):
        return picture(r, "new")
    return ('<label class="pic flip" title="hover or click: the reference in its place"><input type="checkbox">'
            '<img class="new" src="%s" alt="new"><img class="ref" src="%s" alt="reference">'
            '<span class="new">new</span><span class="ref">reference</span></label>' % (esc(new), esc(ref)))


def layer_table(r):
    head = "<tr><th>layer</th><th>tolerance</th><th>max</th><th>at (x, y)</th><th>PSNR dB</th><th>over</th></tr>"
    lines = []
    for layer, key in LAYERS:
        m = r["layers"].get(layer)
        if m:
            at = "—" if m["max_at"][0] < 0 else "%d, %d" % tuple(m["max_at"])
            lines.append('<tr%s><th>%s</th><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s %%</td></tr>' % (
                "" if m["pass"] else ' class="bad"', layer, fig(r["tolerance"][key]), fig(m["max"]), at,
                db(m["psnr"]), fig(m["over_percent"])))
    return '<table class="layers">%s%s</table>' % (head, "".join(lines)) if lines else ""


def line(title, text, bad, why=""):
    return '<tr class="%s" title="%s"><th>%s</th><td>%s</td></tr>' % ("bad" if bad else "", esc(why), title, text)


def accuracy_line(r):
    a = r.get("accuracy")
    if not a:
        return ""
    g = a["gate"]
    high = "max %s" % fig(a["max"])
    if "rgb_max" in g:  # the gate holds for the whole frame's max: named when it is not the covered pixels'
        high += ("" if a["frame_max"] == a["max"] else ", frame max %s" % fig(a["frame_max"])) + \
            " (gate ≤ %s)" % fig(g["rgb_max"])
    psnr = "PSNR %s dB" % db(a["psnr"]) + (" (gate ≥ %s dB)" % fig(g["rgb_min_psnr"]) if "rgb_min_psnr" in g else "")
    truth = ", ".join("%s: %s" % kv for kv in sorted(a["truth"].items())) or "shading model"
    text = "%s, %s<br><small>RGB over %d covered pixels; truth: %s</small>" % (high, psnr, a["pixels"], esc(truth))
    return line("golden model", text, bool(r["accuracy_problems"]), g.get("why", ""))


def cycles_line(r):
    c = r.get("cycles")
    if not c:
        return ""
    if c["then"] is None:
        return line("cycles", "%d now, none accepted" % c["now"], True)
    change = 100.0 * (c["now"] - c["then"]) / max(1, c["then"])
    moved = ", ".join("%s %s → %s" % (esc(b), "—" if t is None else t, "—" if n is None else n) for b, t, n in c["moved"])
    text = "%d accepted → %d (%s %%; tolerance %s %%)%s" % (
        c["then"], c["now"], "%+.4g" % change, fig(100 * c["tolerance"]), "<br>out of tolerance: " + moved if moved else "")
    return line("cycles", text, bool(moved) or not within(c["now"], c["then"], c["tolerance"]))


def accept_command(scenes):
    return "REGEN_GOLDEN=1 scripts/regress.sh --no-build" + "".join(" --scene " + s for s in scenes)


def command(cmd):
    return '<div class="cmd"><code>%s</code><button type="button" onclick="copy(this)">copy</button></div>' % esc(cmd)


def files(paths):
    return ", ".join("<code>%s</code>" % esc(p) for p in paths)


def accept(r):
    """How to accept a failing row: REGEN_GOLDEN=1 runs a whole scene (regress.sh has no
    per-configuration option), so it says what else in the scene it rewrites."""
    out = []
    if r["files"]:
        others = [o for o in rows if o is not r and o["scene"] == r["scene"] and failing(o) and o["files"]]
        also = ", and for the scene's other failing configurations " + "; ".join(
            "%s (%s)" % (files(o["files"]), esc(o["config"])) for o in others) if others else \
            "; nothing else, the scene's other configurations pass"
        out.append("<p><b>Accept this change</b>: runs every configuration of %s and rewrites what fails or is "
                   "missing: this row's %s%s.</p>%s" % (esc(r["scene"]), files(r["files"]), also,
                                                        command(accept_command([r["scene"]]))))
    if "accuracy" not in r:
        out.append("<p>The render failed: nothing to accept.</p>")
    elif r["accuracy_problems"]:
        out.append("<p>REGEN_GOLDEN=1 cannot make this row pass: it fails its accuracy gate against the golden model "
                   "(<code>golden/%s/golden.json</code>). Fix the change, or move the gate with its why.</p>" % esc(r["scene"]))
    return '<div class="accept">%s</div>' % "".join(out)


def row_html(r):
    st = state(r)
    name = '<div class="name" id="%s"><b>%s</b><br>%s<br><span class="badge">%s</span>%s</div>' % (
        esc(r["scene"] + "/" + r["config"]), esc(r["scene"]), esc(r["config"]), {"fail": "FAIL"}.get(st, st),
        "".join("<br><code>%s</code>" % esc(s).replace(".", ".<wbr>") for s in r["sets"]))
    images = flip(r) + picture(r, "reference") + picture(r, "diff") + picture(r, "heat")
    figs = '<div class="figs">%s<table class="more">%s%s</table></div>' % (layer_table(r), accuracy_line(r), cycles_line(r))
    problems = r["accuracy_problems"] + r["problems"]
    notes = '<ul class="problems">%s</ul>' % "".join("<li>%s</li>" % esc(p) for p in problems) if problems else ""
    return '<section class="row %s">%s%s%s%s%s</section>' % (
        st, name, images, figs, notes, accept(r) if st == "fail" else "")


def summary():
    rewritten = sum(r.get("regenerated", False) for r in rows)
    head = '<p class="summary %s">%d configurations, %d failing%s</p>' % (
        "fail" if failed else "ok", len(rows), len(failed), ", %d rewritten by REGEN_GOLDEN=1" % rewritten if rewritten else "")
    if not failed:
        return head
    links = ", ".join('<a href="#%s/%s">%s/%s</a>' % ((esc(r["scene"]), esc(r["config"])) * 2) for r in failed)
    scenes = sorted({r["scene"] for r in failed if r["files"]})
    stuck = ", ".join("%s/%s" % (esc(r["scene"]), esc(r["config"])) for r in failed if r["accuracy_problems"])
    every = ("<p><b>Accept every change</b> (from the checkout's root; rewrites only what fails or is missing: the "
             "files each row below names; ignored when CI is set):</p>%s" % command(accept_command(scenes))) if scenes else ""
    if stuck:
        every += "<p>REGEN_GOLDEN=1 cannot make these pass, their render or accuracy gate fails: %s.</p>" % stuck
    return head + "<p>Failing: %s</p>%s" % (links, every)


def key():
    tolerances = sorted({r["tolerance"]["rgb"] for r in rows if "tolerance" in r})
    return ('<div class="key"><div><b>error heat map</b>: per pixel the largest |new − reference| of R, G and B, '
            'log scale; dashed: the colour tolerance (%s).%s</div>'
            '<div><b>|diff| ×16</b>: R, G and B each |new − reference| × 16, so 1/16 and more is full.<br>'
            '<b>new</b>: hover or click to see the reference in its place.</div></div>' % (
                ", ".join(fig(t) for t in tolerances) or "none", legend(tolerances)))


STYLE = """
body{font:14px/1.4 system-ui,sans-serif;margin:0 16px 32px;color:#222}
h1{font-size:22px;margin:16px 0 8px}
a{color:#036}
code{font:12px ui-monospace,monospace;background:#f3f3f3;padding:0 2px;overflow-wrap:anywhere}
.summary{font-size:18px;font-weight:600;padding:8px 12px;margin:8px 0}
.summary.fail{background:#fde8e8;color:#a00;border-left:8px solid #c00}
.summary.ok{background:#e6f4e8;color:#060;border-left:8px solid #2a2}
.cmd{display:flex;gap:8px;align-items:center;margin:4px 0}
.cmd code{display:block;user-select:all;font-size:13px;padding:6px 10px;background:#222;color:#fff;border-radius:3px}
.cmd button{font:12px system-ui,sans-serif;padding:3px 8px;cursor:pointer}
.key{display:grid;grid-template-columns:minmax(20rem,1fr) minmax(20rem,1fr);gap:8px 24px;margin:12px 0;color:#444}
.legend{display:flex;gap:6px;font-size:11px;margin-top:4px}
.zero b{display:block;width:16px;height:14px;background:#000}
.scale{flex:1;padding:0 14px}
.bar{position:relative;height:14px}
.bar i{position:absolute;top:-3px;bottom:-3px;border-left:2px dashed #fff;outline:1px solid #0006}
.ticks{position:relative;height:1.5em}
.ticks span{position:absolute;transform:translateX(-50%);white-space:nowrap;padding-top:3px}
.ticks span::before{content:"";position:absolute;left:50%;top:0;height:3px;border-left:1px solid #444}
.row{display:grid;grid-template-columns:9rem repeat(4,minmax(6rem,16rem)) minmax(26rem,1fr);gap:6px 10px;
     padding:8px;border-bottom:1px solid #ddd;align-items:start}
.row.head{position:sticky;top:0;z-index:1;background:#fff;font-weight:600;border-bottom:2px solid #888}
.row.head .legend{font-weight:400}
.row.fail{background:#fff0f0;border:2px solid #c00;border-left-width:8px;margin:8px 0}
.row.rewritten{background:#fff8e1;border-left:8px solid #c80}
.name{scroll-margin-top:7rem}  /* a link to a row lands below the sticky header */
.name code{font-size:11px;background:none}
.badge{display:inline-block;font-weight:700;font-size:12px;padding:0 6px;border-radius:3px;background:#2a2;color:#fff}
.fail .badge{background:#c00}.rewritten .badge{background:#c80}
.pic img{display:block;width:100%;image-rendering:pixelated;background:#000}
.pic p{margin:0;color:#888}
.flip{position:relative;cursor:pointer}
.flip input,.flip .ref{display:none}
.flip:hover .new,.flip input:checked~.new{display:none}
.flip:hover .ref,.flip input:checked~.ref{display:block}
.flip span{font-size:11px;color:#555}
.flip span.ref{color:#a50;font-weight:700}
.flip img.ref{outline:3px solid #e80;outline-offset:-3px}
.figs{font-size:13px}
.more{border-collapse:collapse;margin-top:4px}
.more th{text-align:left;font-weight:400;color:#666;padding:1px 8px 1px 0;vertical-align:top;white-space:nowrap}
.more td{padding:1px 0}
.more small{color:#666}
.more tr.bad td{color:#b00;font-weight:700}
.layers{border-collapse:collapse;font-variant-numeric:tabular-nums}
.layers th,.layers td{padding:1px 8px 1px 0;text-align:right;white-space:nowrap}
.layers tr:first-child th{font-weight:400;color:#666}
.layers tr.bad{color:#b00;font-weight:700}
.problems,.accept{grid-column:1/-1;margin:0}
.problems{color:#b00;font-weight:600;padding-left:1.2em}
.rewritten .problems{color:#850}
.accept p{margin:4px 0}
@media (max-width:1000px){.row{grid-template-columns:8rem repeat(4,1fr)}.figs{grid-column:2/-1}}
"""

# A click copies a command; a file:// page may have no clipboard, so it selects it for Ctrl+C then.
SCRIPT = """function copy(b){const c=b.previousElementSibling;
const sel=()=>{getSelection().selectAllChildren(c);b.textContent="selected: Ctrl+C"};
navigator.clipboard?navigator.clipboard.writeText(c.textContent).then(()=>{b.textContent="copied"},sel):sel()}"""

HEAD = ('<div class="row head"><div>scene / configuration</div><div>new <small>(hover: reference)</small></div>'
        '<div>reference</div><div>|diff| ×16</div><div>error heat map%s</div><div>figures</div></div>')

out = ['<!doctype html><html lang="en"><meta charset="utf-8"><title>shadetlm regression</title>',
       "<style>%s</style><script>%s</script>" % (STYLE, SCRIPT),
       "<h1>shadetlm golden-image regression</h1>", summary(), key(),
       "<p>Thresholds and their reasons: golden/&lt;scene&gt;/golden.json; docs/regression.md.</p>",
       HEAD % legend(labels=(6, 4, 2))]
out += [row_html(r) for r in rows]
# Every row as the report shows it (a Slurm run's merge and a local run give the same).
shards.write_atomically(os.path.join(OUT, "rows.json"), json.dumps(rows, indent=1, sort_keys=True) + "\n")
shards.write_atomically(os.path.join(OUT, "index.html"), "\n".join(out))
print("%d configurations, %d failing; report: %s" % (len(rows), len(failed), os.path.join(OUT, "index.html")))
for c in changed:
    print("REGEN_GOLDEN rewrote " + c)
sys.exit(1 if failed else 0)
