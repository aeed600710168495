#!/usr/bin/env python3
"""The include rules of src/shadetlm (docs/development.md, "Code layout"), from a checkout:

* every `#include "shadetlm/…"` is a file below src/ (or one the build generates), so an
  editor or grep follows it without configuring;
* the independent answers stay independent: core/ includes only core/; reference/ and
  timing_reference/ include only core/ (never a kernel, never the fast timing);
* no two headers include each other, directly or through others.

Usage: scripts/check-includes.py ROOT   (exit 1 and each broken rule named on failure)
"""
import pathlib
import re
import sys

# Written by the build, not in a checkout (core/CMakeLists.txt, rtl/CMakeLists.txt).
GENERATED = {"core/version.hpp", "rtl/normalize_rtl_build.hpp"}
# A room and the rooms it may include (rooms not named here may include any).
ALLOWED = {
    "core": {"core"},
    "reference": {"core", "reference"},
    "timing_reference": {"core", "timing_reference"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"(shadetlm|app)/([^"]+)"', re.M)


def sources(root):
    for top in ("src", "app", "testbenches", "examples"):
        for p in sorted((root / top).rglob("*")):
            if p.suffix in (".cpp", ".hpp", ".in") and p.is_file():
                yield p


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[1]).resolve()
    src = root / "src" / "shadetlm"
    if not src.is_dir():
        sys.exit(f"check-includes: {src}: no such folder")
    problems, edges, count = [], {}, 0
    for path in sources(root):
        rel = path.relative_to(root).as_posix()
        room = path.relative_to(src).parts[0] if src in path.parents else None
        text = path.read_text(errors="replace")
        for m in INCLUDE.finditer(text):
            count += 1
            line = text.count("\n", 0, m.start()) + 1
            prefix, name = m.group(1), m.group(2)
            target = (src / name) if prefix == "shadetlm" else (root / "app" / name)
            if prefix == "shadetlm" and name in GENERATED:
                continue
            if not target.is_file():
                problems.append(f'{rel}:{line}: "{prefix}/{name}": no such file ({target.relative_to(root)})')
                continue
            if room in ALLOWED and name.split("/")[0] not in ALLOWED[room]:
                problems.append(f"{rel}:{line}: {room}/ may include only {', '.join(r + '/' for r in sorted(ALLOWED[room]))}, not {name}")
            edges.setdefault(path, set()).add(target.resolve())
    cycle = find_cycle(edges)
    if cycle:
        problems.append("an include cycle: " + " -> ".join(p.relative_to(root).as_posix() for p in cycle))
    for p in problems:
        print(p)
    if problems:
        sys.exit(1)
    print(f"check-includes: {count} includes resolve below src/ and app/, the rules hold, no cycle")


def find_cycle(edges):
    """A cycle of the include graph as a list of files, or None (iterative DFS)."""
    state = {}  # 1: on the current path, 2: done
    for start in edges:
        if state.get(start):
            continue
        path, stack = [], [(start, iter(sorted(edges.get(start, ()))))]
        state[start] = 1
        path.append(start)
        while stack:
            node, children = stack[-1]
            child = next(children, None)
            if child is None:
                state[node] = 2
                stack.pop()
                path.pop()
            elif state.get(child) == 1:
                return path[path.index(child):] + [child]
            elif not state.get(child):
                state[child] = 1
                path.append(child)
                stack.append((child, iter(sorted(edges.get(child, ())))))
    return None


if __name__ == "__main__":
    main()
