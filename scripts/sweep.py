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
goes to stderr when it is a terminal.
Exit 2, one line on stderr naming it and nothing written: a bad option, a missing
program or checkout, a CSV or manifest that is not the sweep's; a render that fails stops
the run with one line (the program's message) and exit 2 when the program found its input
bad (its own exit 2), else 1."""
import argparse
import csv
import io
import json
import os
import random
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile

import shards

MAX_RESOLUTION = 16384  # the program's limit (camera.resolution)
MAX_REPEATS = 1000      # more rounds than anyone waits for is a typo


class Parser(argparse.ArgumentParser):
    """A bad option as one line and exit 2 (no usage block); `where` names whose options
    they are when they do not come from the command line."""
    where = ""

    def error(self, message):
        shards.fail(self.where + message)


# What every shard of one sweep must be given alike (the merge takes them from the manifest).
run_options = Parser(add_help=False)
run_options.add_argument("--match", default="")
# 384 x 288: large enough for wall times above the noise, small enough for the golden model.
run_options.add_argument("--resolution", default="384,288")
run_options.add_argument("--map-cache", metavar="DIR")
run_options.add_argument("--no-map-cache", action="store_true", help="every run builds its maps (to time what the cache saves)")
parser = Parser(parents=[run_options], description="run time against error: see the module's docstring")
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
if ARGS.shard:
    shards.parse(ARGS.shard)


def runs_as(options, where=""):
    """The run options checked: the resolution, the map cache (None: every run builds its
    maps) and the compiled --match; exits 2 naming a bad one (`where`: whose options)."""
    size = re.fullmatch(r"([0-9]+),([0-9]+)", options.resolution)
    if not size or not all(1 <= int(v) <= MAX_RESOLUTION for v in size.groups()):
        shards.fail("%s--resolution takes W,H, each from 1 to %d, not %r" % (where, MAX_RESOLUTION, options.resolution))
    try:
        match = re.compile(options.match)
    except re.error as e:
        shards.fail("%s--match %r is not a regular expression: %s" % (where, options.match, e))
    cache = None if options.no_map_cache else \
        options.map_cache or os.environ.get("SHADETLM_MAP_CACHE") or os.path.join(ROOT, "out", "map-cache")
    return argparse.Namespace(resolution="[%d,%d]" % tuple(map(int, size.groups())), map_cache=cache, match=match)


RUN = runs_as(ARGS)
if not 1 <= ARGS.shards <= shards.MAX_SHARDS:
    parser.error("--shards takes a count from 1 to %d, not %d" % (shards.MAX_SHARDS, ARGS.shards))
if not 0 <= ARGS.repeats <= MAX_REPEATS:
    parser.error("--repeats takes a count from 0 to %d, not %d" % (MAX_REPEATS, ARGS.repeats))
if ARGS.time is not None and not 1 <= ARGS.time <= MAX_REPEATS:
    parser.error("--time takes a count of repeats from 1 to %d, not %d" % (MAX_REPEATS, ARGS.time))
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


def say(text):
    """A line among the progress bar's (this one's or sweep.sh's, on a terminal): the bar
    cleared first, so that the text is not written into it; the next update draws it
    again below."""
    if not text:
        return
    if sys.stderr.isatty():
        sys.stderr.write("\r\033[K")
    sys.stderr.write(text if text.endswith("\n") else text + "\n")
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
    try:
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, errors="replace", env=env)
    except OSError as e:
        shards.fail("%s: cannot run it: %s" % (BIN, e.strerror or e))
    if r.returncode != 0:  # one line: the program's message (its last, or its own "shadetlm: …" line)
        said = [line for line in r.stderr.splitlines() if line.strip()] or ["no message"]
        say("sweep: %s failed on %s (%s): %s" % (
            BIN, scene, "exit %d" % r.returncode if r.returncode > 0 else "signal %d" % -r.returncode,
            next((line for line in reversed(said) if line.startswith("shadetlm: ")), said[-1])))
        sys.exit(2 if r.returncode == 2 else 1)
    say(r.stderr)  # its warnings, if any
    try:
        with open(stats_file) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        shards.fail("%s wrote no readable stats for %s (%s)" % (BIN, scene, e.strerror if isinstance(e, OSError) else e))
    if not isinstance(s, dict) or type(s.get("wall_s")) not in (int, float):
        shards.fail("the stats of %s on %s have no wall time: not the program of this checkout?" % (BIN, scene))
    return s


def selected(runs):
    """(index, run) of the runs --match keeps; the index is the run's in the whole plan."""
    return [(i, r) for i, r in enumerate(runs)
            if RUN.match.search("%s %s %s" % (r[0], r[1], ";".join("%s=%s" % kv for kv in r[2].items())))]


def measure(runs, tmp):
    """--shard: one row per run of this shard, its error against the golden model, into
    the shard's file; a line per run done into its .progress beside it meanwhile (for
    sweep.sh's progress bar), removed when the shard ends, done or not (with the folders
    it made, when they stay empty)."""
    shard, count = shards.parse(ARGS.shard)
    mine = shards.mine(selected(runs), shard, count)
    path = shards.shard_path(ARGS.results, "sweep", shard, count, "csv")
    made = []  # the folders made here, deepest first
    folder = os.path.abspath(os.path.dirname(path))
    while not os.path.exists(folder):
        made.append(folder)
        folder = os.path.dirname(folder)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    text = io.StringIO()
    out = csv.writer(text)
    out.writerow(COLUMNS)
    done = path[:-len(".csv")] + ".progress"
    try:
        with open(done, "w") as partial:
            for k, (index, (family, scene, sets)) in enumerate(mine):
                progress(k, len(mine))
                s = render(tmp, scene, sets, True)
                config = ";".join("%s=%s" % (key.replace("pipeline.", "").replace("materials.", ""), value)
                                  for key, value in sets.items())
                wall = "%.6g" % s["wall_s"]
                try:
                    e = s["error"]["rgb"]
                    out.writerow([index, family, scene, config, wall, s["frame_cycles"], s["pixels"]["shaded"]] +
                                 [s["ops"][op] for op in OPS] + [e["max"], e["rmse"], e["psnr"]] + [wall] * 4 + [1] +
                                 silicon(s))
                except (KeyError, TypeError) as e:
                    shards.fail("the stats of %s on %s lack %s: not the program of this checkout?" % (BIN, scene, e))
                partial.write("%d\n" % index)
                partial.flush()
        shards.write_atomically(path, text.getvalue())
    finally:
        if os.path.exists(done):
            os.remove(done)
        if not os.path.exists(path):
            for folder in made:
                try:
                    os.rmdir(folder)
                except OSError:  # another shard's file is there
                    break
    progress(len(mine), len(mine))


def merge(runs, tmp):
    """--merge: the shards' rows in run order, timed again --repeats times one run at a
    time (0: the shards' own times kept), into DIR/sweep.csv. The runs are timed as the
    shards ran them: with the run options the manifest holds."""
    global RUN
    manifest = shards.manifest(ARGS.merge)
    if manifest["kind"] != "sweep":
        shards.fail("%s holds a %s, not a sweep" % (ARGS.merge, manifest["kind"]))
    run_options.where = "%s: args: " % os.path.join(ARGS.merge, "manifest.json")
    RUN = runs_as(run_options.parse_args(manifest.get("args", [])), run_options.where)
    rows, seen = [], set()
    for path in shards.collect(ARGS.merge, "sweep", "csv"):
        with open(path, newline="") as f:
            rows += read_rows(f, path, runs, seen)
    rows.sort(key=lambda r: int(r["run"]))
    if ARGS.repeats > 0:
        check_program()
        rows = time_rows(runs, tmp, ARGS.repeats, rows)
    shards.write_atomically(os.path.join(ARGS.merge, "sweep.csv"), csv_text(rows))


def time_rows(runs, tmp, repeats, rows):
    """Every row's run again, REPEATS rounds, one process at a time; the rows with wall_s
    the median and its spread. Each round takes the rows in a new order (seeded, so reruns
    match): a slow spell of the machine, or one run warming the caches for the next, then
    spreads over all configurations instead of always hitting the same one. The rows are
    read_rows' (checked against the plan)."""
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


def read_rows(f, where, runs, seen):
    """The rows of a sweep CSV (`where`: its name), each checked against the plan: a run
    number of it, not in `seen` (the runs read before; this file's are added), of the
    same family and scene, every field there; exits 2 naming the first bad one."""
    try:
        reader = csv.DictReader(f)
        rows = list(reader)
    except (csv.Error, ValueError) as e:  # a NUL byte, bytes that are not text (UnicodeDecodeError)
        shards.fail("%s: not a CSV: %s" % (where, e))
    fields = reader.fieldnames or []
    lacking = [c for c in COLUMNS[:COLUMNS.index("err_psnr") + 1] if c not in fields]
    if lacking:
        shards.fail("%s: no column %s: not a CSV of the sweep" % (where, ", ".join(lacking)))
    unknown = [c for c in fields if c not in COLUMNS]
    if unknown:
        shards.fail("%s: column %s is not the sweep's" % (where, ", ".join(map(repr, unknown))))
    for k, r in enumerate(rows, 1):
        if None in r or None in r.values():
            shards.fail("%s: row %d has %s fields than the header" % (where, k, "more" if None in r else "fewer"))
        if not re.fullmatch(r"[0-9]+", r["run"]) or int(r["run"]) >= len(runs):
            shards.fail("%s: row %d: run %r is not a run of this sweep.py (0 to %d)" % (where, k, r["run"], len(runs) - 1))
        family, scene, _ = runs[int(r["run"])]
        if (family, scene) != (r["family"], r["scene"]):
            shards.fail("%s: row %d: run %s is %s %s here, not %s %s: not a CSV of this sweep.py"
                        % (where, k, r["run"], family, scene, r["family"], r["scene"]))
        if int(r["run"]) in seen:
            shards.fail("%s: row %d: run %s is there twice" % (where, k, r["run"]))
        seen.add(int(r["run"]))
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
# end, so that the columns before them stay where they were); then the silicon of the
# blocks' arithmetic (docs/silicon.md), empty where a block's format has no figure.
COLUMNS = (["run", "family", "scene", "configuration", "wall_s", "frame_cycles", "pixels"] + OPS +
           ["err_max", "err_rmse", "err_psnr", "wall_q1_s", "wall_q3_s", "wall_min_s", "wall_max_s", "wall_runs",
            "area_mm2", "energy_nj_per_pixel"])


def silicon(s):
    """[area in mm², energy a shaded pixel in nJ] of a render's stats; empty when some block
    is not priced (its total would leave that block out)."""
    si = s["silicon"]
    if si["unpriced_blocks"] or si["area_mm2"] is None or si["energy_nj_per_shaded_pixel"] is None:
        return ["", ""]
    return ["%.6g" % si["area_mm2"], "%.6g" % si["energy_nj_per_shaded_pixel"]]


def check_program():
    """The program and the checkout are there; exits 2 naming the one that is not."""
    if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
        shards.fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
    if not os.path.isdir(os.path.join(ROOT, "golden")):
        shards.fail("%s: not the checkout (it has no golden/)" % ROOT)


def main():
    runs = plan()
    if ARGS.list or ARGS.plan:
        if ARGS.plan:  # the manifest of a local sweep (scripts/sweep.sh): what its shards and merge share
            args = ["--match", ARGS.match, "--resolution", ARGS.resolution] + \
                (["--map-cache", ARGS.map_cache] if ARGS.map_cache else []) + (["--no-map-cache"] if ARGS.no_map_cache else [])
            shards.write_atomically(os.path.join(ARGS.plan, "manifest.json"),
                                    json.dumps({"kind": "sweep", "shards": ARGS.shards, "args": args}) + "\n")
        print(len(selected(runs)))
        return
    if ARGS.time is not None:
        if sys.stdin.isatty():
            parser.error("--time reads the rows to time on stdin (< sweep.csv), not from a terminal")
        rows = read_rows(sys.stdin, "--time: stdin", runs, set())
    if not ARGS.merge:
        check_program()
    # scancel and timeout stop a run with SIGTERM: taken as an exit, so that the render is
    # killed (subprocess.run does) and the scratch folder and the .progress file go too.
    signal.signal(signal.SIGTERM, lambda number, frame: sys.exit(128 + number))
    # Scratch frames on tmpfs where there is one: every output is synced to disk when
    # written (src/shadetlm/core/output.hpp), a wait that shards running side by side would share.
    scratch = "/dev/shm" if os.access("/dev/shm", os.W_OK) else None
    tmp = tempfile.mkdtemp(prefix="sweep-", dir=scratch)
    try:
        if ARGS.merge:
            merge(runs, tmp)
        elif ARGS.time is not None:
            sys.stdout.write(csv_text(time_rows(runs, tmp, ARGS.time, rows)))
        else:
            measure(runs, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


shards.run_main(main)
