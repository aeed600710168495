#!/usr/bin/env python3
"""A Markdown table of two scripts/bench.sh runs' instruction counts, side by side:
per path, SystemC / loop instructions per shaded pixel and their ratio in each run
(docs/performance.md). Usage: scripts/bench-table.py RUN_A.txt RUN_B.txt [LABEL_A LABEL_B]"""
import re
import sys

def counts(path):
    """{path label: {engine: instructions per shaded pixel}} in the order printed."""
    out = {}
    for line in open(path):
        m = re.match(r"\s+(.+?)\s+(systemc|loop)\s+\d+ instructions /\s+\d+ shaded pixels =\s+([0-9.]+)", line)
        if m:
            out.setdefault(m.group(1), {})[m.group(2)] = float(m.group(3))
    return out

a, b = counts(sys.argv[1]), counts(sys.argv[2])
label_a, label_b = (sys.argv[3], sys.argv[4]) if len(sys.argv) > 4 else ("A", "B")
print(f"| path (instructions a shaded pixel) | SystemC / loop, {label_a} | ratio | SystemC / loop, {label_b} | ratio |")
print("|---|---|---:|---|---:|")
for path, x in a.items():
    y = b.get(path, {})
    cells = []
    for c in (x, y):
        if "systemc" in c and "loop" in c:
            cells += [f"{c['systemc']:.1f} / {c['loop']:.1f}", f"{c['systemc'] / c['loop']:.3f}"]
        else:
            cells += ["—", "—"]
    print(f"| {path} | " + " | ".join(cells) + " |")
