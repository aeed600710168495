#!/usr/bin/env python3
"""One waveform of the pipeline's blocks and the RTL normalize unit (docs/rtl.md,
"Waveforms"): merges the VCD of `shadetlm render --vcd` with the one of
`shadetlm timing-check --rtl-normalize M --rtl-vcd` made from the same render's timing
log — the same cycles, as the timing check proves. A cycle is 1 ns in both files, and
in the merged one (written in ps, as Verilator's is). Writes OUT.vcd and a GTKWave view
OUT.gtkw beside it (paths relative to it, as the render's view): the normalize block's
signals, then the RTL unit's pins and counters.

Usage: scripts/merge-vcd.py PIPELINE.vcd RTL.vcd OUT.vcd
Exit 0; 2 with a message naming the file when one is not a VCD it can read; 1 when
the output cannot be written (nothing is left)."""
import argparse
import itertools
import os
import re
import string
import sys


def fail(path, why):
    print(f"merge-vcd.py: {path}: {why}", file=sys.stderr)
    sys.exit(2)


def read(path):
    """(header lines before $enddefinitions, [(time, [change lines])], timescale in ps)."""
    try:
        text = open(path, encoding="utf-8", errors="replace").read()
    except OSError as e:
        fail(path, e.strerror)
    head, sep, body = text.partition("$enddefinitions $end")
    if not sep:
        fail(path, "no $enddefinitions: not a VCD")
    scale = re.search(r"\$timescale\s*(\d+)\s*(ps|ns)\s*\$end", head)
    if not scale:
        fail(path, "its $timescale is not in ps or ns")
    ps = int(scale.group(1)) * (1000 if scale.group(2) == "ns" else 1)
    steps, comment = [], False
    for number, line in enumerate(body.split("\n"), 1):
        line = line.strip()
        if comment or line.startswith("$comment"):  # skipped to its $end
            comment = not line.endswith("$end")
            continue
        if not line or line.startswith("$"):  # $dumpvars … $end: the changes inside count at their time
            continue
        if line.startswith("#"):
            if not line[1:].isdigit():
                fail(path, f"line {number} after the header: a time that is not a number: {line[:40]}")
            steps.append((int(line[1:]), []))
        else:
            if line[0] not in "01xzXZbBrR" or (line[0] in "bBrR" and len(line.split()) != 2) or len(line) < 2:
                fail(path, f"line {number} after the header: not a value change: {line[:40]}")
            if not steps:
                steps.append((0, []))
            steps[-1][1].append(line)
    return head, steps, ps


def write(path, text):
    """The whole file or none: a temporary beside it, renamed into place."""
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        print(f"merge-vcd.py: {path}: {e.strerror}", file=sys.stderr)
        sys.exit(1)


def var_lines(head):
    """(kind, words) of each $scope, $upscope and $var: by tokens, as an identifier may be "$"."""
    tokens, out, k = head.split(), [], 0
    while k < len(tokens):
        if tokens[k] in ("$scope", "$upscope", "$var"):
            end = tokens.index("$end", k + 1 + (3 if tokens[k] == "$var" else 0))  # ValueError: none
            out.append((tokens[k][1:], " ".join(tokens[k + 1:end])))
            k = end
        k += 1
    return out


def declarations(path, head):
    try:
        found = var_lines(head)
    except ValueError:
        fail(path, "a $scope, $upscope or $var without its $end")
    depth = 0
    for kind, rest in found:
        depth += {"scope": 1, "upscope": -1}.get(kind, 0)
        if depth < 0 or (kind == "scope" and len(rest.split()) < 2) or (kind == "var" and len(rest.split()) < 4):
            fail(path, f"a ${kind} it cannot read: {rest[:40]}")
    return found


def identifiers():
    chars = string.printable[:94].replace("$", "")
    for n in itertools.count(1):
        for t in itertools.product(chars, repeat=n):
            yield "".join(t)


def main():
    ap = argparse.ArgumentParser()
    ap.error = lambda message: fail("arguments", message)  # one line, exit 2 (no usage block)
    ap.add_argument("pipeline")
    ap.add_argument("rtl")
    ap.add_argument("out")
    a = ap.parse_args()
    if not a.out.endswith(".vcd"):
        fail(a.out, "the output must end in .vcd")
    p_head, p_steps, p_ps = read(a.pipeline)
    if p_ps != 1000 or "one time unit is one cycle" not in p_head:  # (a render's VCD of before: a period a cycle)
        fail(a.pipeline, "not a render's VCD of one time unit a cycle ($timescale 1 ns): render it again")
    r_head, r_steps, r_ps = read(a.rtl)
    # New identifiers for every variable of both files (the two files' overlap).
    fresh, rename = identifiers(), [{}, {}]
    lines = ["$version shadetlm merge-vcd.py $end", "$timescale 1 ps $end", "$comment one cycle is 1 ns (1000 time units) $end"]
    names = []  # (file, hierarchical name) for the view
    for k, (path, head) in enumerate(((a.pipeline, p_head), (a.rtl, r_head))):
        if k == 1:
            lines.append("$scope module rtl $end")
        scope = ["rtl"] if k == 1 else []
        for kind, rest in declarations(path, head):
            words = rest.split()
            if kind == "scope":
                scope.append(words[1])
                lines.append(f"$scope module {words[1]} $end")
            elif kind == "upscope":
                scope.pop()
                lines.append("$upscope $end")
            else:
                old = words[2]
                if old not in rename[k]:
                    rename[k][old] = next(fresh)
                words[2] = rename[k][old]
                lines.append("$var " + " ".join(words) + " $end")
                names.append((k, words[0], ".".join(scope + [words[3]]) + (words[4] if len(words) > 4 else "")))
        if k == 1:
            lines.append("$upscope $end")
    lines.append("$enddefinitions $end")

    def changes(steps, k, unit_ps):
        path = (a.pipeline, a.rtl)[k]
        for time, ch in steps:
            out = []
            for c in ch:
                value, ident = c.split() if c[0] in "bBrR" else (c[0], c[1:])
                if ident not in rename[k]:
                    fail(path, f"a change of an identifier it never declared: {c[:40]}")
                out.append(f"{value} {rename[k][ident]}" if c[0] in "bBrR" else value + rename[k][ident])
            yield round(time * unit_ps), out

    # Each file's cycle n is at n ns (the RTL's clock falls at half cycles: kept in ps).
    merged = {}
    for t, ch in changes(p_steps, 0, p_ps):
        merged.setdefault(t, []).extend(ch)
    for t, ch in changes(r_steps, 1, r_ps):
        merged.setdefault(t, []).extend(ch)
    for t in sorted(merged):
        lines.append(f"#{t}")
        lines.extend(merged[t])
    write(a.out, "\n".join(lines) + "\n")

    # The view: the normalize block's signals, then the RTL's pins and held pixels.
    # It opens on the first traced pixel (the pipeline's first change after the start).
    first = next((t for t, ch in changes(p_steps, 0, p_ps) if t > 0 and ch), 0)
    gtkw = a.out[:-4] + ".gtkw"
    view = [f"[dumpfile] \"{os.path.basename(a.out)}\"", f"[savefile] \"{os.path.basename(gtkw)}\"",
            f"[timestart] {first}", "[sst_expanded] 1", "@800200", "-normalize (TLM)"]
    style = lambda kind, name: "@40020" if kind == "real" else "@28" if "[" not in name else "@24"
    for k, kind, name in names:
        if k == 0 and ".normalize." in name:
            view += [style(kind, name), name]
    view += ["@1000200", "-normalize (TLM)", "@800200", "-normalize (RTL)"]
    pins = ("clk", "in_valid", "in_ready", "in_first", "out_valid", "out_ready", "out_tag", "count", "busy")
    for k, kind, name in names:
        base = re.sub(r"\[.*$", "", name.rsplit(".", 1)[-1])
        if k == 1 and "normalize_unit." in name and base in pins:
            view += [style(kind, name), name]
    view += ["@1000200", "-normalize (RTL)"]
    write(gtkw, "\n".join(view) + "\n")
    print(f"{a.out}: {len(names)} signals, {len(merged)} time steps; view {gtkw}")


main()
