#!/usr/bin/env python3
"""Fixed-point operators in standard cells (docs/rtl.md, "Operators"): the area, delay and
energy of one operation of each kind the model counts, at each width, through the flow of
scripts/cells.py (Yosys onto OSU 0.18 um, OpenSTA), for the cost model of every block
(issue 41). Each operator is a unit of its own: its operands registered, the operation,
its result registered. What the registers cost is taken off (their flip-flops' area from
the library, their power from a unit of registers alone), so a row is the operation's
logic.

  add      a + b (W bits, wrapping: the model's saturation is a compare and a select more)
  mul      a · b of fixed:I.F, rounded to nearest at F fraction bits (the product's bits the
           rounded result needs, then an increment: Yosys drops the columns above them)
  div      a / b of fixed:I.F, to nearest: (a · 2^F + b/2) / b, unsigned
  sqrt     √a of fixed:I.F, to nearest: ⌊√(a · 2^F)⌋ digit by digit (rtl/normalize's
           fx_isqrt), rounded up when the remainder exceeds the root
  add_sat  a + b saturating at the format's limits, as the model's fixed-point type adds
  mul_sat  mul saturating: the whole product kept to see whether it fits
  compare  a < b (signed)
  mux      s ? a : b
  register one W-bit register (its flip-flops alone: area from the library, energy from
           the registers-only unit)

W = 1 + I + F is the word; F = W/2 (rounded down) fraction bits. Energy: OpenSTA's power
at the model's clock with every input bit switching 0.5 times a cycle (random data), times
the clock period: the energy of one operation a cycle.

Usage: scripts/operators.py [--doc] [--fresh] [--jobs N] [--widths "8 12 ..."] [--ops "add mul ..."]
       scripts/operators.py --check   the 8-bit add and mul through the flow (ctest operators_flow)
  --doc    the tables into docs/rtl.md between its <!-- operators:N --> markers, and their
           power laws into src/shadetlm/cost/operator_fits.inc (the program's cost model)
  --fresh  synthesize again what out/cells/operators.json holds (by default a row saved by an
           earlier run on the same flow, library and tools is taken as it is, and only the
           missing ones are synthesized)
Exit 2 on bad arguments or a missing tool (naming its Debian package); 1 if a synthesis fails."""
import functools
import hashlib
import inspect
import json
import math
import os
import pathlib
import re
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor, as_completed

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cells  # noqa: E402  (the flow: synthesize, sta, the library)

OPS = ["add", "mul", "div", "sqrt", "add_sat", "mul_sat", "compare", "mux", "register"]
WIDTHS = [8, 12, 16, 20, 24]
ACTIVITY = 0.5  # transitions a cycle of each input bit: random data
ISQRT = cells.RTL / "fx_isqrt.sv"


def fail(message, code=2):
    print("operators.py: " + message, file=sys.stderr)
    sys.exit(code)


def source(op, w):
    """The unit's Verilog: operands registered, the operation, the result registered."""
    f = w // 2
    body = {
        "add": f"wire [{w - 1}:0] r = ra + rb;",
        "mul": (f"wire signed [{2 * w - 1}:0] p = $signed(ra) * $signed(rb);\n"
                f"  wire signed [{2 * w - 1}:0] q = (p + ({2 * w}'sd1 <<< {f - 1})) >>> {f};\n"
                f"  wire [{w - 1}:0] r = q[{w - 1}:0];"),
        "div": (f"wire [{2 * w - 1}:0] n = ({{{w}'d0, ra}} << {f}) + {{{w + 1}'d0, rb[{w - 1}:1]}};\n"
                f"  wire [{2 * w - 1}:0] q = n / {{{w}'d0, rb}};\n"
                f"  wire [{w - 1}:0] r = q[{w - 1}:0];"),
        "sqrt": (f"wire [{2 * w - 1}:0] v = {{{w}'d0, ra}} << {f};\n"
                 f"  wire [{w - 1}:0] root;\n  wire [{w + 1}:0] rem;\n"
                 f"  fx_isqrt #(.N({w})) isqrt (.v(v), .root(root), .rem(rem));\n"
                 f"  wire [{w - 1}:0] r = root + ({{2'b00, root}} < rem ? {w}'d1 : {w}'d0);"),
        "add_sat": (f"wire signed [{w}:0] t = $signed(ra) + $signed(rb);\n"
                    f"  wire [{w - 1}:0] r = t[{w}] == t[{w - 1}] ? t[{w - 1}:0] : {{t[{w}], {{{w - 1}{{!t[{w}]}}}}}};"),
        "mul_sat": (f"wire signed [{2 * w - 1}:0] p = $signed(ra) * $signed(rb);\n"
                    f"  wire signed [{2 * w - 1}:0] q = (p + ({2 * w}'sd1 <<< {f - 1})) >>> {f};\n"
                    f"  wire fits = q[{2 * w - 1}:{w - 1}] == {{{w + 1}{{q[{2 * w - 1}]}}}};\n"
                    f"  wire [{w - 1}:0] r = fits ? q[{w - 1}:0] : {{q[{2 * w - 1}], {{{w - 1}{{!q[{2 * w - 1}]}}}}}};"),
        "compare": f"wire [{w - 1}:0] r = {{{w - 1}'d0, $signed(ra) < $signed(rb)}};",
        "mux": f"wire [{w - 1}:0] r = rs ? ra : rb;",
        "register": f"wire [{w - 1}:0] r = ra ^ rb;",  # (only its flip-flops are kept: see row())
    }[op]
    return (f"module op_unit(input logic clk, input logic s, input logic [{w - 1}:0] a, b, output logic [{w - 1}:0] y);\n"
            f"  logic [{w - 1}:0] ra, rb;\n  logic rs;\n  {body}\n"
            f"  always_ff @(posedge clk) begin ra <= a; rb <= b; rs <= s; y <= r; end\nendmodule\n")


def registers_only(w):
    """Registers without logic: the unit's inputs registered, then registered again at the
    output (2·(2W + 1) flip-flops, none removable)."""
    return (f"module op_unit(input logic clk, input logic s, input logic [{w - 1}:0] a, b, output logic [{2 * w}:0] y);\n"
            f"  logic [{w - 1}:0] ra, rb;\n  logic rs;\n"
            f"  always_ff @(posedge clk) begin ra <= a; rb <= b; rs <= s; y <= {{rs, ra, rb}}; end\nendmodule\n")


def measure(text, work):
    """(area um^2, flip-flops, the critical path ns, power W at the model's clock)."""
    src = work / "op_unit.sv"
    src.write_text(text)
    net, counts, area = cells.synthesize([src, ISQRT], "op_unit", {}, work)
    period = cells.min_period(net, "op_unit", work)
    _, power = cells.sta(net, "op_unit", 1000.0 / cells.CLOCK_MHZ, ACTIVITY, work)
    return area, sum(n for c, n in counts.items() if c.startswith("DFF")), period, power


@functools.lru_cache(maxsize=None)
def flop_costs(w):
    """A flip-flop's area (the library's DFFPOSX1) and power at the model's clock (the
    registers-only unit's, per flip-flop)."""
    with tempfile.TemporaryDirectory(prefix="operators-") as tmp:
        _, flops, _, power = measure(registers_only(w), pathlib.Path(tmp))
    return cells.cell_areas()["DFFPOSX1"], power / flops


def row(op, w, overhead):
    period_ns = 1000.0 / cells.CLOCK_MHZ
    dff_area, dff_power = flop_costs(w)
    if op == "register":
        area, power, delay = w * dff_area, w * dff_power, overhead
    else:
        with tempfile.TemporaryDirectory(prefix="operators-") as tmp:
            total, flops, path, unit_power = measure(source(op, w), pathlib.Path(tmp))
        area, power = total - flops * dff_area, max(unit_power - flops * dff_power, 0.0)
        delay = max(path - overhead, 0.0)  # the operation between two registers
    return {"op": op, "width": w, "area_um2": area, "delay_ns": delay, "energy_pj": power * period_ns * 1e3}


def fingerprint():
    """The flow (cells.py's synthesis and timing, this script's units), the library and the
    tools' versions: what a saved row was measured on."""
    h = hashlib.sha256()
    for f in (cells.synthesize, cells.sta, cells.min_period, cells.register_overhead, cells.cell_areas, source,
              registers_only, measure, flop_costs, row):
        h.update(inspect.getsource(f).encode() + b"\0")
    for path in (ISQRT, pathlib.Path(cells.LIBERTY)):
        h.update(path.read_bytes() + b"\0")
    h.update(f"{cells.CLOCK_MHZ} {cells.TARGET_PS} {ACTIVITY}".encode())
    for cmd in (["yosys", "-V"], ["sta", "-version"]):
        h.update(cells.subprocess.run(cmd, capture_output=True, text=True).stdout.strip().encode() + b"\0")
    return h.hexdigest()[:16]


def power_law(points):
    """Least squares of log y = log c + k·log W: y = c · W^k, with R² of the logs."""
    xs, ys = [math.log(w) for w, _ in points], [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    k = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    c = math.exp(my - k * mx)
    ss = sum((y - my) ** 2 for y in ys)
    res = sum((y - (my + k * (x - mx))) ** 2 for x, y in zip(xs, ys))
    return c, k, (1 - res / ss if ss > 0 else 1.0)


def tables(rows):
    widths = sorted(set(r["width"] for r in rows))
    ops = [o for o in OPS if any(r["op"] == o for r in rows)]
    at = {(r["op"], r["width"]): r for r in rows}
    out = []
    for key, unit, fmt in (("area_um2", "area, µm²", "%.0f"), ("delay_ns", "delay, ns", "%.2f"),
                           ("energy_pj", "energy an operation, pJ", "%.3f")):
        out.append("| operation (%s) | %s |" % (unit, " | ".join("W = %d" % w for w in widths)))
        out.append("|---|%s|" % "|".join("---:" for _ in widths))
        for o in ops:
            out.append("| %s | %s |" % (o, " | ".join(fmt % at[(o, w)][key] if (o, w) in at else "–" for w in widths)))
        out.append("")
    # How each grows with the word: a power law through the widths (the exponent: 1 for
    # what grows bit by bit, 2 for an array of partial products or digits).
    out.append("| operation | area, µm² ≈ c · W^k | R² (of the logs) | energy, pJ ≈ c · W^k | R² (of the logs) |")
    out.append("|---|---|---:|---|---:|")
    for o in ops:
        pts = sorted((r["width"], r) for r in rows if r["op"] == o)
        if len(pts) < 3:
            continue
        texts = []
        for key in ("area_um2", "energy_pj"):
            if any(r[key] <= 0 for _, r in pts):  # (an energy below the registers' own: no power law)
                texts += ["–", "–"]
                continue
            c, k, r2 = power_law([(w, r[key]) for w, r in pts])
            texts += ["%.4g · W^%.2f" % (c, k), "%.4f" % r2]
        out.append("| %s | %s | %s | %s | %s |" % (o, *texts))
    return "\n".join(out) + "\n"


FITS = cells.ROOT / "src/shadetlm/cost/operator_fits.inc"


def write_fits(rows, stamp):
    """The power laws the program prices operations by (src/shadetlm/cost/), written beside
    the doc's tables from the same rows, so that the two cannot differ."""
    lines = ["// Written by scripts/operators.py --doc (flow %s): do not edit." % stamp,
             "// {operation, area c, area k, energy c, energy k}: area um^2 = c * W^k and energy pJ",
             "// = c * W^k of one operation of a W-bit word, fitted over W = %s bits (docs/rtl.md)."
             % ", ".join(str(w) for w in sorted(set(r["width"] for r in rows)))]
    for o in OPS:
        pts = sorted((r["width"], r) for r in rows if r["op"] == o)
        if len(pts) < 3 or any(r[key] <= 0 for _, r in pts for key in ("area_um2", "energy_pj")):
            fail(f"{o}: fewer than three widths measured, or a figure not positive: no power law to write")
        area = power_law([(w, r["area_um2"]) for w, r in pts])
        energy = power_law([(w, r["energy_pj"]) for w, r in pts])
        lines.append('{"%s", %.6g, %.6g, %.6g, %.6g},' % (o, area[0], area[1], energy[0], energy[1]))
    tmp = FITS.with_name(FITS.name + ".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, FITS)
    print(f"{FITS.relative_to(cells.ROOT)} written")


def check():
    """The 8-bit add and mul through the flow: each area the sum of its cells' (cells.py
    --check holds Yosys's area to the library's), the multiplier larger and slower, both
    with positive energy."""
    with tempfile.TemporaryDirectory(prefix="operators-") as tmp:
        overhead = cells.register_overhead(pathlib.Path(tmp))
    add, mul = row("add", 8, overhead), row("mul", 8, overhead)
    problems = []
    if not 0 < add["area_um2"] < mul["area_um2"]:
        problems.append(f"area: add {add['area_um2']:.0f}, mul {mul['area_um2']:.0f} um^2")
    if not 0 < add["delay_ns"] < mul["delay_ns"]:
        problems.append(f"delay: add {add['delay_ns']:.3f}, mul {mul['delay_ns']:.3f} ns")
    if not 0 < add["energy_pj"] < mul["energy_pj"]:
        problems.append(f"energy: add {add['energy_pj']:.4f}, mul {mul['energy_pj']:.4f} pJ")
    cells.report_problems("operators.py --check", problems)
    print(f"operators.py --check: 8 bits: add {add['area_um2']:.0f} um^2 {add['delay_ns']:.2f} ns "
          f"{add['energy_pj']:.3f} pJ, mul {mul['area_um2']:.0f} um^2 {mul['delay_ns']:.2f} ns {mul['energy_pj']:.3f} pJ")


def main(argv):
    ops, widths, doc, fresh, jobs = OPS, WIDTHS, False, False, os.cpu_count() or 1
    usage = "usage: scripts/operators.py [--doc] [--fresh] [--jobs N] [--widths \"8 12 ...\"] [--ops \"add ...\"] | --check"
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--check" and not argv[1:]:
            cells.tools()
            return check()
        if a == "--doc":
            doc = True
        elif a == "--fresh":
            fresh = True
        elif a == "--jobs":
            if not args or not args[0].isdigit() or int(args[0]) < 1:
                fail("--jobs: a positive whole number of syntheses at once")
            jobs = int(args.pop(0))
        elif a == "--ops":
            value = args.pop(0).split() if args else []
            bad = [o for o in value if o not in OPS]
            if bad or not value:
                fail(f"--ops: {' '.join(bad) or 'none given'}: the operations are {', '.join(OPS)}")
            ops = value
        elif a == "--widths":
            value = args.pop(0).split() if args else []
            if not value or not all(re.fullmatch(r"[0-9]+", w) and 4 <= int(w) <= 25 for w in value):
                fail("--widths: whole numbers of bits from 4 to 25 (fixed:I.F with I + F ≤ 24)")
            widths = [int(w) for w in value]
        else:
            fail(f"{a}: unknown argument ({usage})")
    cells.tools()
    stamp = fingerprint()
    out = cells.ROOT / "out/cells"
    out.mkdir(parents=True, exist_ok=True)
    saved = out / "operators.json"
    rows = {}
    try:
        earlier = json.loads(saved.read_text()) if saved.exists() else []
        if not isinstance(earlier, list):
            raise ValueError("not a list")
        for r in earlier:
            if r.get("flow") == stamp:
                rows[(r["op"], r["width"])] = r
            else:
                print(f"operators.py: {saved}: {r.get('op')} at {r.get('width')} bits dropped: measured on another "
                      f"flow, library or tools (fingerprint {r.get('flow')}, now {stamp})", file=sys.stderr)
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        print(f"operators.py: {saved}: not its rows ({e}), dropped", file=sys.stderr)
        rows = {}
    wanted = [(o, w) for w in widths for o in ops if fresh or (o, w) not in rows]
    with tempfile.TemporaryDirectory(prefix="operators-") as tmp:
        overhead = cells.register_overhead(pathlib.Path(tmp))
    lock, failed = threading.Lock(), None
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        running = {pool.submit(row, o, w, overhead): (o, w) for o, w in wanted}
        for done in as_completed(running):
            try:
                r = dict(done.result(), flow=stamp)
            except SystemExit as e:  # (its synthesis failed, said already: the others still run and are saved)
                failed = failed or e
                continue
            with lock:  # each row saved as it completes, whole (a kill keeps the others)
                rows[(r["op"], r["width"])] = r
                tmp = saved.with_name(saved.name + ".tmp")
                tmp.write_text(json.dumps(sorted(rows.values(), key=lambda r: (OPS.index(r["op"]), r["width"])),
                                          indent=1) + "\n")
                os.replace(tmp, saved)
            print(f"operators.py: {r['op']} at {r['width']} bits done", file=sys.stderr)
    if failed:
        raise failed
    text = tables(list(rows.values()))
    print(f"Register overhead (clock-to-Q + setup of DFFPOSX1): {overhead:.3f} ns; inputs switching {ACTIVITY} "
          f"times a cycle; energy at {cells.CLOCK_MHZ} MHz.\n")
    print(text, end="")
    (out / "operators.txt").write_text(text)
    if doc:
        write_fits(list(rows.values()), stamp)
        cells.subprocess.run([sys.executable, str(cells.ROOT / "scripts/doc-tables.py"), str(out / "operators.txt"),
                              str(cells.ROOT / "docs/rtl.md"), "operators", "4"], check=True)
        print("docs/rtl.md updated")


if __name__ == "__main__":
    main(sys.argv[1:])
