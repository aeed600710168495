#!/usr/bin/env python3
"""The cost model against the standard-cell flow (docs/rtl.md, "Calibration"; issue 41
item 5): for each normalize unit the flow synthesized (out/cells/cells.json, scripts/cells.py),
the area and energy a pixel that the operators' figures (out/cells/operators.json,
scripts/operators.py) give for the operations the model counts, and the error.

The model's view of the unit as written (one combinational step a pixel, then the
latency's registers):
  - a unit of each kind for each operation a pixel (rounded up: the packet's seed counts
    in the average), at the format's word W = 1 + I + F, priced by the operators' power
    law in W (sums and products as the saturating operators); a correctly rounded 1/√
    (forward-difference mode) as a square root and a division, as the RTL computes it;
  - the pixels in flight, ⌈(L + 1) / II⌉ results of 3 words each, as flip-flops;
  - energy a pixel: each operation's energy scaled from the operators' input activity
    (0.5 a cycle) to the unit's measured one over the II cycles of a pixel, as if
    dynamic power were proportional to it (an assumption, stated); each flip-flop's for
    II cycles as measured (its clock switches every cycle, whatever the data).
The counts come from a render of golden/sphere at that mode and format (--stats).

Usage: scripts/calibrate.py [--doc]   (--doc: the table into docs/rtl.md between <!-- calibration:1 --> markers)
Exit 2, one line, when the saved rows or the program are missing."""
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cells  # noqa: E402
import operators  # noqa: E402

# The operators each counted operation is priced as: the model's fixed-point type
# saturates its sums and products (its divisions too, whose saturating form is not
# characterized: the plain divider stands in).
KINDS = {"add": ["add_sat"], "mul": ["mul_sat"], "div": ["div"], "sqrt": ["sqrt"], "rsqrt": ["sqrt", "div"]}


def fail(message):
    print("calibrate.py: " + message, file=sys.stderr)
    sys.exit(2)


def load(path, what):
    try:
        rows = json.loads(path.read_text())
        if not isinstance(rows, list) or not rows:
            raise ValueError("no rows")
        return rows
    except (OSError, ValueError) as e:
        fail(f"{path}: {e} ({what} makes it)")


def laws(rows):
    """Each operation's (area, energy) power laws: (c, k) pairs."""
    out = {}
    for op in operators.OPS:
        pts = sorted((r["width"], r) for r in rows if r["op"] == op)
        if len(pts) >= 3 and all(r["area_um2"] > 0 and r["energy_pj"] > 0 for _, r in pts):
            a = operators.power_law([(w, r["area_um2"]) for w, r in pts])
            e = operators.power_law([(w, r["energy_pj"]) for w, r in pts])
            out[op] = ((a[0], a[1]), (e[0], e[1]))
    return out


def counts(binary, mode, fmt):
    """The normalize block's operations a pixel on golden/sphere."""
    with tempfile.TemporaryDirectory(prefix="calibrate-") as tmp:
        stats = pathlib.Path(tmp) / "s.json"
        r = subprocess.run([binary, "render", str(cells.ROOT / "golden/sphere/scene.json"), "-o", f"{tmp}/f.exr",
                            "--set", f"pipeline.normalize.mode={mode}", "--set", f"pipeline.normalize.format={fmt}",
                            "--allow-overflow", "--stats", str(stats)], capture_output=True, text=True)
        last = (r.stderr.strip().splitlines() or ["no message"])[-1][-300:]
        if r.returncode != 0:
            fail(f"render of {mode} at {fmt} exited {r.returncode}: {last}")
        try:
            b = json.loads(stats.read_text())["blocks"]["normalize"]
            return {k: v / b["pixels"] for k, v in b["ops"].items() if v}
        except (OSError, ValueError, KeyError, TypeError, ZeroDivisionError) as e:
            fail(f"render of {mode} at {fmt}: no normalize statistics ({type(e).__name__}: {e})")


def estimate(row, ops, law):
    ibits, fbits = map(int, re.fullmatch(r"fixed:(\d+)\.(\d+)", row["format"]).groups())
    w = 1 + ibits + fbits
    price = lambda op, which: law[op][which][0] * w ** law[op][which][1]
    area = energy = 0.0
    missing = []
    for kind, per_pixel in ops.items():
        if kind not in KINDS or any(op not in law for op in KINDS[kind]):
            missing.append(kind)
            continue
        for op in KINDS[kind]:
            area += math.ceil(per_pixel - 1e-9) * price(op, 0)
            # The unit's inputs switch `activity` times a cycle, II cycles a pixel.
            energy += per_pixel * price(op, 1) * row["activity"] * row["ii"] / operators.ACTIVITY
    capacity = -(-(row["latency"] + 1) // row["ii"])
    flops = capacity * 3 * w
    area += flops * price("register", 0) / w
    energy += flops * price("register", 1) / w * row["ii"]  # (clocked every cycle: not scaled by the data)
    return area, energy, flops, missing


def main(argv):
    if argv not in ([], ["--doc"]):
        fail("usage: scripts/calibrate.py [--doc]")
    out = cells.ROOT / "out/cells"
    units = load(out / "cells.json", "scripts/cells.py")
    law = laws(load(out / "operators.json", "scripts/operators.py"))
    if "register" not in law:
        fail(f"{out / 'operators.json'}: no register rows at three widths (scripts/operators.py makes them)")
    binary = os.environ.get("SHADETLM", str(cells.ROOT / "build/app/shadetlm"))
    if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
        fail(f"{binary}: no program (scripts/build.sh builds it)")
    lines = ["| mode | format | operations a pixel | area, flow, mm² | area, model, mm² | error |"
             " flip-flops, flow / model | energy a pixel, flow, pJ | model, pJ | error |",
             "|---|---|---|---:|---:|---:|---|---:|---:|---:|"]
    for row in units:
        ops = counts(binary, row["mode"], row["format"])
        area, energy, flops, missing = estimate(row, ops, law)
        said = ", ".join(f"{k} {v:.2f}" for k, v in sorted(ops.items())) + (
            f" ({', '.join(missing)}: no figure)" if missing else "")
        lines.append(f"| {row['mode']} | `{row['format']}` | {said} | {row['area_um2'] / 1e6:.3f} | {area / 1e6:.3f} |"
                     f" {100 * (area / row['area_um2'] - 1):+.0f} % | {row['flops']} / {flops} |"
                     f" {row['energy_pj']:.0f} | {energy:.0f} | {100 * (energy / row['energy_pj'] - 1):+.0f} % |")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    (out / "calibration.txt").write_text(text)
    if argv == ["--doc"]:
        subprocess.run([sys.executable, str(cells.ROOT / "scripts/doc-tables.py"), str(out / "calibration.txt"),
                        str(cells.ROOT / "docs/rtl.md"), "calibration", "1"], check=True)
        print("docs/rtl.md updated")


if __name__ == "__main__":
    main(sys.argv[1:])
