#!/usr/bin/env python3
"""Where a render's time goes, and what writing its frame costs (docs/performance.md).

Table 1: the 1080p benchmark rendered with -o f.exr under each of OpenEXR's lossless
compressions (--compression), with the threads given and with one: the write phase's
seconds (encoding the frame and writing it to its temporary), the file's size, and the
process's wall time against the pipeline's own.
Table 2: the phases of a render with --compare-reference (load, pipeline, golden model,
write), with the threads given and with one; the golden phase's speed-up.
Each figure is the median of --repeats runs (default 3), run one after another.

Usage: scripts/phases-report.py SHADETLM ROOT [--threads N] [--repeats N]
Bad arguments: one line, exit 2."""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

COMPRESSIONS = ["none", "rle", "zips:1", "zips", "zip:1", "zip", "zip:9", "piz"]


def fail(message):
    print("phases-report: " + message, file=sys.stderr)
    sys.exit(2)


class Parser(argparse.ArgumentParser):
    def error(self, message):
        fail(message)


def positive(text):
    if not text.isdigit() or not 1 <= int(text) <= 1024:
        raise argparse.ArgumentTypeError("expected a count from 1 to 1024, not %r" % text)
    return int(text)


def render(binary, scene, folder, args):
    """One render's phases (stats phases_s), the frame's size and the process's wall time."""
    frame, stats = os.path.join(folder, "f.exr"), os.path.join(folder, "s.json")
    start = time.perf_counter()
    done = subprocess.run([binary] + args + ["render", scene, "-o", frame, "--stats", stats],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        fail("%s: the render failed (exit %d): %s" % (scene, done.returncode, done.stderr.strip()[:300]))
    with open(stats) as f:
        phases = json.load(f)["phases_s"]
    return phases, os.path.getsize(frame), wall


def median_run(binary, scene, folder, args, repeats):
    runs = [render(binary, scene, folder, args) for _ in range(repeats)]
    phases = {k: statistics.median(r[0].get(k, 0.0) for r in runs) for k in runs[0][0]}
    return phases, runs[0][1], statistics.median(r[2] for r in runs)


def main():
    parser = Parser(add_help=False)
    parser.add_argument("binary")
    parser.add_argument("root")
    parser.add_argument("--threads", type=positive, default=os.cpu_count() or 1)
    parser.add_argument("--repeats", type=positive, default=3)
    a = parser.parse_args()
    if not (os.path.isfile(a.binary) and os.access(a.binary, os.X_OK)):
        fail("%s: not an executable program" % a.binary)
    scene = os.path.join(a.root, "scenes", "bench-1080p.json")
    if not os.path.isfile(scene):
        fail("%s: no such scene (is %s the checkout?)" % (scene, a.root))
    folder = tempfile.mkdtemp(prefix="phases-")
    try:
        print("| compression | threads | write, s | frame, MB | process wall ÷ pipeline |")
        print("|---|---:|---:|---:|---:|")
        for compression in COMPRESSIONS:
            for threads in sorted({a.threads, 1}, reverse=True):
                phases, size, wall = median_run(
                    a.binary, scene, folder, ["--threads", str(threads), "--compression", compression], a.repeats)
                print("| %s | %d | %.3f | %.1f | %.2f |" % (compression, threads, phases["write"], size / 1e6,
                                                            wall / phases["pipeline"]))
        print()
        print("| threads | load, s | pipeline, s | golden model, s | write, s | golden model speed-up |")
        print("|---:|---:|---:|---:|---:|---:|")
        golden = {}
        for threads in sorted({a.threads, 1}):
            phases = golden_run(a, scene, folder, threads)
            golden[threads] = phases["golden_model"]
            print("| %d | %.3f | %.3f | %.3f | %.3f | %.2f |" % (
                threads, phases["load"], phases["pipeline"], phases["golden_model"], phases["write"],
                golden[1] / phases["golden_model"]))
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def golden_run(a, scene, folder, threads):
    """The phases of a render with --compare-reference on `threads` threads (median of repeats)."""
    runs = []
    for _ in range(a.repeats):
        frame, stats = os.path.join(folder, "g.exr"), os.path.join(folder, "g.json")
        done = subprocess.run([a.binary, "--threads", str(threads), "render", scene, "-o", frame, "--stats", stats,
                               "--compare-reference"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            fail("%s: the render failed (exit %d): %s" % (scene, done.returncode, done.stderr.strip()[:300]))
        with open(stats) as f:
            runs.append(json.load(f)["phases_s"])
    return {k: statistics.median(r[k] for r in runs) for k in runs[0]}


if __name__ == "__main__":
    main()
