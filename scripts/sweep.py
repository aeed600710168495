#!/usr/bin/env python3
"""Run time against error (docs/benchmarks.md): scenes × configuration axes through the
SystemC pipeline, each run against the golden model; one CSV row per run.

  scripts/sweep.py SHADETLM ROOT [--shard I/N] [--list] > rows.csv
  scripts/sweep.py SHADETLM ROOT --time REPEATS < rows.csv > timed.csv

Block families and their axes:
  normal    normal_interp.mode × normalize.mode        golden Phong scenes
  bump      material path × bump_fetch.filter          scenes/bump/*.json
  texture   material path × texture_fetch.filter        golden texture scenes
  parallax  tracer (method, map) × max_iterations       golden/parallax-steps
  number_format is an axis of every family, float32 here: the reduced formats keep the
  cycles and cost the model emulation time, so their error is measured against the
  float32 frame by scripts/format-report.sh instead.
--shard I/N runs the runs whose index is I modulo N (independent jobs: xargs -P here,
a Slurm job array on a cluster). Error, cycles and operations do not depend on what else
runs; the wall time of a shard's run does, so it is one sample (wall_runs 1).
--time REPEATS times the runs of rows.csv again, one process at a time, REPEATS rounds
over all of them, and rewrites wall_s as the median, with the quartiles and the extremes
as its spread (a finished sweep.csv can be timed again the same way). A progress bar goes to stderr when it is a terminal."""
import csv
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile

BIN, ROOT = sys.argv[1], sys.argv[2]
shard, shards = 0, 1
if "--shard" in sys.argv:
    shard, shards = (int(x) for x in sys.argv[sys.argv.index("--shard") + 1].split("/"))
    if not 0 <= shard < shards:
        sys.exit("sweep: --shard I/N needs 0 <= I < N")
RESOLUTION = "[384,288]"  # large enough for wall times above the noise, small enough for the golden model
OPS = ["add", "mul", "div", "sqrt", "rsqrt", "lut", "fetch", "line"]
FORMATS = ["float32"]


def plan():
    runs = []
    for scene in ["golden/sphere/scene.json", "golden/torus/scene.json", "golden/point-light/scene.json",
                  "golden/grazing-plane/scene.json"]:
        for interp in ["perspective", "affine"]:
            for mode in ["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]:
                for fmt in FORMATS:
                    runs.append(("normal", scene, {"pipeline.normal_interp.mode": interp, "pipeline.normalize.mode": mode,
                                                   "pipeline.number_format": fmt}))
    for surface in ["quad", "sphere", "torus", "knot"]:
        for path in ["bump-classic", "bump-tangent", "bump-square", "bump-object"]:
            for filt in ["nearest", "bilinear", "trilinear", "anisotropic"]:
                for fmt in FORMATS:
                    sets = {"materials.bumpy.path": path, "pipeline.bump_fetch.filter": filt, "pipeline.number_format": fmt}
                    if path == "bump-square":
                        sets["materials.bumpy.square_k"] = {"quad": 2, "sphere": 3.6, "torus": 4.4, "knot": 8}[surface]
                    runs.append(("bump", "scenes/bump/%s.json" % surface, sets))
    for scene, material in [("golden/texture-object/scene.json", "floor"), ("golden/texture-screen/scene.json", "wall")]:
        for path, filt in [("texture-object", None)] + [("texture-screen", f) for f in
                                                        ["nearest", "bilinear", "trilinear", "anisotropic", "ewa"]]:
            for fmt in FORMATS:
                sets = {"materials.%s.path" % material: path, "pipeline.number_format": fmt}
                if filt:
                    sets["pipeline.texture_fetch.filter"] = filt
                runs.append(("texture", scene, sets))
    # The parallax tracers: the refined distance map (the default), Donnelly's map, cone
    # stepping, and the layered searches, each at three iteration caps.
    tracers = [{}, {"parallax.method": "distance", "parallax.map": "donnelly"}] + [
        {"parallax.method": m} for m in ["cone", "relief", "pom", "steep", "offset"]]
    for tracer in tracers:
        for cap in [256] if tracer.get("parallax.method") == "offset" else [16, 64, 256]:  # offset: no loop
            for fmt in FORMATS:
                sets = {"materials.carved.%s" % k: v for k, v in tracer.items()}
                sets.update({"materials.carved.parallax.max_iterations": cap, "pipeline.number_format": fmt})
                runs.append(("parallax", "golden/parallax-steps/scene.json", sets))
    return runs


def progress(done, total):
    if not sys.stderr.isatty() or shards > 1:  # shards: sweep.sh draws one bar for all
        return
    filled = int(30 * done / max(1, total))
    sys.stderr.write("\rsweep [%s%s] %d/%d" % ("#" * filled, " " * (30 - filled), done, total))
    if done == total:
        sys.stderr.write("\n")
    sys.stderr.flush()


def render(tmp, scene, sets, compare):
    """One run's statistics. Without compare the golden model is not rendered: wall_s is
    the simulation's own time (sc_start), which the golden model never enters."""
    stats_file = os.path.join(tmp, "stats.json")
    cmd = [BIN, "render", os.path.join(ROOT, scene), "-o", os.path.join(tmp, "f.exr"), "--stats", stats_file,
           "--set", "camera.resolution=" + RESOLUTION]
    if compare:
        cmd.append("--compare-reference")
    for key, value in sets.items():
        cmd += ["--set", "%s=%s" % (key, value)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(stats_file) as f:
        return json.load(f)


def measure(runs, tmp):
    """--shard: one row per run of this shard, its error against the golden model."""
    mine = [(i, r) for i, r in enumerate(runs) if i % shards == shard]
    out = csv.writer(sys.stdout)
    out.writerow(COLUMNS)
    for k, (index, (family, scene, sets)) in enumerate(mine):
        progress(k, len(mine))
        s = render(tmp, scene, sets, True)
        e = s["error"]["rgb"]
        config = ";".join("%s=%s" % (key.replace("pipeline.", "").replace("materials.", ""), value)
                          for key, value in sets.items())
        wall = "%.6g" % s["wall_s"]
        out.writerow([index, family, scene, config, wall, s["frame_cycles"], s["pixels"]["shaded"]] +
                     [s["ops"][op] for op in OPS] + [e["max"], e["rmse"], e["psnr"]] + [wall] * 4 + [1])
        sys.stdout.flush()
    progress(len(mine), len(mine))


def time_rows(runs, tmp, repeats):
    """--time: every row's run again, REPEATS rounds, one process at a time. Each round
    takes the rows in a new order (seeded, so reruns match): a slow spell of the machine,
    or one run warming the caches for the next, then spreads over all configurations
    instead of always hitting the same one."""
    if repeats < 1:
        sys.exit("sweep: --time needs at least 1 repeat")
    rows = list(csv.DictReader(sys.stdin))
    for r in rows:
        family, scene, _ = runs[int(r["run"])]
        if (family, scene) != (r["family"], r["scene"]):
            sys.exit("sweep: run %s of the CSV is not run %s of this sweep.py" % (r["run"], r["run"]))
    samples = {r["run"]: [] for r in rows}
    # One run first, not counted: the first of a series comes out slow (binary, libraries
    # and scene files not yet in the page cache).
    if rows:
        _, scene, sets = runs[int(rows[0]["run"])]
        render(tmp, scene, sets, False)
    for round_ in range(repeats):
        order = list(rows)
        random.Random(round_).shuffle(order)
        for k, r in enumerate(order):
            progress(round_ * len(rows) + k, repeats * len(rows))
            _, scene, sets = runs[int(r["run"])]
            samples[r["run"]].append(render(tmp, scene, sets, False)["wall_s"])
    progress(repeats * len(rows), repeats * len(rows))
    out = csv.DictWriter(sys.stdout, COLUMNS)
    out.writeheader()
    for r in rows:
        r.update(spread(samples[r["run"]]))
        out.writerow(r)


def spread(t):
    """The median of the samples, their quartiles (the middle half, which one run slowed
    by something else on the machine does not move) and their extremes."""
    q1, median, q3 = statistics.quantiles(t, n=4, method="inclusive") if len(t) > 1 else t * 3
    times = dict(wall_s=median, wall_q1_s=q1, wall_q3_s=q3, wall_min_s=min(t), wall_max_s=max(t))
    return dict({k: "%.6g" % v for k, v in times.items()}, wall_runs=len(t))


# wall_s is the median of wall_runs samples, the columns after err_psnr its spread (at the
# end, so that the columns before them stay where they were).
COLUMNS = (["run", "family", "scene", "configuration", "wall_s", "frame_cycles", "pixels"] + OPS +
           ["err_max", "err_rmse", "err_psnr", "wall_q1_s", "wall_q3_s", "wall_min_s", "wall_max_s", "wall_runs"])


def main():
    runs = plan()
    if "--list" in sys.argv:
        print(len(runs))
        return
    tmp = tempfile.mkdtemp(prefix="sweep-")
    try:
        if "--time" in sys.argv:
            time_rows(runs, tmp, int(sys.argv[sys.argv.index("--time") + 1]))
        else:
            measure(runs, tmp)
    finally:
        for name in os.listdir(tmp):
            os.remove(os.path.join(tmp, name))
        os.rmdir(tmp)


main()
