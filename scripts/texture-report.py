#!/usr/bin/env python3
"""The texturing report (docs/object-space-texturing.md): object-space texturing
(texel_project) against the screen-space filters of the texture unit, on a checker, a
fine line pattern and a photograph, on planes at 0°, 45°, 75° and 85° from the view
direction and on a sphere, against the footprint-averaged golden model, with both of
texel_project's LOD rules; then the plane every 5° from 0° to 85°, object space against
16-probe anisotropic filtering, and the angles where anisotropic filtering starts to
win. Prints Markdown.

Usage: scripts/texture-report.py SHADETLM_BINARY PHOTO_PNG_OR_EMPTY [--images DIR]"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("texture-report: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) not in (3, 5) or len(sys.argv) == 5 and sys.argv[3] != "--images":
    fail("usage: scripts/texture-report.py SHADETLM_BINARY PHOTO_PNG_OR_EMPTY [--images DIR]")
BIN, PHOTO = sys.argv[1], sys.argv[2]
IMAGES = sys.argv[4] if len(sys.argv) == 5 else None
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if PHOTO and not os.path.isfile(PHOTO):
    fail("%s: no such file (the photograph; \"\" for none)" % PHOTO)
if IMAGES is not None and (not IMAGES or os.path.exists(IMAGES) and not os.path.isdir(IMAGES)):
    fail("--images %r: not a folder (the previews'; made when missing)" % IMAGES)
TMP = tempfile.mkdtemp(prefix="texture-report-")
ARITH = ["add", "mul", "div", "sqrt", "rsqrt", "lut"]
CONFIGS = [("object space (texel_project)", "texture-object", None, 4),
           ("object space, constant z′", "texture-object", "constant-z", 4),
           ("nearest", "texture-screen", "nearest", 4), ("bilinear", "texture-screen", "bilinear", 4),
           ("trilinear", "texture-screen", "trilinear", 4), ("anisotropic 4", "texture-screen", "anisotropic", 4),
           ("anisotropic 16", "texture-screen", "anisotropic", 16), ("EWA", "texture-screen", "ewa", 4)]
TEXTURES = {
    "checker": {"type": "checker", "size": [256, 256], "cells": 16},
    "fine lines": {"type": "bricks", "size": [512, 512], "cells": [32, 64], "gap": 0.1,
                   "colors": [[0.9, 0.9, 0.9], [0.05, 0.05, 0.05]]},
}
if PHOTO:
    TEXTURES["photograph"] = {"type": "image", "file": PHOTO}
runs = 0


def scene(texture, view):
    """A textured plane at `view` degrees from the view direction, or a sphere."""
    s = {"format": 1,
         "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "resolution": [192, 144],
                    "near": 0.05, "far": 100, "local_viewer": False},
         "ambient": [0.25, 0.25, 0.25],
         "lights": [{"type": "directional", "direction": [-0.3, -0.6, -0.7], "intensity": 0.8}],
         "textures": {"t": TEXTURES[texture]},
         "materials": {"m": {"texture": "t", "ambient": [1, 1, 1], "diffuse": [0.9, 0.9, 0.9],
                             "specular": [0, 0, 0], "path": "texture-object"}}}
    if view == "sphere":
        s["objects"] = [{"shape": "sphere", "radius": 1, "segments": 64, "rings": 32, "material": "m"}]
    else:
        # The plane faces +z; the camera looks at its centre from `view` degrees off its normal.
        t = math.radians(view)
        s["camera"]["position"] = [0, 2.6 * math.sin(t), 2.6 * math.cos(t)]
        s["objects"] = [{"shape": "plane", "size": [3, 3], "tessellation": [4, 4], "uv_repeat": [2, 2],
                         "material": "m"}]
    return s


def render(doc, path, filt, probes, units=4, preview=None):
    global runs
    runs += 1
    doc = json.loads(json.dumps(doc))
    doc["materials"]["m"]["path"] = path
    doc["pipeline"] = {"texel_project": {"units": units}}
    if path == "texture-object" and filt:  # texel_project's LOD rule
        doc["pipeline"]["texel_project"]["lod"] = filt
    elif filt:
        doc["pipeline"]["texture_fetch"] = {"filter": filt, "probes": probes}
    name = os.path.join(TMP, "s%d" % runs)
    with open(name + ".json", "w") as f:
        json.dump(doc, f)
    cmd = [BIN, "render", name + ".json", "-o", name + ".exr", "--stats", name + ".stats.json", "--compare-reference"]
    if preview:
        cmd += ["--preview", preview]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(name + ".stats.json") as f:
        return json.load(f)


def block(stats, name):
    return stats["blocks"].get(name, {})


def figures(stats, path):
    b = block(stats, "texel_project" if path == "texture-object" else "texture_fetch")
    n = max(1, stats["pixels"]["shaded"])
    ops = b.get("ops", {})
    d = b.get("details", {})
    lods = d.get("lod_computations", 0)
    return {"psnr": float(stats["error"]["rgb"]["psnr"]), "rmse": stats["error"]["rgb"]["rmse"],
            "fetch": ops.get("fetch", 0) / n, "arith": sum(ops.get(k, 0) for k in ARITH) / n,
            "lines": ops.get("line", 0) / n, "lods": lods, "holes": d.get("holes", 0), "pixels": n}


views = [0, 45, 75, 85, "sphere"]
results = {}
for texture in TEXTURES:
    for view in views:
        doc = scene(texture, view)
        for label, path, filt, probes in CONFIGS:
            preview = None
            if IMAGES and texture == "checker" and view == 85:
                name = "object-z" if "z′" in label else label.split(" ")[0].lower()
                preview = os.path.join(IMAGES, "texture-85-%s.png" % name)
            results[(texture, view, label)] = figures(render(doc, path, filt, probes, preview=preview), path)
        if IMAGES and texture == "checker" and view == 85:  # and the golden model's
            with open(os.path.join(TMP, "golden.json"), "w") as f:
                json.dump(doc, f)
            subprocess.run([BIN, "reference", os.path.join(TMP, "golden.json"), "-o", os.path.join(TMP, "golden.exr"),
                            "--preview", os.path.join(IMAGES, "texture-85-golden.png")], check=True,
                           stdout=subprocess.DEVNULL)

print("## Accuracy against the golden model (claim 1)\n")
print("PSNR (dB) of the colour against the footprint-averaged golden model (16×16 stratified samples per pixel); "
      "192×144; planes at an angle from the view direction, and a sphere.\n")
for texture in TEXTURES:
    print("### %s\n" % texture)
    print("| method | " + " | ".join(("%d°" % v) if v != "sphere" else "sphere" for v in views) + " |")
    print("|---|" + "---|" * len(views))
    for label, _, _, _ in CONFIGS:
        cells = []
        for view in views:
            r = results[(texture, view, label)]
            best = max(results[(texture, view, l)]["psnr"] for l, _, _, _ in CONFIGS)
            cell = "%.1f" % r["psnr"]
            cells.append("**%s**" % cell if r["psnr"] == best else cell)
        print("| %s | %s |" % (label, " | ".join(cells)))
    print()

print("## Cost per pixel (claims 2 and 3)\n")
print("The texturing block only (texel_project, or texture_fetch): texel fetches, arithmetic operations "
      "(add, mul, div, sqrt, lut) and memory lines per shaded pixel; LOD computations for the frame; holes "
      "(covered pixels no splat reached). Checker. Memory lines: the texture unit reads a pixel's lines with "
      "no cache between pixels; texel_project streams a triangle's texels with a buffer of one row of tiles "
      "— two different cache models.\n")
print("| method | view | texel fetches / px | arithmetic / px | lines / px | LOD computations | pixels | holes |")
print("|---|---|---|---|---|---|---|---|")
for view in views:
    for label, _, _, _ in CONFIGS:
        r = results[("checker", view, label)]
        print("| %s | %s | %.1f | %.1f | %.2f | %d | %d | %d |" % (
            label, ("%d°" % view) if view != "sphere" else "sphere", r["fetch"], r["arith"], r["lines"], r["lods"],
            r["pixels"], r["holes"]))

print("\n## Parallel splat units (claim 4)\n")
print("texel_project on the checker plane at 75°: units own interleaved 4×4 pixel tiles and a texel goes to "
      "the unit of its first pixel; the texels of the busiest unit, against an even split (round robin); the "
      "share of splats that land in another unit's tile (writes across units); the pass's cycles at II 1.\n")
print("| units | texels | busiest unit (tiles) | busiest unit (round robin) | balance (texels / units / busiest) | splats across units | cycles | speed-up |")
print("|---|---|---|---|---|---|---|---|")
base = None
for units in [1, 2, 4, 8, 16, 32]:
    s = render(scene("checker", 75), "texture-object", None, 4, units)
    d = block(s, "texel_project")["details"]
    base = base or d["cycles"]
    print("| %d | %d | %d | %d | %.2f | %.0f %% | %d | %.2f |" % (
        units, d["texels"], d["busiest_unit_texels"], d["busiest_unit_texels_round_robin"],
        d["texels"] / units / max(1, d["busiest_unit_texels"]), 100.0 * d["cross_unit_splats"] / max(1, d["splats"]),
        d["cycles"], base / d["cycles"]))

# Where object-space texturing stops beating 16-probe anisotropic filtering: a sweep over
# the plane's angle from the view direction, every 5°, with both LOD rules.
SWEEP = list(range(0, 90, 5))
RIVALS = [c for c in CONFIGS if c[0].startswith("object space")] + [c for c in CONFIGS if c[0] == "anisotropic 16"]
sweep = {}
for texture in TEXTURES:
    for view in SWEEP:
        doc = scene(texture, view)
        for label, path, filt, probes in RIVALS:
            sweep[(texture, view, label)] = figures(render(doc, path, filt, probes), path)
print("\n## Object space against 16-probe anisotropic filtering, angle by angle (claim 3)\n")
print("The plane at every 5° from the view direction; PSNR against the golden model (dB), and the texturing block's "
      "arithmetic and texel fetches per shaded pixel, for object space with each LOD rule and for anisotropic 16.\n")
for texture in TEXTURES:
    print("### %s, by angle\n" % texture)
    print("| angle | PSNR: object, object z′, aniso 16 | arithmetic / px: object, object z′, aniso 16 | "
          "fetches / px: object, object z′, aniso 16 |")
    print("|---|---|---|---|")
    for view in SWEEP:
        r = [sweep[(texture, view, c[0])] for c in RIVALS]
        print("| %d° | %s | %s | %s |" % (view, " / ".join("%.1f" % x["psnr"] for x in r),
                                          " / ".join("%.0f" % x["arith"] for x in r),
                                          " / ".join("%.1f" % x["fetch"] for x in r)))
    print()


def crossover(texture, label, worse):
    """The first angle of the sweep at which anisotropic 16 beats object space (`worse`)."""
    for view in SWEEP:
        if worse(sweep[(texture, view, label)], sweep[(texture, view, "anisotropic 16")]):
            return "%d°" % view
    return "none up to %d°" % SWEEP[-1]


print("### Crossover angles\n")
print("The first angle of the sweep at which 16-probe anisotropic filtering beats object-space texturing: a higher "
      "PSNR, fewer arithmetic operations, fewer texel fetches per pixel.\n")
print("| texture | LOD rule | error | arithmetic | fetches |")
print("|---|---|---|---|---|")
for texture in TEXTURES:
    for label, _, _, _ in RIVALS[:2]:
        print("| %s | %s | %s | %s | %s |" % (
            texture, "constant z′ (the paper's)" if "z′" in label else "most magnified vertex",
            crossover(texture, label, lambda o, a: a["psnr"] > o["psnr"]),
            crossover(texture, label, lambda o, a: a["arith"] < o["arith"]),
            crossover(texture, label, lambda o, a: a["fetch"] < o["fetch"])))

print("\n%d renders; `scripts/texture-report.sh%s`." % (runs, " --images " + IMAGES if IMAGES else ""))
shutil.rmtree(TMP, ignore_errors=True)
