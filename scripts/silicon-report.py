#!/usr/bin/env python3
"""The silicon tables of docs/silicon.md, printed from the program's own cost model:
1. one operation of each kind in each number format (`shadetlm cost --json`);
2. the floating-point operators set against published ratios (Horowitz, ISSCC 2014, 45 nm:
   a float32 add takes 9 times a 32-bit integer add's energy, a float32 product 1.19
   times a 32-bit integer product's), the integer ones here the model's 32-bit fixed point;
3. each golden scene's area, energy a shaded pixel and power, and its largest block
   (`render --stats`, the SystemC engine);
4. the normalize block in each mode and format on golden/sphere;
5. the papers' cost claims in silicon: normal increments (the walker's constant increments,
   re-seeded per line and per 8 pixels, against perspective-correct interpolation; the
   normalization's forward difference against the exact root), bump mapping (classic
   against the paper's paths), object-space texturing against the screen-space filters on
   a plane at 45°, 75° and 85°, each with its error against the golden model; the
   parallax tracers (the refined distance map, the box-gap map, classic and relaxed
   cones, Donnelly's map as published), each at the fewest iterations that reach its own
   least worst error, on golden/parallax-steps.

Usage: scripts/silicon-report.py SHADETLM ROOT
Exit 0; 2 with one line when the program cannot be run or prints what it should not."""
import json
import math
import os
import subprocess
import sys
import tempfile

FORMATS = ["float32", "float16", "fixed:3.20", "fixed:1.12", "fixed:2.8"]
OPS = ["add", "mul", "div", "sqrt", "rsqrt"]
SCENES = ["sphere", "bump-sphere", "bump-plane", "texture-screen", "texture-object", "parallax-steps", "demo"]
# Published energy ratios at 45 nm, 0.9 V (M. Horowitz, "Computing's energy problem (and
# what we can do about it)", ISSCC 2014): float32 add 0.9 pJ over int32 add 0.1 pJ;
# float32 mul 3.7 pJ over int32 mul 3.1 pJ.
PUBLISHED = {"add": 0.9 / 0.1, "mul": 3.7 / 3.1}


def fail(message):
    print("silicon-report: " + message, file=sys.stderr)
    sys.exit(2)


def run(argv):
    try:
        p = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    except OSError as e:
        fail(f"{argv[0]}: {e.strerror}")
    except subprocess.TimeoutExpired:
        fail(f"{' '.join(argv[1:3])}: still running after 600 s")
    if p.returncode != 0:
        fail(f"{' '.join(argv[1:3])}: exit {p.returncode}: {p.stderr.strip()[:200]}")
    return p.stdout


def cost(bin_, formats):
    try:
        return json.loads(run([bin_, "cost", *formats, "--json"]))["formats"]
    except (ValueError, KeyError) as e:
        fail(f"cost --json: not the figures it should print ({e})")


def render_stats(bin_, scene, sets=(), compare=False):
    with tempfile.TemporaryDirectory(prefix="silicon-") as tmp:
        argv = [bin_, "render", scene, "-o", os.path.join(tmp, "f.exr"), "--stats", os.path.join(tmp, "s.json"),
                "--compression", "none"]
        for s in sets:
            argv += ["--set", s]
        if compare:
            argv.append("--compare-reference")
        if sets:  # (the unit's format saturates on some pixels, as calibrate.py's render does; counted in the stats)
            argv.append("--allow-overflow")
        run(argv)
        with open(os.path.join(tmp, "s.json")) as f:
            return json.load(f)


def operations_table(figures):
    out = ["| format | " + " | ".join(f"{o}: µm², pJ" for o in OPS) + " |", "|---|" + "---:|" * len(OPS)]
    for f in FORMATS:
        out.append(f"| {f} | " + " | ".join("%.0f, %.1f" % (figures[f][o]["area_um2"], figures[f][o]["energy_pj"])
                                           for o in OPS) + " |")
    return out


def published_table(figures):
    fx = figures["fixed:15.16"]  # a 32-bit word
    out = ["| operation | float32 ÷ 32-bit fixed, energy (model) | float32 ÷ int32, energy (Horowitz, 45 nm) |"
           " float32 ÷ 32-bit fixed, area (model) |", "|---|---:|---:|---:|"]
    for o, ratio in PUBLISHED.items():
        f = figures["float32"][o]
        out.append("| %s | %.2f | %.2f | %.2f |" % (o, f["energy_pj"] / fx[o]["energy_pj"], ratio,
                                                   f["area_um2"] / fx[o]["area_um2"]))
    return out


def scenes_table(bin_, root):
    out = ["| scene | area, mm² | energy a shaded pixel, nJ | power at the clock, mW | largest block (mm²) |"
           " operations not priced |", "|---|---:|---:|---:|---|---:|"]
    for name in SCENES:
        s = render_stats(bin_, os.path.join(root, "golden", name, "scene.json"))
        si = s["silicon"]
        blocks = [(b["silicon"]["area_mm2"] or 0, n) for n, b in s["blocks"].items() if b["silicon"]["priced"]]
        area, block = max(blocks)
        out.append("| %s | %.3f | %.3g | %.4g | %s (%.3f) | %d |" % (
            name, si["area_mm2"], si["energy_nj_per_shaded_pixel"], si["power_mw"], block, area, si["unpriced_ops"]))
    return out


def normalize_table(bin_, root):
    out = ["| mode | format | units (add, mul, div, sqrt, rsqrt) | area, mm² | energy a pixel, nJ |",
           "|---|---|---|---:|---:|"]
    scene = os.path.join(root, "golden", "sphere", "scene.json")
    for mode in ["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]:
        for fmt in ["float32", "fixed:1.12"]:
            s = render_stats(bin_, scene, [f"pipeline.normalize.mode={mode}", f"pipeline.normalize.format={fmt}"])
            n = s["blocks"]["normalize"]["silicon"]
            units = ", ".join(str(n["units"][o]) for o in OPS)
            out.append("| %s | %s | %s | %.4f | %.3g |" % (mode, fmt, units, n["area_mm2"], n["energy_nj_per_item"]))
    return out


def claim_row(bin_, what, scene, sets, blocks=None):
    """A configuration's arithmetic (the blocks named, or all) and its error, as a table row."""
    s = render_stats(bin_, scene, sets, compare=True)
    chosen = [b for n, b in s["blocks"].items() if blocks is None or n in blocks]
    if not all(b["silicon"]["priced"] and b["silicon"]["area_mm2"] is not None for b in chosen):
        fail(f"{scene} {' '.join(sets)}: a block not priced, or no area (the loop engine?)")
    area = sum(b["silicon"]["area_mm2"] for b in chosen)
    energy = sum(b["silicon"]["energy_nj"] for b in chosen) / max(1, s["pixels"]["shaded"])
    unpriced = sum(b["silicon"]["unpriced_ops"] for b in chosen) / max(1, s["pixels"]["shaded"])
    return "| %s | %.4f | %.4g | %.3g | %.2e | %.1f |" % (what, area, energy, unpriced, s["error"]["rgb"]["rmse"],
                                                       s["error"]["rgb"]["psnr"])


CLAIM_HEAD = ["| configuration | area, mm² | energy a shaded pixel, nJ | tables and fetches a pixel (not priced) "
              "| RMSE | PSNR (dB) |", "|---|---:|---:|---:|---:|---:|"]


def plane_scene(tmp, view, path, texture_sets):
    """A checkered plane `view` degrees off the view direction (as scripts/texture-report.py's)."""
    t = math.radians(view)
    doc = {"format": 1,
           "camera": {"position": [0, 2.6 * math.sin(t), 2.6 * math.cos(t)], "target": [0, 0, 0], "fov_y": 40,
                      "resolution": [192, 144], "near": 0.05, "far": 100, "local_viewer": False},
           "ambient": [0.25, 0.25, 0.25],
           "lights": [{"type": "directional", "direction": [-0.3, -0.6, -0.7], "intensity": 0.8}],
           "textures": {"t": {"type": "checker", "size": [256, 256], "cells": 16}},
           "materials": {"m": {"texture": "t", "ambient": [1, 1, 1], "diffuse": [0.9, 0.9, 0.9],
                               "specular": [0, 0, 0], "path": path}},
           "objects": [{"shape": "plane", "size": [3, 3], "tessellation": [4, 4], "uv_repeat": [2, 2],
                        "material": "m"}]}
    name = os.path.join(tmp, "plane-%d-%s.json" % (view, path))
    with open(name, "w") as f:
        json.dump(doc, f)
    return name


def claims_tables(bin_, root):
    golden = lambda name: os.path.join(root, "golden", name, "scene.json")
    walker = ["normal_interp", "normalize"]
    normal = list(CLAIM_HEAD)
    for what, sets in [("constant increments (affine), no re-seed, exact normalization",
                        ["pipeline.normal_interp.mode=affine", "pipeline.normalize.mode=exact"]),
                       ("constant increments, re-seeded per line", ["pipeline.normal_interp.mode=affine",
                                                                    "pipeline.normal_interp.reseed=line"]),
                       ("constant increments, re-seeded every 8 pixels", ["pipeline.normal_interp.mode=affine",
                                                                          "pipeline.normal_interp.reseed=tile8"]),
                       ("perspective-correct", ["pipeline.normal_interp.mode=perspective"]),
                       ("affine, normalization by forward difference",
                        ["pipeline.normal_interp.mode=affine", "pipeline.normalize.mode=forward-difference"])]:
        normal.append(claim_row(bin_, what, golden("sphere"), sets, walker))
    bump = list(CLAIM_HEAD)
    for path in ["bump-classic", "bump-tangent", "bump-square", "bump-object"]:
        bump.append(claim_row(bin_, path, golden("bump-sphere"), ["materials.red.path=" + path]))
    texture = list(CLAIM_HEAD)
    with tempfile.TemporaryDirectory(prefix="silicon-planes-") as tmp:
        for view in [45, 75, 85]:
            texture.append(claim_row(bin_, "%d°: object space (texel_project)" % view,
                                     plane_scene(tmp, view, "texture-object", None), []))
            for filt in ["ewa", "anisotropic"]:
                texture.append(claim_row(bin_, "%d°: %s" % (view, filt), plane_scene(tmp, view, "texture-screen", None),
                                         ["pipeline.texture_fetch.filter=" + filt]))
    return normal, bump, texture, parallax_table(bin_, golden("parallax-steps"))


def parallax_table(bin_, scene):
    """Each tracer at the smallest of the caps whose worst error is its least (within 1 %)."""
    tracers = [("refined distance map", [], "max_iterations"),
               ("box-gap map", ["parallax.method=distance", "parallax.map=box-gap"], "max_iterations"),
               ("cone", ["parallax.method=cone"], "max_iterations"),
               ("relaxed cone", ["parallax.method=cone", "parallax.cones=relaxed"], "max_iterations"),
               ("Donnelly's map, as published", ["parallax.method=distance", "parallax.map=donnelly"], "steps")]
    out = ["| tracer | iterations (cap or steps) | worst error | RMSE | area, mm² | energy a shaded pixel, nJ |",
           "|---|---:|---:|---:|---:|---:|"]
    for name, sets, limit in tracers:
        runs = []
        for cap in [16, 64, 256]:
            s = render_stats(bin_, scene, ["materials.carved." + k for k in sets + ["parallax.%s=%d" % (limit, cap)]],
                             compare=True)
            runs.append((cap, s))
        floor = min(s["error"]["rgb"]["max"] for _, s in runs)
        cap, s = next((c, s) for c, s in runs if s["error"]["rgb"]["max"] <= floor * 1.01)
        si = s["silicon"]
        if si["area_mm2"] is None or si["unpriced_blocks"]:
            fail(f"{scene}: {name}: a block not priced")
        out.append("| %s | %d | %.2e | %.2e | %.3f | %.4g |" % (name, cap, s["error"]["rgb"]["max"],
                                                                  s["error"]["rgb"]["rmse"], si["area_mm2"],
                                                                  si["energy_nj_per_shaded_pixel"]))
    return out


def main():
    if len(sys.argv) != 3:
        fail("usage: scripts/silicon-report.py SHADETLM ROOT")
    bin_, root = sys.argv[1:]
    if not os.path.isdir(os.path.join(root, "golden")):
        fail(f"{root}: no golden/ folder: not the project's root")
    figures = cost(bin_, FORMATS + ["fixed:15.16"])
    for table in (operations_table(figures), published_table(figures), scenes_table(bin_, root),
                  normalize_table(bin_, root), *claims_tables(bin_, root)):
        print("\n".join(table) + "\n")


if __name__ == "__main__":
    main()
