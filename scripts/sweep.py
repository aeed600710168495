#!/usr/bin/env python3
"""Run time against error (docs/benchmarks.md): scenes × configuration axes through the
SystemC pipeline, each run against the golden model; one CSV row per run.

  scripts/sweep.py SHADETLM ROOT --list                          the number of runs
  scripts/sweep.py SHADETLM ROOT --plan DIR --shards N            the same, and DIR/manifest.json
  scripts/sweep.py SHADETLM ROOT --shard I/N --results DIR        one shard's rows
  scripts/sweep.py SHADETLM ROOT --merge DIR [--repeats R]       DIR/sweep.csv
  scripts/sweep.py SHADETLM ROOT --time REPEATS < rows.csv > timed.csv
  Any of them with --match REGEX (only the runs whose "family scene configuration"
  matches), --resolution W,H (default 384,288) and --map-cache DIR (the parallax maps,
  render --map-cache; default ROOT/out/map-cache; --no-map-cache: every run builds its
  maps): every shard of a sweep must get the same ones (scripts/sweep.sh and
  scripts/slurm.py pass them on).

Block families and their axes:
  normal    normal_interp.mode × normalize.mode        golden Phong scenes
  bump      material path × bump_fetch.filter          scenes/bump/*.json
  texture   material path × texture_fetch.filter        golden texture scenes
  parallax  tracer (method, map) × max_iterations       golden/parallax-steps
  number_format is an axis of every family, float32 here: the reduced formats keep the
  cycles and cost the model emulation time, so their error is measured against the
  float32 frame by scripts/format-report.sh instead.
--shard I/N runs every N-th run from the I-th (independent jobs: xargs -P here, a Slurm
job array on a cluster) and writes its rows to DIR/shards/sweep-I-of-N.csv, whole or not
at all (scripts/shards.py). Error, cycles and operations do not depend on what else
runs; the wall time of a shard's run does, so it is one sample (wall_runs 1).
--merge puts the N shards' rows together in run order once all are there (else it names
the missing shards, exits 2 and writes nothing), times them again as --time does when
--repeats R is over 0, and writes DIR/sweep.csv.
--time REPEATS times the runs of rows.csv again, one process at a time, REPEATS rounds
over all of them, and rewrites wall_s as the median, with the quartiles and the extremes
as its spread (a finished sweep.csv can be timed again the same way). A progress bar
goes to stderr when it is a terminal."""
import argparse
import csv
import io
import json
import os
import random
import re
import statistics
import subprocess
import sys
import tempfile

import shards

# What every shard of one sweep must be given alike (the merge takes them from the manifest).
run_options = argparse.ArgumentParser(add_help=False)
run_options.add_argument("--match", default="")
# 384 x 288: large enough for wall times above the noise, small enough for the golden model.
run_options.add_argument("--resolution", default="384,288")
run_options.add_argument("--map-cache", metavar="DIR")
run_options.add_argument("--no-map-cache", action="store_true", help="every run builds its maps (to time what the cache saves)")
parser = argparse.ArgumentParser(parents=[run_options], description="run time against error: see the module's docstring")
parser.add_argument("bin")
parser.add_argument("root")
mode = parser.add_mutually_exclusive_group(required=True)
mode.add_argument("--list", action="store_true")
mode.add_argument("--plan", metavar="DIR")
mode.add_argument("--shard")
mode.add_argument("--merge", metavar="DIR")
mode.add_argument("--time", type=int, metavar="REPEATS")
parser.add_argument("--results", metavar="DIR")
parser.add_argument("--shards", type=int, default=1, help="--plan: the number of shards")
parser.add_argument("--repeats", type=int, default=0, help="--merge: times each run this many times (0: the shards' times)")
ARGS = parser.parse_args()
BIN, ROOT = ARGS.bin, ARGS.root
if ARGS.shard and not ARGS.results:
    parser.error("--shard needs --results DIR")


def runs_as(options):
    """The run options checked: the resolution, the map cache (None: every run builds its
    maps) and the compiled --match; exits 2 naming a bad one."""
    if not re.fullmatch(r"\d+,\d+", options.resolution):
        parser.error("--resolution takes W,H, not %r" % options.resolution)
    try:
        match = re.compile(options.match)
    except re.error as e:
        parser.error("--match %r is not a regular expression: %s" % (options.match, e))
    cache = None if options.no_map_cache else \
        options.map_cache or os.environ.get("SHADETLM_MAP_CACHE") or os.path.join(ROOT, "out", "map-cache")
    return argparse.Namespace(resolution="[%s]" % options.resolution, map_cache=cache, match=match)


RUN = runs_as(ARGS)
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
    # The parallax tracers: the refined distance map (the default), the box-gap map,
    # Donnelly's map as published, classic and relaxed cone stepping, and the layered
    # searches, each at three iteration caps.
    tracers = [{}] + [{"parallax.method": "distance", "parallax.map": m} for m in ["box-gap", "donnelly"]] + [
        {"parallax.method": "cone", "parallax.cones": "relaxed"}] + [
        {"parallax.method": m} for m in ["cone", "relief", "pom", "steep", "offset"]]
    for tracer in tracers:
        # Donnelly's tracer takes a fixed count of steps (parallax.steps), the others a cap.
        limit = "parallax.steps" if tracer.get("parallax.map") == "donnelly" else "parallax.max_iterations"
        for cap in [256] if tracer.get("parallax.method") == "offset" else [16, 64, 256]:  # offset: no loop
            for fmt in FORMATS:
                sets = {"materials.carved.%s" % k: v for k, v in tracer.items()}
                sets.update({"materials.carved." + limit: cap, "pipeline.number_format": fmt})
                runs.append(("parallax", "golden/parallax-steps/scene.json", sets))
    return runs


def progress(done, total):
    if not sys.stderr.isatty() or ARGS.shard:  # shards: sweep.sh draws one bar for all
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
           "--set", "camera.resolution=" + RUN.resolution]
    env = dict(os.environ)
    if RUN.map_cache:
        cmd += ["--map-cache", RUN.map_cache]
    else:
        env.pop("SHADETLM_MAP_CACHE", None)  # render would take the cache from it
    if compare:
        cmd.append("--compare-reference")
    for key, value in sets.items():
        cmd += ["--set", "%s=%s" % (key, value)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=env)
    with open(stats_file) as f:
        return json.load(f)


def selected(runs):
    """(index, run) of the runs --match keeps; the index is the run's in the whole plan."""
    return [(i, r) for i, r in enumerate(runs)
            if RUN.match.search("%s %s %s" % (r[0], r[1], ";".join("%s=%s" % kv for kv in r[2].items())))]


def measure(runs, tmp):
    """--shard: one row per run of this shard, its error against the golden model, into
    the shard's file; a line per run done into its .progress beside it meanwhile (for
    sweep.sh's progress bar)."""
    shard, count = shards.parse(ARGS.shard)
    mine = shards.mine(selected(runs), shard, count)
    path = shards.shard_path(ARGS.results, "sweep", shard, count, "csv")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    text = io.StringIO()
    out = csv.writer(text)
    out.writerow(COLUMNS)
    done = path[:-len(".csv")] + ".progress"
    with open(done, "w") as partial:
        for k, (index, (family, scene, sets)) in enumerate(mine):
            progress(k, len(mine))
            s = render(tmp, scene, sets, True)
            e = s["error"]["rgb"]
            config = ";".join("%s=%s" % (key.replace("pipeline.", "").replace("materials.", ""), value)
                              for key, value in sets.items())
            wall = "%.6g" % s["wall_s"]
            out.writerow([index, family, scene, config, wall, s["frame_cycles"], s["pixels"]["shaded"]] +
                         [s["ops"][op] for op in OPS] + [e["max"], e["rmse"], e["psnr"]] + [wall] * 4 + [1])
            partial.write("%d\n" % index)
            partial.flush()
    shards.write_atomically(path, text.getvalue())
    os.remove(done)
    progress(len(mine), len(mine))


def merge(runs, tmp):
    """--merge: the shards' rows in run order, timed again --repeats times one run at a
    time (0: the shards' own times kept), into DIR/sweep.csv. The runs are timed as the
    shards ran them: with the run options the manifest holds."""
    global RUN
    RUN = runs_as(run_options.parse_args(shards.manifest(ARGS.merge).get("args", [])))
    rows = []
    for path in shards.collect(ARGS.merge, "sweep", "csv"):
        with open(path) as f:
            rows += list(csv.DictReader(f))
    rows.sort(key=lambda r: int(r["run"]))
    if ARGS.repeats > 0:
        rows = time_rows(runs, tmp, ARGS.repeats, rows)
    shards.write_atomically(os.path.join(ARGS.merge, "sweep.csv"), csv_text(rows))


def time_rows(runs, tmp, repeats, rows):
    """Every row's run again, REPEATS rounds, one process at a time; the rows with wall_s
    the median and its spread. Each round takes the rows in a new order (seeded, so reruns
    match): a slow spell of the machine, or one run warming the caches for the next, then
    spreads over all configurations instead of always hitting the same one."""
    if repeats < 1:
        sys.exit("sweep: --time needs at least 1 repeat")
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
    for r in rows:
        r.update(spread(samples[r["run"]]))
    return rows


def csv_text(rows):
    text = io.StringIO()
    out = csv.DictWriter(text, COLUMNS)
    out.writeheader()
    out.writerows(rows)
    return text.getvalue()


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
    if ARGS.list or ARGS.plan:
        if ARGS.plan:  # the manifest of a local sweep (scripts/sweep.sh): what its shards and merge share
            if ARGS.shards < 1:
                parser.error("--shards takes a positive count")
            args = ["--match", ARGS.match, "--resolution", ARGS.resolution] + \
                (["--map-cache", ARGS.map_cache] if ARGS.map_cache else []) + (["--no-map-cache"] if ARGS.no_map_cache else [])
            shards.write_atomically(os.path.join(ARGS.plan, "manifest.json"),
                                    json.dumps({"kind": "sweep", "shards": ARGS.shards, "args": args}) + "\n")
        print(len(selected(runs)))
        return
    # Scratch frames on tmpfs where there is one: every output is synced to disk when
    # written (core/output.hpp), a wait that shards running side by side would share.
    scratch = "/dev/shm" if os.access("/dev/shm", os.W_OK) else None
    tmp = tempfile.mkdtemp(prefix="sweep-", dir=scratch)
    try:
        if ARGS.merge:
            merge(runs, tmp)
        elif ARGS.time is not None:
            sys.stdout.write(csv_text(time_rows(runs, tmp, ARGS.time, list(csv.DictReader(sys.stdin)))))
        else:
            measure(runs, tmp)
    finally:
        for name in os.listdir(tmp):
            os.remove(os.path.join(tmp, name))
        os.rmdir(tmp)


main()
