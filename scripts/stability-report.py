#!/usr/bin/env python3
"""Error growth of the normal walker (docs/numerical-stability.md): the largest error of
the normal against the golden model's, on the stress scenes' longest span
(scenes/stress/long-spans.json, scaled to spans of 16 … 16384 pixels) and tallest
triangle (tall-triangle.json, 16 … 16384 rows), with and without re-seeding
(normal_interp.reseed), per number format. Prints Markdown tables; with gnuplot, draws
OUT/stability-span.png and OUT/stability-height.png.

Usage: scripts/stability-report.py SHADETLM ROOT OUT"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

BIN, ROOT, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(OUT, exist_ok=True)
TMP = tempfile.mkdtemp(prefix="stability-")
MODES = ["none", "line", "tile32", "tile16", "tile8"]
# The walker's formats: float16 and fixed point of 16 and 24 bits (N/w of these scenes
# lies in [−1, 1), so no integer bit: fixed:0.15 is float16's storage, fixed:0.23 float32's significand).
FORMATS = ["float32", "float16", "fixed:0.15", "fixed:0.23"]
LENGTHS = [16, 64, 256, 1024, 4096, 16384]


def error(scene, scale, mode, fmt):
    stats = os.path.join(TMP, "s.json")
    subprocess.run([BIN, "render", os.path.join(ROOT, "scenes/stress", scene), "-o", os.path.join(TMP, "f.exr"),
                    "--stats", stats, "--compare-reference", "--set", "pipeline.normal_interp.reseed=" + mode,
                    "--set", "pipeline.normal_interp.format=" + fmt,
                    "--set", 'objects.0.transform={"scale":[%r,%r,1]}' % scale], check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        s = json.load(f)
    return float(s["error"]["n"]["max"]), float(s["error"]["rgb"]["max"])


for title, scene, axis, name in [("span length", "long-spans.json", 0, "span"),
                                 ("triangle height", "tall-triangle.json", 1, "height")]:
    print("## Against %s\n" % title)
    print("Largest error of the unit normal against the golden model's (and of the colour), float32.\n")
    print("| %s (px) | " % title + " | ".join(MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    table = {m: [] for m in MODES}
    for length in LENGTHS:
        s = length / 16384.0
        scale = (s, 1.0) if axis == 0 else (1.0, s)
        cells = []
        for mode in MODES:
            n, rgb = error(scene, scale, mode, "float32")
            table[mode].append((length, n))
            cells.append("%.1e (%.1e)" % (n, rgb))
        print("| %d | %s |" % (length, " | ".join(cells)))
    print()
    if shutil.which("gnuplot"):
        data = os.path.join(TMP, name + ".dat")
        with open(data, "w") as f:
            for mode in MODES:
                for length, n in table[mode]:
                    f.write("%d %g\n" % (length, max(n, 1e-9)))
                f.write("\n\n")
        plot = ", ".join("'%s' index %d with linespoints lw 2 title '%s'" % (data, k, m) for k, m in enumerate(MODES))
        script = "\n".join(["set terminal png size 800,500 noenhanced",
                            "set output '%s'" % os.path.join(OUT, "stability-%s.png" % name),
                            "set logscale xy", "set grid", "set key left top",
                            "set title 'normal error against %s, float32, by re-seeding'" % title,
                            "set xlabel '%s (pixels)'" % title, "set ylabel 'max |N - N_exact|'", "plot " + plot])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)

# Per format of the walker: no re-seeding, and the re-seeding that bounds the direction.
for title, scene, axis, name, bound in [("span length", "long-spans.json", 0, "span", "tile32"),
                                        ("triangle height", "tall-triangle.json", 1, "height", "line")]:
    print("## Per number format, against %s\n" % title)
    print("Largest error of the unit normal against the golden model's (and of the colour); "
          "the walker in each format, the other blocks in float32.\n")
    columns = ["%s, %s" % (fmt, mode) for fmt in FORMATS for mode in ("none", bound)]
    print("| %s (px) | " % title + " | ".join(columns) + " |")
    print("|---|" + "---|" * len(columns))
    series = {c: [] for c in columns}
    for length in LENGTHS:
        s = length / 16384.0
        scale = (s, 1.0) if axis == 0 else (1.0, s)
        cells = []
        for fmt in FORMATS:
            for mode in ("none", bound):
                n, rgb = error(scene, scale, mode, fmt)
                series["%s, %s" % (fmt, mode)].append((length, n))
                cells.append("%.1e (%.1e)" % (n, rgb))
        print("| %d | %s |" % (length, " | ".join(cells)))
    print()
    if shutil.which("gnuplot"):
        data = os.path.join(TMP, name + "-formats.dat")
        with open(data, "w") as f:
            for c in columns:
                for length, n in series[c]:
                    f.write("%d %g\n" % (length, max(n, 1e-9)))
                f.write("\n\n")
        plot = ", ".join("'%s' index %d with linespoints lw 2 dt %d title '%s'" % (data, k, 1 if k % 2 == 0 else 2, c)
                         for k, c in enumerate(columns))
        script = "\n".join(["set terminal png size 800,500 noenhanced",
                            "set output '%s'" % os.path.join(OUT, "stability-formats-%s.png" % name),
                            "set logscale xy", "set grid", "set key outside right",
                            "set title 'normal error against %s, by format of the walker'" % title,
                            "set xlabel '%s (pixels)'" % title, "set ylabel 'max |N - N_exact|'", "plot " + plot])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
shutil.rmtree(TMP, ignore_errors=True)
