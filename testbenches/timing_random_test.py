#!/usr/bin/env python3
"""The fast timing model against the clocked timing reference on random configurations
(docs/pipeline.md, "The timing check"): small random scenes (spheres, planes, cubes and
tori of every shading path, point and directional lights), random FIFO depths (1-16),
IIs (1-6) and latencies of every block, the arithmetic units' latencies, normalize's
modes and seeding, the memory model on and off, elaborate=all or as needed. Each must
give the same start and hand-over cycle for every pixel at every block as the clocked
reference (`shadetlm timing-check`), and the same render without the log (the plain
sweep, as users run it) the same statistics as the logged one. Deterministic: configuration k of seed S is the
same on every machine; a failure prints the seed and the k that reproduce it alone
(--seed S --only k).

Usage: timing_random_test.py SHADETLM [--count 200] [--seed 38] [--only K]
Prints "N passed, N failed"; exit 1 if any failed, 2 on bad arguments."""
import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

PATHS = ["phong", "bump-classic", "bump-tangent", "bump-square", "bump-object", "texture-screen", "texture-object",
         "parallax"]
SHAPES = ["sphere", "plane", "cube", "torus"]


def fail(message):
    print("timing_random_test: " + message, file=sys.stderr)
    sys.exit(2)


def random_scene(rng):
    """A small scene: 1-3 objects of random shapes and paths, 1-3 lights."""
    width = rng.randint(16, 160)  # (up to 160: packets longer than the FIFOs, timed in chunks)
    # (A camera as near as 1.2 clips objects against the near plane and the guard band.)
    scene = {"camera": {"position": [rng.uniform(-1, 1), rng.uniform(-0.5, 1.5), rng.uniform(1.2, 5)],
                        "target": [0, 0, 0], "resolution": [width, rng.randint(12, 96)],
                        "local_viewer": rng.random() < 0.5},
             "lights": [], "textures": {
                 "relief": {"type": "steps", "size": [32, 32], "cells": rng.randint(2, 6), "levels": rng.randint(2, 5),
                            "seed": rng.randint(1, 99)},
                 "check": {"type": "checker", "size": [32, 32], "cells": rng.choice([2, 4, 8])}},
             "materials": {}, "objects": []}
    for _ in range(rng.randint(1, 3)):
        if rng.random() < 0.5:
            scene["lights"].append({"type": "directional", "direction": [rng.uniform(-1, 1), rng.uniform(-1, 0), -1]})
        else:
            scene["lights"].append({"type": "point", "position": [rng.uniform(-3, 3), rng.uniform(0, 3), rng.uniform(1, 3)]})
    for k in range(rng.randint(1, 3)):
        path = rng.choice(PATHS)
        material = {"path": path, "shininess": rng.choice([4, 16, 64])}
        if path.startswith("bump") or path == "parallax":
            material["height_map"] = "relief"
        if path.startswith("texture") or rng.random() < 0.3:
            material["texture"] = "check"
        scene["materials"]["m%d" % k] = material
        shape = rng.choice(SHAPES)
        obj = {"shape": shape, "material": "m%d" % k,
               "transform": {"translate": [rng.uniform(-1, 1), rng.uniform(-0.5, 0.5), rng.uniform(-1, 0.5)],
                             "rotate": [rng.uniform(-60, 60), rng.uniform(-60, 60), 0]}}
        if shape == "sphere":
            obj["radius"] = rng.uniform(0.3, 1)
        if rng.random() < 0.5:
            obj["cull"] = "back"
        scene["objects"].append(obj)
    return scene


def random_settings(rng, keys):
    """--set values: each timed key drawn with probability 1/2, and the modes."""
    sets = []
    for key in keys:
        if rng.random() < 0.5:
            continue
        if key.endswith(".fifo_depth"):
            sets.append("pipeline.%s=%d" % (key, rng.randint(1, 16)))
        elif key.endswith(".ii"):
            sets.append("pipeline.%s=%d" % (key, rng.randint(1, 6)))
        elif key.endswith(".latency") and key != "memory.latency":
            sets.append("pipeline.%s=%d" % (key, rng.randint(1, 40)))
    if rng.random() < 0.5:
        sets.append("pipeline.setup.reject_cycles=%d" % rng.randint(1, 8))
    sets.append("pipeline.normalize.mode=" + rng.choice(["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]))
    sets.append("pipeline.normalize.seed=" + rng.choice(["packet", "line"]))
    sets.append("pipeline.elaborate=" + rng.choice(["needed", "all"]))
    if rng.random() < 0.5:
        sets.append("pipeline.memory.model=dram")
        sets.append("pipeline.memory.latency=%d" % rng.randint(1, 300))
    return sets


def timed_keys(binary, folder):
    """The settings that time the blocks (latency, II, FIFO depth), from a render's stats."""
    stats = os.path.join(folder, "keys.json")
    subprocess.run([binary, "render", "--set", "camera.resolution=[4,4]", "-o", os.path.join(folder, "keys.exr"),
                    "--stats", stats], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        config = json.load(f)["config"]
    return sorted(k for k in config if k.endswith((".fifo_depth", ".ii", ".latency")))


def one(binary, folder, keys, seed, k):
    """Configuration k of `seed`: (ok, what), rendered and checked."""
    rng = random.Random("%d/%d" % (seed, k))
    scene, sets = random_scene(rng), random_settings(rng, keys)
    path = os.path.join(folder, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    log = os.path.join(folder, "t.log")
    stats = os.path.join(folder, "s.json")
    cmd = [binary, "render", path, "-o", os.path.join(folder, "f.exr"), "--timing-log", log, "--allow-overflow",
           "--allow-nonfinite", "--stats", stats]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        return False, "render exit %d: %s" % (r.returncode, r.stderr.strip()[:300])
    c = subprocess.run([binary, "timing-check", log, "--show", "3"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    if c.returncode == 1:
        return False, "DIFFERENT (%s): %s" % (" ".join(sets), c.stdout.strip()[:600])
    if c.returncode != 0:
        return False, "timing-check exit %d: %s" % (c.returncode, c.stdout.strip()[:300])
    m = re.search(r"times compared \((\d+) pixels", c.stdout)
    if not m:
        return False, "timing-check said EQUAL without its count: %s" % c.stdout.strip()[:300]
    with open(stats) as f:
        checked = json.load(f)
    # The same render without the log takes the plain sweep (no times kept: blocks that
    # only delay timed as delays); its statistics must be those the clocked reference
    # just judged.
    plain_stats = os.path.join(folder, "plain.json")
    plain = [x for x in cmd if x not in ("--timing-log", log)]
    plain[plain.index(stats)] = plain_stats
    r = subprocess.run(plain, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        return False, "plain render exit %d: %s" % (r.returncode, r.stderr.strip()[:300])
    with open(plain_stats) as f:
        unlogged = json.load(f)
    moved = timing_differences(checked, unlogged)
    if moved:
        return False, "PLAIN SWEEP DIFFERENT (%s): %s" % (" ".join(sets), "; ".join(moved[:5]))
    triangles = checked["triangles"]
    return True, (int(m.group(1)), triangles["in"] > triangles["drawn"])


TIMED = ["busy_cycles", "starved_cycles", "blocked_cycles", "fifo_peak", "fifo_mean", "last_cycle", "memory"]


def timing_differences(checked, plain):
    """What a plain render's statistics say otherwise than the logged one's: frame cycles,
    each block's timed figures and its utilization over time."""
    out = []
    if checked["frame_cycles"] != plain["frame_cycles"]:
        out.append("frame cycles %s, plain %s" % (checked["frame_cycles"], plain["frame_cycles"]))
    for name, block in checked["blocks"].items():
        other = plain["blocks"].get(name, {})
        for key in TIMED:
            if block.get(key) != other.get(key):
                out.append("%s %s %s, plain %s" % (name, key, block.get(key), other.get(key)))
    if checked.get("utilization_over_time") != plain.get("utilization_over_time"):
        out.append("utilization over time")
    return out


def main():
    p = argparse.ArgumentParser(add_help=False)
    p.error = lambda message: fail(message)
    p.add_argument("binary")
    p.add_argument("--count", type=int, default=200)
    p.add_argument("--seed", type=int, default=38)
    p.add_argument("--only", type=int)
    a = p.parse_args()
    if not (os.path.isfile(a.binary) and os.access(a.binary, os.X_OK)):
        fail("%s: not an executable program" % a.binary)
    if not 1 <= a.count <= 100000:
        fail("--count takes 1 to 100000, not %d" % a.count)
    folder = tempfile.mkdtemp(prefix="timing-random-")
    passes = failures = pixels = empty = dropping = 0
    try:
        keys = timed_keys(a.binary, folder)
        if not any(k.endswith(".fifo_depth") for k in keys) or not any(k.endswith(".ii") for k in keys):
            fail("no FIFO depth or II among the settings (%d keys): nothing would be varied" % len(keys))
        for k in ([a.only] if a.only is not None else range(a.count)):
            ok, what = one(a.binary, folder, keys, a.seed, k)
            if ok:
                passes += 1
                pixels += what[0]
                empty += what[0] == 0
                dropping += what[1]
            else:
                failures += 1
                print("FAIL configuration %d of seed %d (again: %s %s --seed %d --only %d): %s" % (
                    k, a.seed, sys.argv[0], a.binary, a.seed, k, what))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print("%d configurations, %d pixels compared at every block (%d configurations showed none; "
          "%d had triangles culled or clipped away)" % (passes + failures, pixels, empty, dropping))
    if a.only is None and passes and empty * 2 > passes:
        failures += 1
        print("FAIL most configurations showed no pixel: the scenes no longer test anything")
    if a.only is None and passes >= 10 and dropping * 4 < passes:
        failures += 1
        print("FAIL fewer than a quarter of the configurations dropped a triangle: setup's rejections go untested")
    print("%d passed, %d failed" % (passes, failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
