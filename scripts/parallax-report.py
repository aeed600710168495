#!/usr/bin/env python3
"""The parallax report (docs/parallax.md): runs `shadetlm parallax-bench` on each height
map, `shadetlm precompute` on maps of three sizes, renders heat maps, prints Markdown."""
import json
import math
import os
import struct
import subprocess
import sys
import zlib

shadetlm, root, real = sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else ""
out = os.path.join(root, "out", "parallax")
os.makedirs(out, exist_ok=True)
methods = ["offset", "steep", "pom", "relief", "donnelly", "refined", "cone"]


def run(args):
    return subprocess.run([shadetlm] + args, check=True, capture_output=True, text=True).stdout


def scene_for(path):
    """A copy of the steps scene whose height map is the image at `path`."""
    with open(os.path.join(root, "scenes/parallax/steps.json")) as f:
        s = json.load(f)
    s["textures"]["relief"] = {"type": "image", "file": os.path.abspath(path)}
    dst = os.path.join(out, "real.json")
    with open(dst, "w") as f:
        json.dump(s, f)
    return dst


maps = [("smooth bump", "scenes/parallax/bump.json"), ("sharp steps", "scenes/parallax/steps.json"),
        ("thin ridges", "scenes/parallax/ridges.json"), ("noise relief", "scenes/parallax/noise.json")]
if real:
    maps.append(("real (skimage moon, 512²)", scene_for(real)))

results = []
for name, scene in maps:
    path = scene if os.path.isabs(scene) else os.path.join(root, scene)
    dst = os.path.join(out, "bench-" + name.split()[0] + ".json")
    run(["parallax-bench", path, "--json", dst])
    with open(dst) as f:
        results.append((name, json.load(f)))
    print(f"parallax-report: {name} done", file=sys.stderr)

print("## Every tracer against the exact hit\n")
print("Parallel rays (128 × 128, jittered, azimuth 30°) over the whole map; depth 0.06 uv, 16 slices; "
      "iterations per ray mean / p95 / max; uv error in texels mean / p95 / max; wrong layer: rays that end past "
      "the first solid piece the exact ray meets; past hit: the farthest a ray ends beyond the exact hit, in voxels.\n")
for name, r in results:
    print(f"### {name} ({r['size'][0]}×{r['size'][1]})\n")
    print("| view (tracer) | method | iterations | fetches | uv error (texels) | wrong layer | past hit (voxels) | ns/ray |")
    print("|---|---|---|---|---|---|---|---|")
    for v in r["views"]:
        for m in methods:
            x = v["methods"][m]
            it, e = x["iterations"], x["uv_error_texels"]
            print(f"| {v['elevation_deg']:g}° ({v['tracer_elevation_deg']:.0f}°) | {m} | "
                  f"{it['mean']:.1f} / {it['p95']:.0f} / {it['max']:.0f} | {x['fetches']:.1f} | "
                  f"{e['mean']:.3g} / {e['p95']:.3g} / {e['max']:.3g} | {100 * x['wrong_layer']:.2f} % | "
                  f"{max(0.0, x['max_overshoot_voxels']):.3g} | {x['ns_per_ray']:.0f} |")
    print()

print("## The paper's claim: the refined map against Donnelly's\n")
print("| map | view | Donnelly iterations (mean, of which skips) | refined | ratio | rays where refined needs more | "
      "p95 uv error Donnelly / refined |")
print("|---|---|---|---|---|---|---|")
for name, r in results:
    for v in r["views"]:
        d, f = v["methods"]["donnelly"], v["methods"]["refined"]
        print(f"| {name} | {v['elevation_deg']:g}° | {d['iterations']['mean']:.2f} ({d['skips']:.2f}) | "
              f"{f['iterations']['mean']:.2f} ({f['skips']:.2f}) | {f['iterations']['mean'] / d['iterations']['mean']:.2f} | "
              f"{100 * f['rays_over_donnelly'] / r['rays']:.1f} % | "
              f"{d['uv_error_texels']['p95']:.3g} / {f['uv_error_texels']['p95']:.3g} |")
print()


def write_png(path, size, value):
    """An 8-bit grey PNG of size × size, value(x, y) in [0, 1]."""
    rows = b"".join(b"\0" + bytes(int(255 * value(x, y) + 0.5) for x in range(size)) for y in range(size))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 0, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


print("## Precompute time and size\n")
print("A periodic relief of sharp terraces (sines, quantized to 4 levels), 16 slices; refined map: 16 azimuths × 4 "
      "elevations + the vertical from 10°, 2 × 2 rays per texel.\n")
print("| height map | map | time (s) | EXR, ZIP (MB) | in memory, float (MB) |")
print("|---|---|---|---|---|")
for size in (256, 512, 1024):
    png = os.path.join(out, f"terraces-{size}.png")
    if not os.path.exists(png):
        k = 2 * math.pi / size
        write_png(png, size, lambda x, y: min(3, max(0, math.floor(4 * (0.5 + 0.25 * math.sin(3 * k * x) + 0.25 * math.cos(5 * k * y))))) / 3)
    for kind in ("distancemap", "refinedmap", "conemap"):
        dst = os.path.join(out, f"{kind}-{size}.exr")
        text = run(["precompute", kind, png, "-o", dst])
        seconds = float(text.split(" s\n")[0].rsplit(", ", 1)[1])
        raw = size * size * (8 if kind == "conemap" else 16 * 4)
        print(f"| {size}² | {kind} | {seconds:.2f} | {os.path.getsize(dst) / 1e6:.1f} | {raw / 1e6:.1f} |")
        os.remove(dst)
print()

# Heat maps of the iterations per pixel on the sharp-step quad, for the docs.
for method, extra in (("donnelly", ["--set", "materials.carved.parallax.map=donnelly"]), ("refined", []),
                      ("cone", ["--set", "materials.carved.parallax.method=cone"]),
                      ("relief", ["--set", "materials.carved.parallax.method=relief"])):
    run(["render", os.path.join(root, "scenes/parallax/steps.json"), "-o", os.path.join(out, f"steps-{method}.exr"),
         "--preview", os.path.join(out, f"steps-{method}.png"),
         "--heat-map", os.path.join(out, f"steps-{method}-heat.png"), "--heat-max", "24"] + extra)
print(f"Heat maps: {out}/steps-*-heat.png", file=sys.stderr)
