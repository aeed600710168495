#!/usr/bin/env bash
# The memory model's figures (docs/memory.md), every one printed here, on the benchmark
# scenes at 1920×1080 under pipeline.memory.model=dram (the default DRAM: 200 cycles,
# 32 bytes a cycle):
#  1. frame cycles, DRAM bytes per fetched pixel and hit rate against the texture
#     unit's cache size (1 … 64 KiB): the bump fetch (bench-bump), the screen-space
#     filters trilinear, anisotropic and EWA (bench-texture's texture-screen objects)
#     and texel_project (bench-texture's floor: its texel and accumulator caches);
#  2. the three layouts at the default 16 KiB cache, for the bump fetch, the trilinear
#     filter and the framebuffer's colour;
#  3. the bump-mapping paper's cost claim with the texture unit and its memory counted:
#     Phong (bench) against bump (bench-bump), ideal memory against the DRAM;
#  4. the object-space texturing paper's comparison in cycles and bytes: a checkered
#     plane at 0°, 45°, 75° and 85° from the view direction (640×480), texel_project
#     against the screen-space filters, and its accumulators at 16, 32 and 64 bits.
# Usage: scripts/memory.sh [--doc]   (--doc: the tables into docs/memory.md, between
# its <!-- memory:N --> markers). About 8 minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/app/shadetlm
[[ -x $bin ]] || "$root/scripts/build.sh" >/dev/null
doc=0
[[ ${1:-} == --doc ]] && doc=1
out=$root/out/memory
mkdir -p "$out"
python3 - "$bin" "$root" "$out" <<'PY' | tee "$out/memory.txt"
import json, subprocess, sys
bin, root, out = sys.argv[1:4]

def render(scene, *sets):
    path = scene if scene.endswith(".json") else f"{root}/scenes/{scene}.json"
    args = [bin, "render", path, "-o", f"{out}/f.exr", "--stats", f"{out}/s.json"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    return json.load(open(f"{out}/s.json"))

DRAM = "pipeline.memory.model=dram"
def client(stats, block):
    b = stats["blocks"][block]
    m = b["memory"]
    return m["dram_bytes"] / max(b["pixels"], 1), m["hit_rate"]

print("## 1. Frame cycles (millions), DRAM bytes per fetched pixel and hit rate against the cache size\n")
paths = [("bump fetch", "bench-bump-1080p", "bump_fetch", []),
         ("trilinear", "bench-texture-1080p", "texture_fetch", ["pipeline.texture_fetch.filter=trilinear"]),
         ("anisotropic", "bench-texture-1080p", "texture_fetch", ["pipeline.texture_fetch.filter=anisotropic"]),
         ("EWA", "bench-texture-1080p", "texture_fetch", ["pipeline.texture_fetch.filter=ewa"]),
         ("texel_project", "bench-texture-1080p", "texel_project", [])]
print("| cache |" + "".join(f" {p[0]} |" for p in paths))
print("|---:|" + "---|" * len(paths))
ideal = {p[0]: render(p[1], *p[3])["frame_cycles"] for p in paths}
for kib in [1, 2, 4, 8, 16, 32, 64]:
    row = f"| {kib} KiB |"
    for name, scene, block, sets in paths:
        s = render(scene, DRAM, f"pipeline.{block}.cache.size={kib * 1024}", *sets)
        per_pixel, hit = client(s, block)
        row += f" {s['frame_cycles'] / 1e6:.2f} M, {per_pixel:.1f} B, {100 * hit:.1f} % |"
    print(row)
print("| ideal |" + "".join(f" {ideal[p[0]] / 1e6:.2f} M |" for p in paths))

print("\n## 2. The layouts (16 KiB caches): frame cycles, DRAM bytes per pixel of the client, hit rate\n")
print("| layout | bump fetch | trilinear | framebuffer colour (bench) |")
print("|---|---|---|---|")
for layout in ["linear", "tiled", "morton"]:
    row = f"| {layout} |"
    for scene, block, sets in [("bench-bump-1080p", "bump_fetch", []),
                               ("bench-texture-1080p", "texture_fetch", ["pipeline.texture_fetch.filter=trilinear"]),
                               ("bench-1080p", "framebuffer", [])]:
        s = render(scene, DRAM, f"pipeline.{block}.cache.layout={layout}", *sets)
        per_pixel, hit = client(s, block)
        row += f" {s['frame_cycles'] / 1e6:.2f} M, {per_pixel:.1f} B, {100 * hit:.1f} % |"
    print(row)

print("\n## 3. The bump paper's claim, Phong against bump, with the texture unit and its memory counted\n")
print("| scene | memory | cycles per shaded pixel | DRAM bytes per shaded pixel | of which the bump fetch | bump fetch stall cycles per pixel |")
print("|---|---|---:|---:|---:|---:|")
for scene, label in [("bench-1080p", "Phong"), ("bench-bump-1080p", "bump")]:
    for memory in ["ideal", "dram"]:
        s = render(scene, f"pipeline.memory.model={memory}")
        shaded = s["pixels"]["shaded"]
        m = s["memory"]
        total = m.get("dram_bytes", 0) / shaded if memory == "dram" else 0
        bump = m.get("dram_bytes_by_client", {}).get("bump_fetch", 0) / shaded
        stall = s["blocks"].get("bump_fetch", {}).get("memory", {}).get("stall_cycles", 0) / shaded
        print(f"| {label} ({scene}) | {memory} | {s['frame_cycles'] / shaded:.2f} | {total:.1f} | {bump:.1f} | {stall:.1f} |")

print("\n## 4. Object-space texturing against the screen-space filters, in cycles and DRAM bytes per covered pixel\n")
import math
def plane(view, path):
    t = math.radians(view)
    return {"format": 1,
            "camera": {"position": [0, 2.6 * math.sin(t), 2.6 * math.cos(t)], "target": [0, 0, 0], "fov_y": 40,
                       "resolution": [640, 480], "near": 0.05, "far": 100, "local_viewer": False},
            "ambient": [0.25, 0.25, 0.25],
            "lights": [{"type": "directional", "direction": [-0.3, -0.6, -0.7], "intensity": 0.8}],
            "textures": {"t": {"type": "checker", "size": [512, 512], "cells": 16}},
            "materials": {"m": {"texture": "t", "ambient": [1, 1, 1], "diffuse": [0.9, 0.9, 0.9],
                                "specular": [0, 0, 0], "path": path}},
            "objects": [{"shape": "plane", "size": [3, 3], "tessellation": [4, 4], "uv_repeat": [2, 2],
                         "material": "m"}]}
configs = [("texel_project, 32-bit accumulators", "texture-object", []),
           ("texel_project, 16-bit", "texture-object", ["pipeline.texel_project.accumulator_bits=16"]),
           ("texel_project, 64-bit", "texture-object", ["pipeline.texel_project.accumulator_bits=64"]),
           ("trilinear", "texture-screen", ["pipeline.texture_fetch.filter=trilinear"]),
           ("anisotropic 4", "texture-screen", ["pipeline.texture_fetch.filter=anisotropic"]),
           ("EWA", "texture-screen", ["pipeline.texture_fetch.filter=ewa"])]
views = [0, 45, 75, 85]
print("| texturing |" + "".join(f" {v}° |" for v in views))
print("|---|" + "---|" * len(views))
for name, path, sets in configs:
    row = f"| {name} |"
    for v in views:
        json.dump(plane(v, path), open(f"{out}/plane.json", "w"))
        ideal = render(f"{out}/plane.json", *sets)
        s = render(f"{out}/plane.json", DRAM, *sets)
        shaded = max(s["pixels"]["shaded"], 1)
        by = s["memory"]["dram_bytes_by_client"]
        texturing = by.get("texel_project", 0) + by.get("texture_fetch", 0)
        row += (f" {s['frame_cycles'] / shaded:.2f} c ({ideal['frame_cycles'] / shaded:.2f} ideal), "
                f"{s['memory']['dram_bytes_per_shaded_pixel']:.1f} B ({texturing / shaded:.1f} texturing) |")
    print(row)
PY
if ((doc)); then
  python3 "$root/scripts/doc-tables.py" "$out/memory.txt" "$root/docs/memory.md" memory 4
fi
