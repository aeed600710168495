#!/usr/bin/env python3
"""A Markdown table of two scripts/bench.sh runs' instruction counts, side by side:
per path, SystemC / loop instructions per shaded pixel and their ratio in each run
(docs/performance.md). Usage: scripts/bench-table.py RUN_A.txt RUN_B.txt [LABEL_A LABEL_B]"""
import re
import sys


def fail(message):
    """A bad argument or file: one line, exit 2."""
    print("bench-table: " + message, file=sys.stderr)
    sys.exit(2)


ELABORATED = "every block elaborated / the needed ones, golden/sphere 960x720 (instructions)"


def counts(path):
    """{path label: {engine: instructions per shaded pixel}} in the order printed, and
    under ELABORATED the run's every-block / needed ratio where it has one; exits 2 when
    the file cannot be read or holds no count."""
    out, elaborated, ratio = {}, False, None
    try:
        with open(path) as f:
            for line in f:
                m = re.match(r"\s+(.+?)\s+(systemc|loop)\s+\d+ instructions /\s+\d+ shaded pixels =\s+([0-9.]+)", line)
                if m:
                    out.setdefault(m.group(1), {})[m.group(2)] = float(m.group(3))
                elaborated = elaborated or line.startswith("== every block elaborated")
                m = re.match(r"\s+(\d+) / (\d+) = [0-9.]+", line)
                if elaborated and m and ratio is None:  # (from the counts: the line's ratio is rounded)
                    ratio = int(m.group(1)) / int(m.group(2))
    except (OSError, ValueError) as e:  # ValueError: bytes that are not text
        fail("%s: cannot read it: %s" % (path, e.strerror if isinstance(e, OSError) else e))
    if not out:
        fail("%s: no instruction counts in it (the output of scripts/bench.sh)" % path)
    if ratio is not None:
        out[ELABORATED] = {"ratio": ratio}
    return out


if len(sys.argv) not in (3, 5):
    fail("usage: scripts/bench-table.py RUN_A.txt RUN_B.txt [LABEL_A LABEL_B]")
a, b = counts(sys.argv[1]), counts(sys.argv[2])
label_a, label_b = (sys.argv[3], sys.argv[4]) if len(sys.argv) > 4 else ("A", "B")
print(f"| path (instructions a shaded pixel) | SystemC / loop, {label_a} | ratio | SystemC / loop, {label_b} | ratio |")
print("|---|---|---:|---|---:|")
for path in list(a) + [p for p in b if p not in a]:
    x, y = a.get(path, {}), b.get(path, {})
    cells = []
    for c in (x, y):
        if "ratio" in c:
            cells += ["(all / needed)", f"{c['ratio']:.3f}"]
        elif "systemc" in c and "loop" in c:
            cells += [f"{c['systemc']:.1f} / {c['loop']:.1f}", f"{c['systemc'] / c['loop']:.3f}"]
        else:
            cells += ["—", "—"]
    print(f"| {path} | " + " | ".join(cells) + " |")
