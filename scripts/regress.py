#!/usr/bin/env python3
"""Golden-image regression with a report (docs/regression.md): every golden scene under
each of its configurations (golden/<scene>/golden.json) through the SystemC pipeline,
compared per layer with the accepted frame and per block with the accepted cycles, and
against the golden model; writes OUT/index.html (failures first) with, per scene and
configuration, new | reference | |diff|x16 | error heat map.

Usage: scripts/regress.py SHADETLM ROOT OUT [--scene NAME ...]
REGEN_GOLDEN=1 rewrites the frames and stats that fail or are missing (never under CI)."""
import html
import json
import math
import os
import shutil
import subprocess
import sys

BIN, ROOT, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
ONLY = [sys.argv[i + 1] for i, a in enumerate(sys.argv[:-1]) if a == "--scene"]
REGEN = os.environ.get("REGEN_GOLDEN") == "1" and "CI" not in os.environ
LAYERS = [("RGB", "rgb"), ("A", "rgb"), ("Z", "z"), ("N", "n")]  # A (coverage) at the colour threshold


def run(cmd):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def figure(x):
    return float(x)  # non-finite figures come as the strings "inf", "-inf", "nan": float() reads them


def cycles_of(stats):
    return {"frame_cycles": stats["frame_cycles"],
            "busy_cycles": {b: v["busy_cycles"] for b, v in stats["blocks"].items()}}


def within(now, then, tolerance):
    return abs(now - then) <= tolerance * max(1.0, abs(then))


rows, changed = [], []
scenes = sorted(d for d in os.listdir(os.path.join(ROOT, "golden"))
                if os.path.isfile(os.path.join(ROOT, "golden", d, "golden.json")))
for scene in scenes:
    if ONLY and scene not in ONLY:
        continue
    gdir = os.path.join(ROOT, "golden", scene)
    with open(os.path.join(gdir, "golden.json")) as f:
        spec = json.load(f)
    configs = [("default", [], spec["accuracy"])]
    for name, c in spec.get("configurations", {}).items():
        configs.append((name, c["set"], c["accuracy"]))
    for config, sets, accuracy in configs:
        suffix = "" if config == "default" else "." + config
        accepted, accepted_stats = os.path.join(gdir, "frame%s.exr" % suffix), os.path.join(gdir, "stats%s.json" % suffix)
        work = os.path.join(OUT, scene, config)
        os.makedirs(work, exist_ok=True)
        new, new_stats = os.path.join(work, "new.exr"), os.path.join(work, "stats.json")
        cmd = [BIN, "render", os.path.join(gdir, "scene.json"), "-o", new, "--stats", new_stats, "--compare-reference"]
        for s in sets:
            cmd += ["--set", s]
        r = run(cmd)
        # Accuracy problems stay failures whatever REGEN does: it cannot fix them.
        row = {"scene": scene, "config": config, "sets": sets, "problems": [], "accuracy_problems": [], "layers": {}}
        if r.returncode != 0:
            row["accuracy_problems"].append("render failed: " + r.stderr.strip())
            rows.append(row)
            print("%-16s %-20s FAIL: render failed" % (scene, config), file=sys.stderr)
            continue
        with open(new_stats) as f:
            stats = json.load(f)
        # Accuracy against the golden model.
        err = stats["error"]["rgb"]
        row["accuracy"] = {"max": figure(err["max"]), "psnr": figure(err["psnr"]), "pixels": err["pixels"],
                           "truth": stats["error"]["truth"], "gate": accuracy}
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
        # Cycles against the accepted stats.
        now = cycles_of(stats)
        row["cycles"] = {"now": now["frame_cycles"], "then": None}
        cycles_ok = os.path.exists(accepted_stats)
        if cycles_ok:
            with open(accepted_stats) as f:
                then = json.load(f)
            row["cycles"]["then"] = then["frame_cycles"]
            tol = spec["cycles"]["tolerance"]
            cycles_ok = within(now["frame_cycles"], then["frame_cycles"], tol) and \
                set(now["busy_cycles"]) == set(then["busy_cycles"]) and \
                all(within(v, then["busy_cycles"][b], tol) for b, v in now["busy_cycles"].items())
            if not cycles_ok:
                row["problems"].append("cycles: %d now, %d accepted (tolerance %g)" % (
                    now["frame_cycles"], then["frame_cycles"], tol))
        else:
            row["problems"].append("no accepted stats " + os.path.relpath(accepted_stats, ROOT))
        if REGEN and (not frame_ok or not cycles_ok):
            if not frame_ok:
                shutil.copyfile(new, accepted)
            if not cycles_ok:
                with open(accepted_stats, "w") as f:
                    json.dump(now, f, indent=2)
                    f.write("\n")
            changed.append("%s/%s: %s" % (scene, config, "; ".join(row["problems"])))
            row["problems"] = ["rewritten (REGEN_GOLDEN=1): " + p for p in row["problems"]]
            row["regenerated"] = True
        rows.append(row)
        status = "FAIL" if row["accuracy_problems"] or (row["problems"] and not row.get("regenerated")) else \
            "rewritten" if row.get("regenerated") else "ok"
        shown = row["accuracy_problems"] + row["problems"]
        print("%-16s %-20s %s%s" % (scene, config, status, "" if not shown else ": " + "; ".join(shown)), file=sys.stderr)

if ONLY and not rows:
    sys.exit("regress: no golden scene named " + ", ".join(ONLY))
# The report: failures first.
def failing(r):
    return bool(r["accuracy_problems"]) or (bool(r["problems"]) and not r.get("regenerated"))


failed = [r for r in rows if failing(r)]
rows.sort(key=lambda r: (not failing(r), r["scene"], r["config"]))


def img(row, kind):
    path = os.path.join(row["scene"], row["config"], "img-%s.png" % kind)
    if not os.path.exists(os.path.join(OUT, path)):
        return "<td>—</td>"
    return '<td><img src="%s" title="%s"></td>' % (html.escape(path), kind)


out = ['<!doctype html><meta charset="utf-8"><title>shadetlm regression</title>',
       "<style>body{font-family:sans-serif}td,th{padding:4px;vertical-align:top;border-bottom:1px solid #ccc}"
       "img{image-rendering:pixelated;width:256px}.fail{color:#b00}.ok{color:#070}</style>",
       "<h1>shadetlm golden-image regression</h1>",
       "<p>%d scene configurations, <b class=\"%s\">%d failing</b>. Thresholds and their reasons: "
       "golden/&lt;scene&gt;/golden.json; docs/regression.md.</p>" % (len(rows), "fail" if failed else "ok", len(failed)),
       "<table><tr><th>scene / configuration</th><th>new</th><th>reference</th><th>|diff| ×16</th><th>error heat map</th>"
       "<th>figures</th></tr>"]
for r in rows:
    status = '<b class="fail">FAIL</b>' if failing(r) else \
        ('<b>rewritten</b>' if r.get("regenerated") else '<b class="ok">ok</b>')
    figs = []
    for layer, _ in LAYERS:
        m = r["layers"].get(layer)
        if m:
            figs.append("%s: max %.3g at (%d, %d), PSNR %s dB, %.3g %% over threshold" % (
                layer, figure(m["max"]), m["max_at"][0], m["max_at"][1],
                "∞" if math.isinf(figure(m["psnr"])) else "%.1f" % figure(m["psnr"]), m["over_percent"]))
    if "accuracy" in r:
        a = r["accuracy"]
        truth = ", ".join("%s: %s" % kv for kv in sorted(a["truth"].items())) or "the shading model"
        figs.append("golden model (truth: %s): max %.3g, PSNR %.1f dB over %d covered pixels, RGB (gate: %s)" % (
            html.escape(truth), a["max"], a["psnr"], a["pixels"],
            html.escape(", ".join("%s %s" % (k, v) for k, v in a["gate"].items() if k != "why"))))
    if "cycles" in r:
        then = r["cycles"]["then"]
        figs.append("cycles: %s accepted, %s now" % ("none" if then is None else then, r["cycles"]["now"]))
    figs += ['<span class="fail">%s</span>' % html.escape(p) for p in r["accuracy_problems"] + r["problems"]]
    out.append("<tr><td>%s<br>%s<br>%s<br><small>%s</small></td>%s%s%s%s<td>%s</td></tr>" % (
        html.escape(r["scene"]), html.escape(r["config"]), status, html.escape(" ".join(r["sets"])),
        img(r, "new"), img(r, "reference"), img(r, "diff"), img(r, "heat"), "<br>".join(figs)))
out.append("</table><p>Heat map: the largest colour error per pixel, black below 1e-6, then blue (1e-5), cyan "
           "(1e-4), green (1e-3), yellow (1e-2), red (1e-1 and above).</p>")
with open(os.path.join(OUT, "index.html"), "w") as f:
    f.write("\n".join(out))
print("%d configurations, %d failing; report: %s" % (len(rows), len(failed), os.path.join(OUT, "index.html")))
for c in changed:
    print("REGEN_GOLDEN rewrote " + c)
sys.exit(1 if failed else 0)
