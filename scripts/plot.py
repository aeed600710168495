#!/usr/bin/env python3
"""Plots of out/sweep/sweep.csv (docs/benchmarks.md): per block family, the colour error
(RMSE against the golden model) against wall time and against simulated cycles, one
series per scene, each scene's Pareto front drawn as a line; and a Markdown table of
the Pareto-optimal configurations per scene (printed).

Usage: scripts/plot.py SWEEP_CSV OUT_DIR"""
import csv
import os
import subprocess
import sys

CSV, OUT = sys.argv[1], sys.argv[2]
os.makedirs(OUT, exist_ok=True)
with open(CSV) as f:
    rows = list(csv.DictReader(f))
for r in rows:
    r["wall_s"], r["frame_cycles"] = float(r["wall_s"]), float(r["frame_cycles"])
    r["err_rmse"] = float(r["err_rmse"])
    r["err_psnr"] = float(r["err_psnr"]) if r["err_psnr"] not in ("inf", "nan") else float("inf")


def pareto(points, cost):
    """The runs no other run beats in both cost and error (lower is better in both)."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[cost], p["err_rmse"])):
        if p["err_rmse"] < best:
            front.append(p)
            best = p["err_rmse"]
    return front


def short(scene):
    return scene.replace("golden/", "").replace("/scene.json", "").replace("scenes/", "").replace(".json", "")


families = sorted(set(r["family"] for r in rows))
table = []
for family in families:
    runs = [r for r in rows if r["family"] == family]
    scenes = sorted(set(r["scene"] for r in runs))
    for cost, label, unit in [("wall_s", "time", "wall time (s)"), ("frame_cycles", "cycles", "simulated cycles")]:
        plot = []
        for k, scene in enumerate(scenes):
            pts = [r for r in runs if r["scene"] == scene]
            data = os.path.join(OUT, "%s-%s-%d.dat" % (family, label, k))
            with open(data, "w") as f:
                for p in pts:
                    f.write("%g %g\n" % (p[cost], max(p["err_rmse"], 1e-9)))
                f.write("\n\n")
                for p in pareto(pts, cost):
                    f.write("%g %g\n" % (p[cost], max(p["err_rmse"], 1e-9)))
            plot.append("'%s' index 0 with points pt 7 ps 0.8 lc %d title '%s'" % (data, k + 1, short(scene)))
            plot.append("'%s' index 1 with lines lw 2 lc %d notitle" % (data, k + 1))
        script = "\n".join([
            "set terminal png size 900,600 noenhanced",
            "set output '%s'" % os.path.join(OUT, "%s-%s.png" % (family, label)),
            "set logscale xy", "set grid",
            "set title '%s: colour RMSE against %s (lines: Pareto fronts)'" % (family, unit),
            "set xlabel '%s'" % unit, "set ylabel 'RMSE against the golden model'",
            "set key outside right", "plot " + ", ".join(plot)])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    for scene in scenes:
        for p in pareto([r for r in runs if r["scene"] == scene], "wall_s"):
            table.append((family, short(scene), p))

print("| family | scene | configuration | wall time (ms) | cycles | RMSE | PSNR (dB) |")
print("|---|---|---|---|---|---|---|")
for family, scene, p in table:
    config = p["configuration"].replace(";number_format=float32", "").replace(";", ", ")
    print("| %s | %s | %s | %.2f | %d | %.2e | %.1f |" % (family, scene, config, 1000 * p["wall_s"],
                                                       p["frame_cycles"], p["err_rmse"], p["err_psnr"]))
