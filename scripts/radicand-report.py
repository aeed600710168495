#!/usr/bin/env python3
"""The normal-increments paper's radicand (seed 004) on real spans (docs/pipeline.md):
normalize's amortized operations per pixel with the radicand direct (exact mode) against
forward differences seeded at every packet and once per raster line, per scene; the
pixels each seed serves; and the span length from which forward differences win.

The counts are the block's own (stats: blocks.normalize.ops, details.seeds, .jumps and .reseeds),
which testbenches/test_normalize.cpp checks against a counting number type.

Usage: scripts/radicand-report.py SHADETLM ROOT"""
import json
import os
import shutil
import subprocess
import sys
import tempfile


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("radicand-report: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) != 3:
    fail("usage: scripts/radicand-report.py SHADETLM ROOT")
BIN, ROOT = sys.argv[1], sys.argv[2]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "scenes")):
    fail("%s: not the checkout (it has no scenes/)" % ROOT)
TMP = tempfile.mkdtemp(prefix="radicand-")
FD = "pipeline.normalize.mode=forward-difference"
MODES = [("direct", ["pipeline.normalize.mode=exact"]), ("per packet", [FD]),
         ("per line", [FD, "pipeline.normalize.seed=line"])]
# (label, scene, extra settings): the golden scenes a Phong normal reaches normalize
# on, the benchmark scene, and long spans.
SCENES = [("golden/sphere", "golden/sphere/scene.json", []),
          ("golden/torus", "golden/torus/scene.json", []),
          ("golden/knot", "golden/knot/scene.json", []),
          ("golden/point-light", "golden/point-light/scene.json", []),
          ("golden/demo", "golden/demo/scene.json", []),
          ("golden/grazing-plane", "golden/grazing-plane/scene.json", []),
          ("golden/sphere 960×720", "golden/sphere/scene.json", ["camera.resolution=[960,720]"]),
          ("benchmark 1920×1080", "scenes/bench-1080p.json", []),
          ("stress/long-spans", "scenes/stress/long-spans.json", []),
          ("stress/opposite-normals", "scenes/stress/opposite-normals.json", []),
          ("a quad behind a smaller one", os.path.join(TMP, "gaps.json"), [])]
# Hidden gaps inside a triangle's rows need an occluder narrower than the triangle: a
# small quad in front of one of a large quad's two triangles.
with open(os.path.join(TMP, "gaps.json"), "w") as f:
    json.dump({"format": 1, "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [256, 192]},
               "lights": [{"type": "point", "position": [1, 1, 2]}],
               "objects": [{"shape": "plane", "size": [0.5, 0.5], "transform": {"translate": [0.5, -0.5, 0.5]}},
                           {"shape": "plane", "size": [2, 2]}]}, f)


def normalize_stats(scene, sets):
    stats = os.path.join(TMP, "s.json")
    cmd = [BIN, "render", os.path.join(ROOT, scene), "--engine", "loop", "-o", os.path.join(TMP, "f.exr"), "--stats", stats,
           "--allow-nonfinite", "--allow-overflow"]  # counted below
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.load(open(stats))["blocks"]["normalize"]


def per_pixel(b):
    pixels = b["details"]["pixels"] - b["details"]["direct_pixels"]  # the Phong pixels (bump pixels go direct in every mode)
    ops = b["ops"]
    return pixels, ops["mul"] / pixels, ops["add"] / pixels, (ops["sqrt"] + ops["div"] + ops["rsqrt"]) / pixels


print("| scene | pixels | pixels a packet | pixels a line seed (jumps, re-seeds) | mul / px: direct, per packet, per line "
      "| add / px: direct, per packet, per line | roots / px: direct, per packet, per line | non-finite normals: direct, per packet, per line |")
print("|---|---:|---:|---:|---|---|---|---|")
samples = []  # (pixels, seeds, direct ops, per-packet ops) per scene
for label, scene, sets in SCENES:
    b = {m: normalize_stats(scene, sets + s) for m, s in MODES}
    f = {m: per_pixel(b[m]) for m in b}
    pixels = f["direct"][0]
    if pixels == 0:
        continue
    packet, line = b["per packet"]["details"], b["per line"]["details"]
    print("| %s | %d | %.2f | %.2f (%d, %d) | %.2f, %.2f, %.2f | %.2f, %.2f, %.2f | %.2f, %.2f, %.2f | %s |" % (
        label, pixels, pixels / packet["seeds"], pixels / line["seeds"], line["jumps"], line.get("reseeds", 0),
        f["direct"][1], f["per packet"][1], f["per line"][1], f["direct"][2], f["per packet"][2], f["per line"][2],
        f["direct"][3], f["per packet"][3], f["per line"][3],
        ", ".join(str(b[m]["numbers"]["nonfinite"]) for m in ("direct", "per packet", "per line"))))
    samples.append((pixels, packet["seeds"], b["direct"]["ops"], b["per packet"]["ops"]))

# Per pixel and per seed, solved from two scenes' counts (ops = a·pixels + s·seeds), then
# the break-even: a packet of n pixels costs direct·n against a·n + s.
(p1, s1, d1, f1), (p2, s2, _, f2) = samples[0], max(samples, key=lambda x: x[0] / x[1])
det = p1 * s2 - p2 * s1
if det == 0:
    sys.exit("radicand-report: the scenes' spans are all alike; no per-seed cost can be told from the per-pixel one")
costs = {op: (d1[op] / p1, (f1[op] * s2 - f2[op] * s1) / det, (p1 * f2[op] - p2 * f1[op]) / det) for op in ("mul", "add")}
print()
print("| operations counted | direct, per pixel | forward difference, per pixel | a seed | forward difference wins from |")
print("|---|---:|---:|---:|---|")
for name, ops in (("multiplications", ("mul",)), ("multiplications and additions", ("mul", "add"))):
    direct, fd, seed = (sum(costs[o][k] for o in ops) for k in range(3))
    n = next((n for n in range(1, 100000) if fd * n + seed < direct * n), None)
    print("| %s | %g | %g | %g | %s |" % (name, direct, fd, seed, "%d pixels a seed" % n if n else "never"))
shutil.rmtree(TMP, ignore_errors=True)
