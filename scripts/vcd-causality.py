#!/usr/bin/env python3
"""Checks a traced VCD for causality (docs/inspecting.md): every pixel a block hands on
(valid and ready high) must be handed on by the next traced block no earlier than
(1 + that block's latency) cycles after (it waits a cycle in the FIFO, then the block's
latency). Prints the pairs checked and
those that break it, and those where a block shows the pixel before the block before it
did (an overtake). Exit 1 if any breaks it.

    scripts/vcd-causality.py TRACE.vcd STATS.json

STATS.json (`render --stats`) gives the blocks' order and latencies; the VCD's time
unit is a cycle.
"""
import json
import re
import sys


def read_vcd(path):
    """{block: {(x, y, triangle): time}}: when each block handed each pixel on (valid and,
    where the block has one, ready high)."""
    ids, scope, seen = {}, [], {}
    values, changed = {}, set()
    now = None
    stalled = [0]  # cycles with some block's valid high and ready low

    def flush():
        for block in changed:
            v = values.get(block, {})
            if v.get("valid") == 1 and v.get("ready", 1) == 1:
                seen.setdefault(block, {}).setdefault((v.get("x"), v.get("y"), v.get("triangle")), now)
        changed.clear()

    with open(path) as f:
        text = f.read()
    # Times are cycles: a render's VCD of before, in ps, would pass every pair.
    if not re.search(r"\$timescale\s*1\s*ns\s*\$end", text):
        raise ValueError("its $timescale is not 1 ns (one time unit a cycle)")
    tokens = iter(text.split())
    for tok in tokens:
        if tok == "$scope":
            next(tokens)
            scope.append(next(tokens))
        elif tok == "$upscope":
            scope.pop()
        elif tok == "$var":
            _kind, _width, ident, name = next(tokens), next(tokens), next(tokens), next(tokens)
            if name in ("valid", "ready", "x", "y", "triangle") and scope:
                ids[ident] = (scope[-1], name)
        elif tok.startswith("#"):
            flush()
            later = int(tok[1:])
            if now is not None and any(v.get("valid") == 1 and v.get("ready", 1) == 0 for v in values.values()):
                stalled[0] += later - now
            now = later
        elif tok[0] in "01" and tok[1:] in ids:
            block, name = ids[tok[1:]]
            values.setdefault(block, {})[name] = int(tok[0])
            changed.add(block)
        elif tok[0] == "b":
            ident = next(tokens)
            if ident in ids:
                block, name = ids[ident]
                values.setdefault(block, {})[name] = None if tok == "bx" else int(tok[1:], 2)  # x: not valid
                changed.add(block)
    flush()
    return seen, stalled[0]


def fail(message):
    """A bad argument or file: one line, exit 2."""
    print("vcd-causality: " + message, file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) != 3:
        fail("usage: scripts/vcd-causality.py TRACE.vcd STATS.json")
    try:
        with open(sys.argv[2]) as f:
            stats = json.load(f)
        latency = {b: v["latency"] for b, v in stats["blocks"].items()}
        elaborated = list(stats["elaborated"])
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        fail("%s: not the stats of a render (render --stats): %s" % (
            sys.argv[2], e.strerror if isinstance(e, OSError) else "%s %s" % (type(e).__name__, e)))
    try:
        seen, stalled = read_vcd(sys.argv[1])
    except (OSError, ValueError, StopIteration, IndexError) as e:
        fail("%s: not a VCD it can read: %s" % (sys.argv[1], e.strerror if isinstance(e, OSError) else
                                                   str(e) if isinstance(e, ValueError) and str(e) else type(e).__name__))
    order = [b for b in elaborated if b in seen and b in latency]
    checked = broken = overtakes = 0
    for a, b in zip(order, order[1:]):
        need = 1 + latency[b]
        for pixel, t_a in seen[a].items():
            t_b = seen[b].get(pixel)
            if t_b is None:
                continue
            checked += 1
            if t_b < t_a + need:
                broken += 1
                if t_b < t_a:
                    overtakes += 1
                if broken <= 5:
                    print(f"  pixel {pixel[:2]} of triangle {pixel[2]}: {a} at cycle {t_a}, {b} at cycle {t_b}")
    print(f"{checked} block-to-block pixel pairs checked, {broken} too early, {overtakes} overtaking; "
          f"stalls shown for {stalled} cycles (valid high, ready low)")
    sys.exit(1 if broken else 0)


if __name__ == "__main__":
    main()
