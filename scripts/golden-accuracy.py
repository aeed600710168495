#!/usr/bin/env python3
"""Every golden scene's configurations against the golden model, under the headline
metric (R, G, B over the pixels covered in either frame) and the frame-wide one, with the
gate golden/<scene>/golden.json sets and the margin to it; then the configurations whose
PSNR moved most from the metric before (R, G, B and A over the whole frame, rebuilt from
the frame-wide R, G, B and A figures). Exit 1 when a gate fails.

Usage: scripts/golden-accuracy.py SHADETLM ROOT WORKDIR"""
import json
import math
import os
import subprocess
import sys


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("golden-accuracy: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) != 4:
    fail("usage: scripts/golden-accuracy.py SHADETLM ROOT WORKDIR")
BIN, ROOT, WORK = sys.argv[1:4]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "golden")):
    fail("%s: not the checkout (it has no golden/)" % ROOT)
if not os.path.isdir(WORK):
    fail("%s: no such folder (the frames' and stats' scratch folder)" % WORK)


def figure(x):
    return float(x)  # "inf" and "nan" come as strings


def db(x):
    return "∞" if math.isinf(x) else "%.1f" % x


def old_psnr(err):
    """R, G, B and A over the whole frame: the metric every figure used before."""
    mse = (3 * figure(err["rgb"]["frame"]["rmse"]) ** 2 + figure(err["a"]["frame"]["rmse"]) ** 2) / 4
    return math.inf if mse == 0 else 10 * math.log10(1 / mse)


rows, failed = [], []
for scene in sorted(os.listdir(os.path.join(ROOT, "golden"))):
    spec_path = os.path.join(ROOT, "golden", scene, "golden.json")
    if not os.path.isfile(spec_path):
        continue
    spec = json.load(open(spec_path))
    configs = [("default", [], spec["accuracy"])] + [(n, c["set"], c["accuracy"]) for n, c in spec.get("configurations", {}).items()]
    for name, sets, gate in configs:
        stats = os.path.join(WORK, "%s.%s.json" % (scene, name))
        cmd = [BIN, "render", os.path.join(ROOT, "golden", scene, "scene.json"), "--engine", "loop", "--compare-reference",
               "-o", os.path.join(WORK, "%s.%s.exr" % (scene, name)), "--stats", stats]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        err = json.load(open(stats))["error"]
        rgb = err["rgb"]
        psnr, mx = figure(rgb["psnr"]), figure(rgb["max"])
        if "rgb_min_psnr" in gate:
            bar, ok, margin = "PSNR ≥ %g" % gate["rgb_min_psnr"], psnr >= gate["rgb_min_psnr"], "%+.1f dB" % (psnr - gate["rgb_min_psnr"])
        else:
            # rgb_max holds for every pixel of the frame (testbenches/test_golden.cpp)
            frame_max = figure(rgb["frame"]["max"])
            bar, ok, margin = "max ≤ %.3g" % gate["rgb_max"], frame_max <= gate["rgb_max"], "×%.2g" % (frame_max / gate["rgb_max"])
        if not ok:
            failed.append("%s/%s" % (scene, name))
        truth = ", ".join("%s: %s" % kv for kv in sorted(err["truth"].items())) or "shading model"
        rows.append((scene, name, truth, rgb["pixels"], err["coverage"]["differ"], mx, psnr, figure(rgb["frame"]["psnr"]),
                     old_psnr(err), bar, margin, ok))

print("| scene | configuration | truth | covered pixels | covered in one only | max | PSNR (covered, RGB) | PSNR (frame, RGB) | gate | margin |")
print("|---|---|---|---:|---:|---:|---:|---:|---|---:|")
for r in rows:
    print("| %s | %s | %s | %d | %d | %.3g | %s | %s | %s | %s%s |" % (r[0], r[1], r[2], r[3], r[4], r[5], db(r[6]), db(r[7]),
                                                                  r[9], r[10], "" if r[11] else " **FAILS**"))
print()
moved = sorted((r for r in rows if math.isfinite(r[6]) and math.isfinite(r[8])), key=lambda r: r[6] - r[8])[:10]
print("| scene | configuration | PSNR before (frame, RGBA) | PSNR now (covered, RGB) | change |")
print("|---|---|---:|---:|---:|")
for r in moved:
    print("| %s | %s | %s | %s | %+.1f dB |" % (r[0], r[1], db(r[8]), db(r[6]), r[6] - r[8]))
if failed:
    sys.exit("gates failing: " + ", ".join(failed))
