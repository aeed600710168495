#!/usr/bin/env python3
"""The normalize unit in standard cells (docs/rtl.md, "Standard cells"): Yosys maps the RTL
(src/shadetlm/rtl/normalize, the whole unit flattened) to the OSU 0.18 um library of
qflow-tech-osu018, and OpenSTA times it and estimates its power. Per mode and format:
cells, flip-flops, area (um^2, Yosys's `stat -liberty`), the critical path and fmax of the
unit as written (its datapath is one combinational step at issue, then the latency's
registers), the pipeline stages a retiming tool would need to reach the model's clock,
and the power and energy a pixel at the model's clock and at fmax, with the inputs'
switching activity measured on golden/sphere's test vectors (curved: its normals change
from pixel to pixel, where the long-spans scene's flat ones hardly toggle a bit).

Usage: scripts/cells.py [--quick] [--doc] [--fresh] [--jobs N] [--formats "fixed:I.F ..."] [--modes "m ..."]
       scripts/cells.py --check      one operator through the whole flow (the ctest cells_flow)
  --quick  rsqrt0 and exact at fixed:1.12 (a few minutes on 2 cores; the whole table is
           longer: ABC's mapping of the dividers and square roots grows with the width,
           forward-difference at fixed:1.12 took 40 minutes)
  --doc    the tables into docs/rtl.md between its <!-- cells:N --> markers
  --fresh  forget the rows of earlier runs (by default a run's rows join those in
           out/cells/cells.json measured on the same RTL, library, flow and tool versions,
           so configurations can be synthesized one at a time; other rows are dropped,
           and said so). Each row is saved as it completes.
  --jobs N configurations synthesized at once (default: the cores; each can take GBs)
  --saved  synthesize nothing: the table of the rows in out/cells/cells.json (exit 2
           if none is of this RTL, library and flow)
Environment: SHADETLM (the program), SHADETLM_LIBERTY (another Liberty file).
Exit 2, naming the Debian package that installs it, when a tool or the library is missing;
2 on bad arguments."""
import hashlib
import inspect
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor, as_completed

ROOT = pathlib.Path(__file__).resolve().parent.parent
LIBERTY = os.environ.get("SHADETLM_LIBERTY", "/usr/share/qflow/tech/osu018/osu018_stdcells.lib")
RTL = ROOT / "src/shadetlm/rtl/normalize"
CLOCK_MHZ = 500  # the model's clock (pipeline.clock_mhz)
TARGET_PS = 1000000 // CLOCK_MHZ  # ABC's delay target: a clock period
MODES = ["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]


def fail(message, code=2):
    print("cells.py: " + message, file=sys.stderr)
    sys.exit(code)


def tools():
    """Installs what it can (scripts/setup.sh), then refuses what is still missing."""
    subprocess.run([str(ROOT / "scripts/setup.sh"), "yosys", "opensta", "qflow-tech-osu018"],
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for tool, package in (("yosys", "yosys"), ("sta", "opensta")):
        if not shutil.which(tool):
            fail(f"{tool}: not found (the Debian package {package} installs it)")
    if not os.path.isfile(LIBERTY):
        fail(f"{LIBERTY}: no such cell library (the Debian package qflow-tech-osu018 installs OSU 0.18 um's)")


def cell_areas():
    """Each cell's area in the Liberty file (um^2), read apart from Yosys."""
    text = pathlib.Path(LIBERTY).read_text(errors="replace")
    return {m.group(1): float(m.group(2)) for m in re.finditer(r"cell\s*\(\s*(\w+)\s*\)\s*\{\s*area\s*:\s*([0-9.]+)", text)}


def synthesize(sources, top, params, work):
    """Yosys: generic synthesis, flip-flops and logic mapped to the library. Returns the
    netlist's path and the cell counts {cell: n} with Yosys's chip area."""
    net = work / f"{top}.v"
    chparam = " ".join(f"-set {k} {v}" for k, v in params.items())
    script = "\n".join([
        f"read_verilog -sv {' '.join(map(str, sources))}",
        f"chparam {chparam} {top}" if params else "",
        f"synth -top {top} -flatten",
        f"dfflibmap -liberty {LIBERTY}",
        # ABC's mapping for delay at the model's clock, then what a synthesis flow does
        # after it: high fanouts buffered, gates sized up on late paths and down elsewhere
        # (without it a select line driving hundreds of X1 gates took 78 ns on one net).
        # No SAT sweeping (&fraig, scorr): on a fixed:3.16 unit it took more than 24 GB.
        f"abc -liberty {LIBERTY} -script +strash;dc2;dretime;strash;&get,-n;"
        f"&dch,-f;&nf,-D,{TARGET_PS};&put;buffer,-N,10;upsize,-D,{TARGET_PS};dnsize,-D,{TARGET_PS};stime,-p",
        "opt_clean",
        f"stat -liberty {LIBERTY}",
        f"write_verilog -noattr {net}",
    ])
    (work / "synth.ys").write_text(script + "\n")
    log = work / "synth.log"
    r = subprocess.run(["yosys", "-q", "-l", str(log), str(work / "synth.ys")], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"yosys on {top}: {r.stderr.strip()[-400:]}", 1)
    stats = log.read_text().split("Printing statistics")[-1]
    cells = {m.group(1): int(m.group(2)) for m in re.finditer(r"^\s+([A-Z]\w*)\s+(\d+)\s*$", stats, re.M)}
    area = float(re.search(r"Chip area for module .*?:\s*([0-9.]+)", stats).group(1))
    return net, cells, area


def sta(net, top, period_ns, activity, work):
    """OpenSTA at a clock of period_ns: (the worst slack in ns, total power in W). Every
    input but the clock and reset switches `activity` times a cycle (OpenSTA's unit)."""
    tcl = work / "sta.tcl"
    tcl.write_text("\n".join([
        f"read_liberty {LIBERTY}", f"read_verilog {net}", f"link_design {top}",
        f"create_clock -name clk -period {period_ns} [get_ports clk]",
        "set inputs [delete_from_list [all_inputs] [get_ports clk]]",
        "set_input_delay 0 -clock clk $inputs", "set_output_delay 0 -clock clk [all_outputs]",
        "report_worst_slack -digits 4",
        f"set_power_activity -input -activity {activity}",
        "if {[llength [get_ports -quiet rst]]} { set_power_activity -input_ports [get_ports rst] -activity 0 }",
        "report_power -digits 6", ""]))
    r = subprocess.run(["sta", "-no_init", "-exit", str(tcl)], capture_output=True, text=True)
    wns = re.search(r"^worst slack\s+(-?[0-9.]+)", r.stdout, re.M)
    total = re.search(r"^Total\s+\S+\s+\S+\s+\S+\s+([0-9.e+-]+)", r.stdout, re.M)
    if r.returncode != 0 or not wns or not total:
        fail(f"sta on {top}: {(r.stderr or r.stdout).strip()[-400:]}", 1)
    return float(wns.group(1)), float(total.group(1))


def min_period(net, top, work):
    """The shortest clock period with no negative slack: the period less the worst slack
    at a period long enough for every path."""
    slack, _ = sta(net, top, 1000.0, 0.0, work)
    return 1000.0 - slack if slack < 1000.0 else 0.0


def register_overhead(work):
    """A flip-flop into a flip-flop: clock-to-Q plus setup, what a pipeline stage costs."""
    src = work / "ff.sv"
    src.write_text("module ff2(input logic clk, input logic d, output logic q);\n"
                   "  logic m;\n  always_ff @(posedge clk) begin m <= d; q <= m; end\nendmodule\n")
    net, _, _ = synthesize([src], "ff2", {}, work)
    slack, _ = sta(net, "ff2", 1000.0, 0.0, work)
    # (The d -> m and m -> q paths: the register-to-register one is the longer.)
    return 1000.0 - slack


def input_activity(binary, mode, fmt, ii, work):
    """Transitions a cycle of the unit's inputs, from the words the kernel gave the unit on
    golden/sphere (`render --vectors`): a pixel's inputs change once per issue,
    every II cycles."""
    vectors = work / "vectors"
    subprocess.run([binary, "render", str(ROOT / "golden/sphere/scene.json"), "-o", str(work / "f.exr"),
                    "--vectors", str(vectors), "--set", f"pipeline.normalize.mode={mode}",
                    "--set", f"pipeline.normalize.format={fmt}", "--allow-overflow"],
                   check=True, capture_output=True)
    words = [int(line.split()[0], 16) for line in (vectors / "normalize.in.hex").read_text().splitlines()
             if line and not line.startswith("//")]
    bits = int(re.search(r"(\d+) bits a line", (vectors / "normalize.in.hex").read_text()).group(1))
    toggles = sum(bin(a ^ b).count("1") for a, b in zip(words, words[1:]))
    return toggles / (bits * max(len(words) - 1, 1)) / ii


def configuration(binary, mode, fmt, overhead):
    index, latency, ii = next((int(w[1]), int(w[2]), int(w[3])) for w in
                              (l.split() for l in (RTL / "modes.txt").read_text().splitlines())
                              if w and w[0] == mode)
    ibits, fbits = re.fullmatch(r"fixed:(\d+)\.(\d+)", fmt).groups()
    with tempfile.TemporaryDirectory(prefix="cells-") as tmp:
        work = pathlib.Path(tmp)
        net, cells, area = synthesize(
            [RTL / "normalize_datapath.sv", RTL / "fx_isqrt.sv", RTL / "normalize_unit.sv"], "normalize_unit",
            {"IBITS": ibits, "FBITS": fbits, "MODE": index, "LATENCY": latency, "II": ii, "TAG_W": 1}, work)
        period = min_period(net, "normalize_unit", work)
        activity = input_activity(binary, mode, fmt, ii, work)
        _, power_model = sta(net, "normalize_unit", 1000.0 / CLOCK_MHZ, activity, work)
        _, power_fmax = sta(net, "normalize_unit", period, activity, work)
    flops = sum(n for c, n in cells.items() if c.startswith("DFF"))
    logic_ns = period - overhead
    # A pipeline stage holds at most (clock period - register overhead) of the logic.
    stages = math.ceil(logic_ns / (1000.0 / CLOCK_MHZ - overhead))
    pixel_ns = ii * 1000.0 / CLOCK_MHZ  # a pixel every II cycles at full throughput
    return {"mode": mode, "format": fmt, "cells": sum(cells.values()), "flops": flops, "area_um2": area,
            "period_ns": period, "fmax_mhz": 1000.0 / period, "stages_500": stages, "latency": latency, "ii": ii,
            "activity": activity, "power_mw": power_model * 1e3, "power_fmax_mw": power_fmax * 1e3,
            "energy_pj": power_model * pixel_ns * 1e3}


def table(rows):
    lines = ["| mode | format | cells | flip-flops | area, mm² | critical path, ns | fmax as written, MHz |"
             " stages for 500 MHz / latency | input activity | power at 500 MHz, mW | energy a pixel, pJ |"
             " power at fmax, mW |",
             "|---|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['mode']} | `{r['format']}` | {r['cells']} | {r['flops']} | {r['area_um2'] / 1e6:.3f} |"
                     f" {r['period_ns']:.2f} | {r['fmax_mhz']:.1f} | {r['stages_500']} / {r['latency']} |"
                     f" {r['activity']:.3f} | {r['power_mw']:.2f} | {r['energy_pj']:.1f} | {r['power_fmax_mw']:.3f} |")
    return "\n".join(lines) + "\n\n" + verdict(rows) + "\n"


def verdict(rows):
    """Which configurations a retiming could bring to the model's clock within the
    latency the model declares for them."""
    lines = [f"| mode | format | stages for {CLOCK_MHZ} MHz | declared latency | within it, once retimed |",
             "|---|---|---:|---:|---|"]
    for r in rows:
        fits = "yes" if r["stages_500"] <= r["latency"] else "**no**"
        lines.append(f"| {r['mode']} | `{r['format']}` | {r['stages_500']} | {r['latency']} | {fits} |")
    return "\n".join(lines)


def report_problems(who, problems):
    """A check's failures, one a line, then exit 1 (none: nothing)."""
    for p in problems:
        print(f"{who}: {p}")
    if problems:
        sys.exit(1)


def check():
    """One operator through the flow: a registered 12-bit adder. Its area is Yosys's and
    also the sum of its cells' areas in the Liberty file; its period lies above a
    register's overhead; its power grows with the clock."""
    areas = cell_areas()
    with tempfile.TemporaryDirectory(prefix="cells-") as tmp:
        work = pathlib.Path(tmp)
        src = work / "add.sv"
        src.write_text("module add12(input logic clk, input logic [11:0] a, b, output logic [11:0] y);\n"
                       "  logic [11:0] ra, rb;\n"
                       "  always_ff @(posedge clk) begin ra <= a; rb <= b; y <= ra + rb; end\nendmodule\n")
        net, cells, area = synthesize([src], "add12", {}, work)
        summed = sum(areas[c] * n for c, n in cells.items())
        period = min_period(net, "add12", work)
        _, slow = sta(net, "add12", 10.0, 0.1, work)
        _, fast = sta(net, "add12", 5.0, 0.1, work)
        overhead = register_overhead(work)
    flops = sum(n for c, n in cells.items() if c.startswith("DFF"))
    problems = []
    if abs(summed - area) > 1e-6 * area:
        problems.append(f"area {area} um^2 from Yosys, {summed} from the library's cells")
    if flops != 36:
        problems.append(f"{flops} flip-flops, not 36 (two 12-bit operands and the sum registered)")
    if not overhead < period < 100:
        problems.append(f"a period of {period} ns, not between the register overhead {overhead} ns and 100 ns")
    if not 0 < slow < fast:
        problems.append(f"power {slow} W at 100 MHz and {fast} W at 200 MHz")
    report_problems("cells.py --check", problems)
    print(f"cells.py --check: add12 in {sum(cells.values())} cells, {area:.0f} um^2 (the library's cells sum to it), "
          f"{period:.3f} ns ({1000 / period:.0f} MHz), {slow * 1e3:.3f} mW at 100 MHz, {fast * 1e3:.3f} mW at 200 MHz")


def fingerprint():
    """What a row was measured on (sha256): the RTL's sources, the cell library, the flow
    itself (this script's synthesis and timing functions and its clock) and the tools'
    versions. A row of another fingerprint is not this flow's answer."""
    h = hashlib.sha256()
    for path in sorted(RTL.glob("*.sv")) + [RTL / "modes.txt", pathlib.Path(LIBERTY)]:
        h.update(path.name.encode() + b"\0" + path.read_bytes())
    flow = [inspect.getsource(f) for f in (synthesize, sta, min_period, register_overhead, input_activity,
                                           configuration)]
    versions = [subprocess.run(cmd, capture_output=True, text=True).stdout.strip()
                for cmd in (["yosys", "-V"], ["sta", "-version"])]
    for text in flow + versions + [str(CLOCK_MHZ), str(TARGET_PS)]:
        h.update(text.encode() + b"\0")
    return h.hexdigest()[:16]


def merged(earlier_path, rows, stamp):
    """This run's rows and the earlier ones of the same fingerprint, one a configuration
    (this run's where both have it), ordered by format, then mode."""
    kept = {}
    try:
        earlier = json.loads(earlier_path.read_text()) if earlier_path and earlier_path.exists() else []
    except ValueError:
        print(f"cells.py: {earlier_path}: not JSON, its rows are dropped", file=sys.stderr)
        earlier = []
    for r in earlier:
        if r.get("rtl") == stamp:
            kept[(r["format"], r["mode"])] = r
        else:
            print(f"cells.py: {earlier_path}: {r.get('mode')} at {r.get('format')} dropped: measured on other "
                  f"RTL, library, flow or tools (fingerprint {r.get('rtl')}, now {stamp})", file=sys.stderr)
    for r in rows:
        kept[(r["format"], r["mode"])] = r  # (rows of this run: stamped by it)
    order = lambda key: (key[0], MODES.index(key[1]))
    return [kept[k] for k in sorted(kept, key=order)]


def main(argv):
    formats, modes, doc, fresh, saved = ["fixed:1.12", "fixed:3.16"], MODES, False, False, False
    jobs = os.cpu_count() or 1
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--check":
            tools()
            return check()
        if a == "--quick":
            formats, modes = ["fixed:1.12"], ["rsqrt0", "exact"]
        elif a == "--doc":
            doc = True
        elif a == "--saved":
            saved = True
        elif a == "--fresh":
            fresh = True
        elif a == "--jobs" and args and args[0].isdigit() and int(args[0]) > 0:
            jobs = int(args.pop(0))
        elif a == "--jobs":
            fail("--jobs: a positive whole number of configurations at once")
        elif a in ("--formats", "--modes") and args:
            value = args.pop(0).split()
            if a == "--formats":
                formats = value
            else:
                modes = value
        else:
            fail(f"{a}: unknown argument\n" + __doc__.split("\n\n")[1])
    for f in formats:
        if not re.fullmatch(r"fixed:\d+\.[1-9]\d*", f):
            fail(f"{f}: the RTL is fixed point: formats are fixed:I.F")
    for m in modes:
        if m not in MODES:
            fail(f"{m}: unknown mode (one of {', '.join(MODES)})")
    if saved:
        return write_table(None, doc)
    tools()
    binary = os.environ.get("SHADETLM", str(ROOT / "build/app/shadetlm"))
    if not os.access(binary, os.X_OK):
        fail(f"{binary}: no program (scripts/build.sh builds it)")
    with tempfile.TemporaryDirectory(prefix="cells-") as tmp:
        overhead = register_overhead(pathlib.Path(tmp))
    stamp = fingerprint()
    out = ROOT / "out/cells"
    out.mkdir(parents=True, exist_ok=True)
    configurations = [(m, f) for f in formats for m in modes]
    rows, lock = [] if fresh else merged(out / "cells.json", [], stamp), threading.Lock()
    # Each row saved as it completes: a configuration that fails or a kill loses only
    # the rows still running.
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        running = [pool.submit(configuration, binary, m, f, overhead) for m, f in configurations]
        failed = None
        for done in as_completed(running):
            try:
                row = dict(done.result(), rtl=stamp)
            except SystemExit as e:  # (a configuration's fail(): said already; the others still saved)
                failed = failed or e
                continue
            with lock:
                rows = merged(None, rows + [row], stamp)
                save(out / "cells.json", rows)
    if failed:
        raise failed
    print(f"Register overhead (clock-to-Q + setup of DFFPOSX1): {overhead:.3f} ns; the model's clock {CLOCK_MHZ} MHz "
          f"({1000 / CLOCK_MHZ:.1f} ns).\n")
    write_table(rows, doc)


def save(path, rows):
    """Written whole, then renamed: a kill leaves the earlier rows, never half a file."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(rows, indent=1) + "\n")
    os.replace(tmp, path)


def write_table(rows, doc):
    """The rows' table (the saved rows of the current RTL if rows is None), printed, in
    out/cells/cells.txt, and with doc in docs/rtl.md."""
    out = ROOT / "out/cells"
    if rows is None:
        tools()  # (the fingerprint reads the library and asks the tools their versions)
        if not (out / "cells.json").exists():
            fail(f"{out / 'cells.json'}: no saved rows (a run without --saved makes them)")
        rows = merged(out / "cells.json", [], fingerprint())
        if not rows:
            fail(f"{out / 'cells.json'}: no saved row of this RTL, library and flow (a run without --saved makes them)")
    text = table(rows)
    print(text, end="")
    (out / "cells.txt").write_text(text)
    if doc:
        subprocess.run([sys.executable, str(ROOT / "scripts/doc-tables.py"), str(out / "cells.txt"),
                        str(ROOT / "docs/rtl.md"), "cells", "2"], check=True)
        print("docs/rtl.md updated")


if __name__ == "__main__":
    main(sys.argv[1:])
