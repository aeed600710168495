#!/usr/bin/env python3
"""The bump-mapping report (docs/bump-mapping.md): runs the pipeline on scenes/bump/*.json
under each bump path and setting, against the golden model, and prints Markdown tables:
the blocks and costs of each path, the value ranges of its datapaths, its error per
surface, bump depth and view angle, and the error of each approximation on its own.

Usage: scripts/bump-report.py SHADETLM_BINARY [--images DIR]"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("bump-report: " + message, file=sys.stderr)
    sys.exit(2)


if len(sys.argv) not in (2, 4) or len(sys.argv) == 4 and sys.argv[2] != "--images":
    fail("usage: scripts/bump-report.py SHADETLM_BINARY [--images DIR]")
BIN = sys.argv[1]
IMAGES = sys.argv[3] if len(sys.argv) == 4 else None
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if IMAGES is not None and (not IMAGES or os.path.exists(IMAGES) and not os.path.isdir(IMAGES)):
    fail("--images %r: not a folder (the previews'; made when missing)" % IMAGES)
TMP = tempfile.mkdtemp(prefix="bump-report-")
SURFACES = ["quad", "sphere", "torus", "knot"]
PATHS = ["phong", "bump-classic", "bump-tangent", "bump-square", "bump-object"]
ARITH = ["add", "mul", "div", "sqrt", "rsqrt", "lut"]
# The square patch's k: |Pu| = |Pv| = k assumed. Per surface, the mean of |Pu| and |Pv|
# over its uv square (quad: side 2; sphere: 2πr·(2/π) around, πr along; torus: 2πR,
# 2πr; knot: its tube length and girth, roughly) — the best a single k can do.
SQUARE_K = {"quad": 2.0, "sphere": 3.6, "torus": 4.4, "knot": 8.0}
runs = 0


def render(surface, sets, name="run", preview=None):
    """Renders scenes/bump/SURFACE.json with --set overrides; returns (stats, exr path)."""
    global runs
    runs += 1
    exr = os.path.join(TMP, name + ".exr")
    stats = os.path.join(TMP, name + ".json")
    cmd = [BIN, "render", os.path.join(ROOT, "scenes/bump", surface + ".json"), "-o", exr, "--stats", stats,
           "--compare-reference", "--allow-overflow"]  # a format's overflows are counted in the stats
    if preview:
        cmd += ["--preview", preview]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        return json.load(f), exr


def psnr_between(a, b):
    out = subprocess.run([BIN, "compare", a, b, "--layer", "RGB", "--json"], stdout=subprocess.PIPE, text=True)
    return json.loads(out.stdout)["layers"]["RGB"]["psnr"]


def path_sets(path, surface):
    sets = ["materials.bumpy.path=" + path] if path != "phong" else ["materials.bumpy.path=phong",
                                                                      "materials.bumpy.height_scale=0"]
    if path == "bump-square":
        sets.append("materials.bumpy.square_k=%g" % SQUARE_K[surface])
    return sets


def db(x):
    x = float(x)  # compare --json writes "inf"
    return "∞" if math.isinf(x) else "%.1f" % x


def err(stats):
    e = stats["error"]["rgb"]
    return e["max"], e["rmse"], e["psnr"]


def per_pixel(stats, keys):
    return sum(stats["ops_per_shaded_pixel"][k] for k in keys)


def block_per_pixel(stats, block, keys):
    b = stats["blocks"].get(block)
    if not b:
        return 0.0
    return sum(b["ops"][k] for k in keys) / stats["pixels"]["shaded"]


print("## Blocks and cost per path (claims 1 and 2)\n")
print("Sphere (`scenes/bump/sphere.json`, 256×192); operations per shaded pixel, summed over the blocks "
      "(setup's per-triangle work included); the texture fetch counted apart. Under a directional light "
      "with the viewer at infinity, Phong needs no L and H interpolation at all; under a point light with a "
      "local viewer it interpolates and normalizes them, as the paper's Fig. 1 hardware always does.\n")
print("| lighting | path | blocks working | arithmetic / px | of which bump_fetch | of which setup | the rest: per-pixel datapaths | without the texture unit (arithmetic / px less bump_fetch's) | texel fetches / px | memory lines / px | cycles / px | bottleneck | run time (ms) | PSNR (dB) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
LOCAL = ["camera.local_viewer=true", 'lights=[{"type":"point","position":[2,2,3]}]']
H_FIG1 = "pipeline.vector_interp.h=interpolated"
for lighting, extra, path, label in [(l, e, p, p) for l, e in [("directional, at infinity", []), ("point, local viewer", LOCAL)]
                                     for p in PATHS] + [("point, local viewer", LOCAL + [H_FIG1], "phong",
                                                         "phong, H interpolated (Fig. 1)")]:
    preview = os.path.join(IMAGES, "bump-report-" + path + ".png") if IMAGES and not extra else None
    s, _ = render("sphere", path_sets(path, "sphere") + extra, preview=preview)
    blocks = [b for b in ["normal_interp", "bump_fetch", "bump_perturb", "normal_mux", "normalize", "vector_interp"]
              if b in s["blocks"] and s["blocks"][b]["packets"] > 0]
    total = per_pixel(s, ARITH)
    fetch_arith = block_per_pixel(s, "bump_fetch", ARITH)
    setup_arith = block_per_pixel(s, "setup", ARITH)
    print("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f | %s | %.1f | %s |" % (
        lighting, label, ", ".join(blocks), total, fetch_arith, setup_arith, total - fetch_arith - setup_arith,
        total - fetch_arith, per_pixel(s, ["fetch"]),
        per_pixel(s, ["line"]), s["frame_cycles"] / s["pixels"]["shaded"], s["bottleneck"], 1000 * s["wall_s"],
        db(err(s)[2])))
print("\nBlocks working: those between raster and lighting that process packets of the path (elaborated "
      "blocks that the path bypasses are left out: `normal_interp` for the fetched-normal paths). Setup is per "
      "triangle (this sphere has about 10 pixels a triangle). Cycles per pixel: frame cycles over shaded pixels, "
      "default timing (docs/configuration.md).\n")

print("### Operations per pixel by kind, per block\n")
print("| path | block | add | mul | div | sqrt | lut | fetch | line |")
print("|---|---|---|---|---|---|---|---|---|")
for path in PATHS:
    s, _ = render("sphere", path_sets(path, "sphere"))
    for block in ["setup", "normal_interp", "bump_fetch", "bump_perturb", "normal_mux", "normalize", "vector_interp", "lighting"]:
        if block not in s["blocks"]:
            continue
        o = s["blocks"][block]["ops"]
        n = s["pixels"]["shaded"]
        if sum(o.values()) == 0 and block not in ("normal_mux",):
            continue
        print("| %s | %s | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
            path, block, o["add"] / n, o["mul"] / n, o["div"] / n, o["sqrt"] / n, o["lut"] / n, o["fetch"] / n, o["line"] / n))

print("\n## Value ranges on the datapaths (claim 2)\n")
print("Largest magnitude seen on each datapath (the integer bits a fixed-point datapath needs). "
      "Quad of side 2 and of side 100 (uv over [0, 1] both), a point light and a local viewer.\n")
print("| path | quad side | normal_interp N (N/w) | bump_fetch fetched | bump_perturb n×Pv | bump_perturb Pu×n | bump_perturb N' | vector_interp L (before normalize) | vector_interp H |")
print("|---|---|---|---|---|---|---|---|---|")
for side in [2, 100]:
    for path in ["phong", "bump-classic", "bump-tangent"]:
        sets = path_sets(path, "quad") + [
            "objects.0.size=[%d,%d]" % (side, side), "camera.position=[0,%g,%g]" % (0.9 * side, 1.1 * side),
            "camera.far=%g" % (10 * side), "camera.local_viewer=true",
            'lights=[{"type":"point","position":[%g,%g,%g]}]' % (0.3 * side, 0.5 * side, 0.2 * side)]
        s, _ = render("quad", sets)

        def mag(block, name):
            r = s["blocks"].get(block, {}).get("ranges", {}).get(name)
            return "—" if not r else "%.3g" % max(-r[0], r[1])
        print("| %s | %d | %s | %s | %s | %s | %s | %s | %s |" % (
            path, side, mag("normal_interp", "n"), mag("bump_fetch", "fetched"), mag("bump_perturb", "n_x_pv"),
            mag("bump_perturb", "pu_x_n"), mag("bump_perturb", "perturbed"), mag("vector_interp", "l"),
            mag("vector_interp", "h")))

print("\n## Error against the golden model, per surface (claim 3)\n")
print("Default settings (trilinear, unit L and H), one directional light, viewer at infinity, height scale 0.03. "
      "Colour error: max | RMSE | PSNR (dB).\n")
print("| surface | bump-classic | bump-tangent | bump-square (k) | bump-object |")
print("|---|---|---|---|---|")
for surface in SURFACES:
    cells = []
    for path in PATHS[1:]:
        s, _ = render(surface, path_sets(path, surface))
        mx, rmse, psnr = err(s)
        cell = "%.3f \\| %.4f \\| %s" % (mx, rmse, db(psnr))
        if path == "bump-square":
            cell += " (k %g)" % SQUARE_K[surface]
        cells.append(cell)
    print("| %s | %s |" % (surface, " | ".join(cells)))

print("\n### Bump depth, per surface\n")
print("PSNR (dB) against the golden model: classic / tangent (trilinear, unit L and H).\n")
print("| surface | depth 0.01 | depth 0.03 | depth 0.1 |")
print("|---|---|---|---|")
for surface in SURFACES:
    row = []
    for depth in [0.01, 0.03, 0.1]:
        vals = []
        for path in ["bump-classic", "bump-tangent"]:
            s, _ = render(surface, path_sets(path, surface) + ["materials.bumpy.height_scale=%g" % depth])
            vals.append(db(err(s)[2]))
        row.append(" / ".join(vals))
    print("| %s | %s |" % (surface, " | ".join(row)))

print("\n### Bump depth and view angle (quad)\n")
print("PSNR (dB) against the golden model: classic / tangent / square (k 2). Elevation of the view above the quad.\n")
depths = [0.01, 0.03, 0.1]
print("| elevation | " + " | ".join("depth %g" % d for d in depths) + " |")
print("|---|" + "---|" * len(depths))
for elevation in [60, 30, 15]:
    row = []
    for depth in depths:
        e = math.radians(elevation)
        cam = "camera.position=[0,%.4f,%.4f]" % (2.8 * math.sin(e), 2.8 * math.cos(e))
        vals = []
        for path in ["bump-classic", "bump-tangent", "bump-square"]:
            s, _ = render("quad", path_sets(path, "quad") + [cam, "materials.bumpy.height_scale=%g" % depth])
            vals.append(db(err(s)[2]))
        row.append(" / ".join(vals))
    print("| %d° | %s |" % (elevation, " | ".join(row)))

print("\n## Each approximation on its own\n")
print("### Vertex-only transformation of L and H\n")
print("bump-tangent with height scale 0: the fetched normal is exactly +z, no filter error, "
      "so what is left is L and H transformed at the vertices and interpolated. "
      "PSNR (dB) against the golden model: `unit` (the paper's: unit L and H at the vertices) / "
      "`affine` (L = light − P and V = eye − P at the vertices, H per pixel).\n")
print("| surface | directional light, viewer at infinity | point light, local viewer |")
print("|---|---|---|")
for surface in SURFACES:
    row = []
    for local in [False, True]:
        vals = []
        for mode in ["unit", "affine"]:
            sets = path_sets("bump-tangent", surface) + ["materials.bumpy.height_scale=0",
                                                          "pipeline.vector_interp.bump_vectors=" + mode]
            if local:
                sets += ["camera.local_viewer=true", 'lights=[{"type":"point","position":[0.8,1.2,1.0]}]']
            s, _ = render(surface, sets)
            vals.append(db(err(s)[2]))
        row.append(" / ".join(vals))
    print("| %s | %s |" % (surface, " | ".join(row)))

print("\n### Filtering and renormalization\n")
print("bump-tangent; PSNR (dB) against the golden model with mip levels renormalized / not; "
      "texel fetches and memory lines per pixel. The quad seen at 15° (minification, anisotropic footprints) "
      "and the sphere.\n")
print("| filter | quad 15°: PSNR renorm / plain | fetches / px | lines / px | sphere: PSNR renorm / plain | fetches / px | lines / px |")
print("|---|---|---|---|---|---|---|")
low = "camera.position=[0,%.4f,%.4f]" % (2.8 * math.sin(math.radians(15)), 2.8 * math.cos(math.radians(15)))
for filt, probes in [("nearest", 1), ("bilinear", 1), ("trilinear", 1), ("anisotropic", 4), ("anisotropic", 8)]:
    row = ["%s%s" % (filt, " %d" % probes if filt == "anisotropic" else "")]
    for surface, extra in [("quad", [low, "materials.bumpy.height_scale=0.01", "textures.relief.cells=32"]), ("sphere", [])]:
        vals, cost = [], None
        for renorm in ["true", "false"]:
            s, _ = render(surface, path_sets("bump-tangent", surface) + extra + [
                "pipeline.bump_fetch.filter=" + filt, "pipeline.bump_fetch.probes=%d" % probes,
                "pipeline.bump_fetch.renormalize_mips=" + renorm])
            vals.append("%.2f" % float(err(s)[2]))
            cost = "%.2f | %.2f" % (per_pixel(s, ["fetch"]), per_pixel(s, ["line"]))
        row += [" / ".join(vals), cost]
    print("| " + " | ".join(row) + " |")

print("\n### Stored normal maps\n")
print("The fetched-normal paths with their maps stored as a chip would (`pipeline.bump_fetch.stored`): "
      "(N + 1) / 2 in 8, 10 or 16 bits a component, rounded to nearest, mip levels too. PSNR (dB) against the "
      "golden model (its truth stays the height field), and in brackets the largest colour difference from the "
      "float map's frame.\n")
STORED = ["float", "unorm16", "unorm10", "unorm8"]
print("| surface | path | " + " | ".join(STORED) + " |")
print("|---|---|" + "---|" * len(STORED))
for surface in SURFACES:
    for path in ["bump-tangent", "bump-object"]:
        cells, base = [], None
        for stored in STORED:
            st, exr = render(surface, path_sets(path, surface) + ["pipeline.bump_fetch.stored=" + stored], stored)
            if base is None:
                base, cells = exr, [db(err(st)[2])]
                continue
            out = subprocess.run([BIN, "compare", exr, base, "--layer", "RGB", "--json"], stdout=subprocess.PIPE, text=True)
            cells.append("%s (%.1e)" % (db(err(st)[2]), float(json.loads(out.stdout)["layers"]["RGB"]["max"])))
        print("| %s | %s | %s |" % (surface, path, " | ".join(cells)))

print("\n### The square-patch assumption\n")
print("bump-square against bump-tangent, the same filter and L, H: the difference between their frames is the "
      "square-patch error alone. PSNR (dB) of square against tangent, and of each against the golden model.\n")
print("| surface | k | square vs tangent | square vs golden | tangent vs golden |")
print("|---|---|---|---|---|")
for surface in SURFACES:
    sq, sq_exr = render(surface, path_sets("bump-square", surface), "square")
    tg, tg_exr = render(surface, path_sets("bump-tangent", surface), "tangent")
    print("| %s | %g | %s | %s | %s |" % (surface, SQUARE_K[surface], db(psnr_between(sq_exr, tg_exr)),
                                         db(err(sq)[2]), db(err(tg)[2])))

shutil.rmtree(TMP, ignore_errors=True)
print("\n%d renders; `%s`." % (runs, " ".join(["scripts/bump-report.sh"] + (["--images", IMAGES] if IMAGES else []))))
