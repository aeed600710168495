#!/usr/bin/env python3
"""Draws a --timeline JSON (Chrome trace events) as an SVG: one row per block, one
box per slice, like Perfetto's track view. For documents and quick looks where no
browser is at hand; Perfetto UI (ui.perfetto.dev) opens the same file interactively.
Usage: timeline-svg.py timeline.json out.svg [from_us to_us]"""
import json
import sys

events = json.load(open(sys.argv[1]))["traceEvents"]
names = {e["tid"]: e["args"]["name"] for e in events if e.get("ph") == "M" and e.get("name") == "thread_name"}
slices = [e for e in events if e.get("ph") == "X"]
t0 = float(sys.argv[3]) if len(sys.argv) > 3 else min(e["ts"] for e in slices)
t1 = float(sys.argv[4]) if len(sys.argv) > 4 else max(e["ts"] + e["dur"] for e in slices)
W, ROW, LEFT, TOP = 1400, 34, 130, 30
scale = (W - LEFT - 20) / (t1 - t0)
colors = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7"]
out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{TOP + ROW * len(names) + 30}" '
       f'font-family="sans-serif" font-size="13"><rect width="100%" height="100%" fill="white"/>']
for tid, name in sorted(names.items()):
    y = TOP + tid * ROW
    out.append(f'<text x="8" y="{y + 21}">{name}</text><line x1="{LEFT}" x2="{W - 20}" y1="{y + ROW - 2}" '
               f'y2="{y + ROW - 2}" stroke="#ddd"/>')
for e in slices:
    if e["ts"] + e["dur"] < t0 or e["ts"] > t1:
        continue
    x = LEFT + (e["ts"] - t0) * scale
    w = max(0.6, e["dur"] * scale)
    y = TOP + e["tid"] * ROW + 4
    out.append(f'<rect x="{x:.2f}" y="{y}" width="{w:.2f}" height="{ROW - 10}" fill="{colors[e["tid"] % 8]}" stroke="none"/>')
for k in range(6):  # time axis, µs
    t = t0 + (t1 - t0) * k / 5
    x = LEFT + (t - t0) * scale
    out.append(f'<text x="{x:.0f}" y="18" text-anchor="middle">{t:.1f} µs</text>')
out.append("</svg>")
open(sys.argv[2], "w").write("\n".join(out))
