#!/usr/bin/env python3
"""Run time against error (docs/benchmarks.md): scenes × configuration axes through the
SystemC pipeline, each run against the golden model; one CSV row per run.

  scripts/sweep.py SHADETLM ROOT [--shard I/N] [--list] > rows.csv

Block families and their axes:
  normal    normal_interp.mode × normalize.mode        golden Phong scenes
  bump      material path × bump_fetch.filter          scenes/bump/*.json
  texture   material path × texture_fetch.filter        golden texture scenes
  parallax  tracer (method, map) × max_iterations       golden/parallax-steps
  number_format is an axis of every family, float32 here: the reduced formats keep the
  cycles and cost the model emulation time, so their error is measured against the
  float32 frame by scripts/format-report.sh instead.
--shard I/N runs the runs whose index is I modulo N (independent jobs: xargs -P here,
a Slurm job array on a cluster). A progress bar goes to stderr when it is a terminal."""
import csv
import json
import os
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


runs = plan()
if "--list" in sys.argv:
    print(len(runs))
    sys.exit(0)
mine = [(i, r) for i, r in enumerate(runs) if i % shards == shard]
out = csv.writer(sys.stdout)
out.writerow(["run", "family", "scene", "configuration", "wall_s", "frame_cycles", "pixels"] + OPS +
             ["err_max", "err_rmse", "err_psnr"])
tmp = tempfile.mkdtemp(prefix="sweep-")
for k, (index, (family, scene, sets)) in enumerate(mine):
    progress(k, len(mine))
    stats_file = os.path.join(tmp, "stats.json")
    cmd = [BIN, "render", os.path.join(ROOT, scene), "-o", os.path.join(tmp, "f.exr"), "--stats", stats_file,
           "--compare-reference", "--set", "camera.resolution=" + RESOLUTION]
    for key, value in sets.items():
        cmd += ["--set", "%s=%s" % (key, value)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(stats_file) as f:
        s = json.load(f)
    e = s["error"]["rgb"]
    config = ";".join("%s=%s" % (k.replace("pipeline.", "").replace("materials.", ""), v) for k, v in sets.items())
    out.writerow([index, family, scene, config, "%.6g" % s["wall_s"], s["frame_cycles"], s["pixels"]["shaded"]] +
                 [s["ops"][op] for op in OPS] + [e["max"], e["rmse"], e["psnr"]])
    sys.stdout.flush()
progress(len(mine), len(mine))
for name in os.listdir(tmp):
    os.remove(os.path.join(tmp, name))
os.rmdir(tmp)
