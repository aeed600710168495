#!/usr/bin/env python3
"""Scaling (docs/benchmarks.md): wall time and peak memory of the SystemC pipeline at
256² … 4096² pixels (the benchmark scene) and for 10³ … 10⁶ triangles (a sphere at
512²), with least-squares fits: time per covered pixel, time per triangle, memory per
pixel, and R² — cost must grow linearly with covered pixels and with triangles.

Usage: scripts/scaling.py SHADETLM ROOT"""
import json
import os
import subprocess
import sys
import tempfile


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("scaling: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) != 3:
    fail("usage: scripts/scaling.py SHADETLM ROOT")
BIN, ROOT = sys.argv[1], sys.argv[2]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "scenes")):
    fail("%s: not the checkout (it has no scenes/)" % ROOT)
TMP = tempfile.mkdtemp(prefix="scaling-")


def run(scene, sets):
    """Wall time of the render (its own figure), peak resident memory of the process."""
    stats = os.path.join(TMP, "stats.json")
    cmd = [BIN, "render", scene, "-o", os.path.join(TMP, "f.exr"), "--stats", stats]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        sys.exit("render failed: " + " ".join(cmd))
    with open(stats) as f:
        s = json.load(f)
    return s, usage.ru_maxrss / 1024.0  # MiB


def fit(xs, ys):
    """y = a + b·x by least squares, and R²."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - b * mx
    ss = sum((y - my) ** 2 for y in ys)
    r2 = 1 - sum((y - a - b * x) ** 2 for x, y in zip(xs, ys)) / ss if ss > 0 else 1.0
    return a, b, r2


bench = os.path.join(ROOT, "scenes/bench-1080p.json")
print("## Pixels (scenes/bench-1080p.json)\n")
print("| resolution | covered pixels | wall time (s) | ns per covered pixel | peak memory (MiB) |")
print("|---|---|---|---|---|")
px, times, mems, sizes = [], [], [], []
for side in [256, 512, 1024, 2048, 4096]:
    s, mem = run(bench, ["camera.resolution=[%d,%d]" % (side, side)])
    covered = s["pixels"]["shaded"]
    px.append(covered), times.append(s["wall_s"]), mems.append(mem), sizes.append(side * side)
    print("| %d² | %d | %.4f | %.1f | %.1f |" % (side, covered, s["wall_s"], 1e9 * s["wall_s"] / covered, mem))
print("\n| linear fit | fixed part | per unit | R² |\n|---|---|---|---|")
a, b, r2 = fit(px, times)
print("| time | %.4f s | %.1f ns a covered pixel | %.5f |" % (a, b * 1e9, r2))
a, b, r2 = fit(sizes, mems)
print("| memory | %.1f MiB | %.1f bytes a pixel of the frame | %.5f |\n" % (a, b * 1024 * 1024, r2))

print("## Triangles (a sphere at 512²)\n")
print("| triangles | covered pixels | wall time (s) | µs per triangle | peak memory (MiB) |")
print("|---|---|---|---|---|")
tris, times, mems = [], [], []
sphere = os.path.join(ROOT, "golden/sphere/scene.json")
for target in [1e3, 1e4, 1e5, 1e6]:
    segments = max(3, int(round((target / 2) ** 0.5 * 1.41)))
    rings = max(2, segments // 2)
    s, mem = run(sphere, ["camera.resolution=[512,512]", "objects.0.segments=%d" % segments, "objects.0.rings=%d" % rings])
    n = s["triangles"]["in"]
    tris.append(n), times.append(s["wall_s"]), mems.append(mem)
    print("| %d | %d | %.4f | %.3f | %.1f |" % (n, s["pixels"]["shaded"], s["wall_s"], 1e6 * s["wall_s"] / n, mem))
print("\n| linear fit | fixed part | per unit | R² |\n|---|---|---|---|")
a, b, r2 = fit(tris, times)
print("| time | %.4f s | %.3f µs a triangle | %.5f |" % (a, b * 1e6, r2))
a, b, r2 = fit(tris, mems)
print("| memory | %.1f MiB | %.1f bytes a triangle | %.5f |" % (a, b * 1024 * 1024, r2))
for name in os.listdir(TMP):
    os.remove(os.path.join(TMP, name))
os.rmdir(TMP)
