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


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("stability-report: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) != 4:
    fail("usage: scripts/stability-report.py SHADETLM ROOT OUT")
BIN, ROOT, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "scenes")):
    fail("%s: not the checkout (it has no scenes/)" % ROOT)
try:
    os.makedirs(OUT, exist_ok=True)
except OSError as e:
    fail("%s: the plots' folder cannot be made: %s" % (OUT, e.strerror or e))
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
                    "--set", "pipeline.normal_interp.format=" + fmt, "--allow-overflow",
                    "--set", 'objects.0.transform={"scale":[%r,%r,1]}' % scale], check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        s = json.load(f)
    return float(s["error"]["n"]["max"]), float(s["error"]["rgb"]["max"])


def sweep(title, scene, axis, heading, caption, columns, plot, plot_title, key):
    """One table, rows the lengths, columns (label, re-seeding, format); with gnuplot,
    the plot of the normal error of every column."""
    print(heading + "\n")
    print(caption + "\n")
    print("| %s (px) | " % title + " | ".join(label for label, _, _ in columns) + " |")
    print("|---|" + "---|" * len(columns))
    series = {label: [] for label, _, _ in columns}
    for length in LENGTHS:
        s = length / 16384.0
        scale = (s, 1.0) if axis == 0 else (1.0, s)
        cells = []
        for label, mode, fmt in columns:
            n, rgb = error(scene, scale, mode, fmt)
            series[label].append((length, n))
            cells.append("%.1e (%.1e)" % (n, rgb))
        print("| %d | %s |" % (length, " | ".join(cells)))
    print()
    if not shutil.which("gnuplot"):
        return
    data = os.path.join(TMP, plot + ".dat")
    with open(data, "w") as f:
        for label, _, _ in columns:
            for length, n in series[label]:
                f.write("%d %g\n" % (length, max(n, 1e-9)))
            f.write("\n\n")
    dashed = len({fmt for _, _, fmt in columns}) > 1  # per format: re-seeded dashed
    lines = ", ".join("'%s' index %d with linespoints lw 2 dt %d title '%s'" % (data, k, 2 if dashed and k % 2 else 1, c[0])
                      for k, c in enumerate(columns))
    script = "\n".join(["set terminal png size 800,500 noenhanced",
                        "set output '%s'" % os.path.join(OUT, plot + ".png"),
                        "set logscale xy", "set grid", "set key " + key, "set title '%s'" % plot_title,
                        "set xlabel '%s (pixels)'" % title, "set ylabel 'max |N - N_exact|'", "plot " + lines])
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


DIRECTIONS = [("span length", "long-spans.json", 0, "span", "tile32"),
              ("triangle height", "tall-triangle.json", 1, "height", "line")]
for title, scene, axis, name, _ in DIRECTIONS:
    sweep(title, scene, axis, "## Against %s" % title,
          "Largest error of the unit normal against the golden model's (and of the colour), float32.",
          [(mode, mode, "float32") for mode in MODES], "stability-" + name,
          "normal error against %s, float32, by re-seeding" % title, "left top")
# Per format of the walker: no re-seeding, and the re-seeding that bounds the direction.
for title, scene, axis, name, bound in DIRECTIONS:
    sweep(title, scene, axis, "## Per number format, against %s" % title,
          "Largest error of the unit normal against the golden model's (and of the colour); "
          "the walker in each format, the other blocks in float32.",
          [("%s, %s" % (fmt, mode), mode, fmt) for fmt in FORMATS for mode in ("none", bound)],
          "stability-formats-" + name, "normal error against %s, by format of the walker" % title, "outside right")
shutil.rmtree(TMP, ignore_errors=True)
