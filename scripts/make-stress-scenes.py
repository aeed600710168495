#!/usr/bin/env python3
"""Writes the numerical-stability stress scenes into scenes/stress/ (small JSON and OBJ
files, committed; re-run this script after changing it). Each stresses one thing the
pipeline's float datapaths meet in the worst case; testbenches/test_stress.cpp renders
them all and fails on any NaN or infinity in a frame, or a coverage that differs from
the golden model's.

Usage: scripts/make-stress-scenes.py [OUT_DIR]"""
import json
import math
import os
import sys

if len(sys.argv) > 2:
    print("make-stress-scenes: usage: scripts/make-stress-scenes.py [OUT_DIR]", file=sys.stderr)
    sys.exit(2)
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "stress")
try:
    os.makedirs(os.path.join(OUT, "assets"), exist_ok=True)
except OSError as e:
    print("make-stress-scenes: %s: cannot make it: %s" % (os.path.join(OUT, "assets"), e.strerror or e), file=sys.stderr)
    sys.exit(2)
LIGHTS = [{"type": "directional", "direction": [-0.3, -0.4, -1.0]},
          {"type": "point", "position": [0.5, 0.8, 1.5], "intensity": 0.5}]


def scene(name, camera, objects, checks, textures=None, materials=None, pipeline=None):
    d = {"format": 1, "camera": camera, "lights": LIGHTS, "objects": objects}
    if textures:
        d["textures"] = textures
    if materials:
        d["materials"] = materials
    if pipeline:
        d["pipeline"] = pipeline
    with open(os.path.join(OUT, name + ".json"), "w") as f:
        json.dump(d, f, indent=1)
        f.write("\n")
    return name, checks


def obj(name, vertices, normals, faces, uvs=None):
    with open(os.path.join(OUT, "assets", name + ".obj"), "w") as f:
        f.write("# scripts/make-stress-scenes.py\n")
        for v in vertices:
            f.write("v %.17g %.17g %.17g\n" % tuple(v))
        for n in normals:
            f.write("vn %.17g %.17g %.17g\n" % tuple(n))
        for t in uvs or [(0, 0)]:
            f.write("vt %.17g %.17g\n" % tuple(t))
        for face in faces:
            f.write("f " + " ".join("%d/%d/%d" % (i + 1, (i if uvs else 0) + 1, i + 1) for i in face) + "\n")


made = []
# Spans of 1 to 16384 pixels: a triangle across a 16384-pixel-wide frame (its rows run
# from 1 pixel at the tip to the full width).
made.append(scene("long-spans", {"position": [0, 0, 1], "target": [0, 0, 0], "fov_y": 0.5,
                                 "resolution": [16384, 8], "near": 0.1, "far": 10, "local_viewer": True},
                  [{"shape": "mesh", "file": "assets/wide-triangle.obj"}], "spans of 1 … 16384 pixels"))
obj("wide-triangle", [(-9.0, -0.0044, 0), (9.0, -0.0044, 0), (9.0, 0.0044, 0)], [(0, 0, 1), (0.3, 0, 0.95), (-0.3, 0.1, 0.95)],
    [(0, 1, 2)])
# A triangle 16384 pixels tall.
made.append(scene("tall-triangle", {"position": [0, 0, 1], "target": [0, 0, 0], "fov_y": 60,
                                    "resolution": [8, 16384], "near": 0.1, "far": 10, "local_viewer": True},
                  [{"shape": "mesh", "file": "assets/tall-triangle.obj"}], "a triangle 16384 pixels tall"))
obj("tall-triangle", [(-0.0003, -0.6, 0), (0.0003, -0.6, 0), (0, 0.6, 0)], [(0.2, -0.3, 0.9), (-0.2, -0.3, 0.9), (0, 0.4, 0.9)],
    [(0, 1, 2)])
# Slivers (areas far below 1e-6 px²), near-degenerate and degenerate triangles (a
# repeated vertex, collinear vertices).
e = 1e-9
obj("slivers", [(-1, -1, 0), (1, -1, 0), (1, -1 + e, 0),           # a sliver along the bottom
                (-1, 0, 0), (1, 0, 0), (0, 0, 0),                  # collinear: no area
                (0, 0.5, 0), (0, 0.5, 0), (0.5, 0.8, 0),           # a repeated vertex
                (-1, 0.9, 0), (1, 0.9, 0), (1, 0.9 + 1e-7, 0)],    # another sliver, nearly degenerate
    [(0, 0, 1)] * 12, [(0, 1, 2), (3, 4, 5), (6, 7, 8), (9, 10, 11)])
made.append(scene("slivers", {"position": [0, 0, 2.5], "target": [0, 0, 0], "resolution": [256, 256]},
                  [{"shape": "mesh", "file": "assets/slivers.obj"}], "slivers and degenerate triangles"))
# Vertex normals nearly opposite: the interpolated normal passes close to zero length.
obj("opposite-normals", [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
    [(0, 0, 1), (0.001, 0, -1), (0, 0, 1), (-0.001, 0.001, -1)], [(0, 1, 2), (0, 2, 3)])
made.append(scene("opposite-normals", {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [256, 256]},
                  [{"shape": "mesh", "file": "assets/opposite-normals.obj"}], "vertex normals nearly opposite"))
# Normals of near-zero length in the file (the loader makes them unit; opposite ones
# then cancel in the middle of the triangle).
obj("tiny-normals", [(-1, -1, 0), (1, -1, 0), (0, 1, 0)], [(0, 0, 1e-30), (1e-30, 0, -1e-30), (0, 1e-30, 1e-30)], [(0, 1, 2)])
made.append(scene("tiny-normals", {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [128, 128]},
                  [{"shape": "mesh", "file": "assets/tiny-normals.obj"}], "normals of near-zero length"))
# Coordinates at ±1e6.
made.append(scene("far-coordinates", {"position": [0, 2e5, 1e6], "target": [0, 0, -1e6], "fov_y": 40,
                                      "resolution": [256, 192], "near": 1, "far": 1e7, "local_viewer": True},
                  [{"shape": "plane", "size": [1e6, 1e6], "tessellation": [8, 8],
                    "transform": {"rotate": [-90, 0, 0], "translate": [0, -1e5, -1e6]}},
                   {"shape": "sphere", "radius": 2e5, "transform": {"translate": [1e5, 0, -1e6]}}],
                  "coordinates at ±1e6"))
# Geometry across and just beyond the near plane.
made.append(scene("near-plane", {"position": [0, 0.05, 0], "target": [0, 0, -1], "resolution": [256, 192],
                                 "near": 0.1, "far": 100, "local_viewer": True},
                  [{"shape": "plane", "size": [20, 20], "tessellation": [4, 4], "transform": {"rotate": [-90, 0, 0]}},
                   {"shape": "sphere", "radius": 0.3, "transform": {"translate": [0.1, 0.05, -0.25]}}],
                  "triangles across the near plane"))
# Grazing views of planes, 85° to 89.9° from the normal.
for angle in [85, 88, 89, 89.5, 89.9]:
    t = math.radians(angle)
    made.append(scene("grazing-%s" % str(angle).replace(".", "_"),
                      {"position": [0, 3 * math.cos(t), 3 * math.sin(t)], "target": [0, 0, 0], "resolution": [256, 192],
                       "near": 0.01, "far": 1000, "local_viewer": True},
                      [{"shape": "plane", "size": [400, 400], "tessellation": [2, 2], "material": "m",
                        "transform": {"rotate": [-90, 0, 0]}}],
                      "a plane seen at %s° from its normal" % angle,
                      textures={"t": {"type": "checker", "size": [64, 64], "cells": 8}},
                      materials={"m": {"texture": "t", "path": "texture-screen"}},
                      pipeline={"texture_fetch": {"filter": "anisotropic"}}))
# Height maps with full-depth steps, through every bump path.
for path in ["bump-classic", "bump-tangent", "bump-square", "bump-object"]:
    made.append(scene("steps-" + path, {"position": [0, 1.5, 2.0], "target": [0, 0, 0], "resolution": [192, 144],
                                         "local_viewer": True},
                      [{"shape": "plane", "size": [2, 2], "material": "m", "transform": {"rotate": [-90, 0, 0]}},
                       {"shape": "sphere", "radius": 0.5, "material": "m", "transform": {"translate": [0, 0.5, 0]}}],
                      "full-depth steps in the height map, " + path,
                      textures={"steps": {"type": "steps", "size": [64, 64], "cells": 4, "levels": 2}},
                      materials={"m": {"height_map": "steps", "height_scale": 1.0, "path": path}}))
# Full-depth steps under the parallax tracer, at a low view (long rays, many cells).
for method in ["relief", "distance"]:
    made.append(scene("steps-parallax-" + method, {"position": [0, 0.35, 2.0], "target": [0, 0, 0],
                                                  "resolution": [192, 144], "local_viewer": True},
                      [{"shape": "plane", "size": [2, 2], "material": "m", "transform": {"rotate": [-90, 0, 0]}}],
                      "full-depth steps in the height map, parallax " + method + " at a low view",
                      textures={"steps": {"type": "steps", "size": [64, 64], "cells": 4, "levels": 2},
                                "t": {"type": "checker", "size": [64, 64], "cells": 8}},
                      materials={"m": {"texture": "t", "height_map": "steps", "path": "parallax",
                                       "parallax": {"method": method, "depth": 0.1}}}))
# Object-space texturing (texel projection and splat weights) on a plane seen at 85°.
made.append(scene("grazing-object-85", {"position": [0, 3 * math.cos(math.radians(85)), 3 * math.sin(math.radians(85))],
                                        "target": [0, 0, 0], "resolution": [192, 144], "local_viewer": True},
                  [{"shape": "plane", "size": [8, 8], "tessellation": [2, 2], "material": "m",
                    "transform": {"rotate": [-90, 0, 0]}}],
                  "texel projection and splat weights on a plane seen at 85° from its normal",
                  textures={"t": {"type": "checker", "size": [64, 64], "cells": 8}},
                  materials={"m": {"texture": "t", "path": "texture-object"}}))
with open(os.path.join(OUT, "README.md"), "w") as f:
    f.write("# Stress scenes\n\nWritten by `scripts/make-stress-scenes.py` (edit it, not these files); "
            "rendered by `testbenches/test_stress.cpp`.\n\n| scene | stresses |\n|---|---|\n")
    for name, checks in made:
        f.write("| `%s.json` | %s |\n" % (name, checks))
print("%d stress scenes in %s" % (len(made), os.path.normpath(OUT)))
