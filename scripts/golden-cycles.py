#!/usr/bin/env python3
"""Prints, as a Markdown table, each golden configuration's accepted frame cycles at git
revision REV against the working tree's, and the change (docs/regression.md).

    scripts/golden-cycles.py REV
"""
import json
import pathlib
import subprocess
import sys


def accepted_at(rev, path):
    try:
        text = subprocess.run(["git", "show", f"{rev}:{path}"], capture_output=True, check=True, text=True).stdout
    except subprocess.CalledProcessError:
        return None
    return json.loads(text)["frame_cycles"]


def fail(message):
    print("golden-cycles: " + message, file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) != 2:
        fail("usage: scripts/golden-cycles.py REV")
    rev = sys.argv[1]
    top = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True, text=True)
    if top.returncode != 0:
        fail("not in a git checkout: " + (top.stderr.strip().splitlines() or ["git rev-parse failed"])[-1])
    if subprocess.run(["git", "rev-parse", "--verify", "--quiet", rev + "^{commit}"], capture_output=True).returncode != 0:
        fail("%r: no such git revision" % rev)
    root = pathlib.Path(top.stdout.strip())
    print("| scene | configuration | cycles then | cycles now | change |")
    print("|---|---|---:|---:|---:|")
    for stats in sorted((root / "golden").glob("*/stats*.json")):
        scene = stats.parent.name
        config = stats.stem[len("stats."):] if stats.stem != "stats" else "default"
        now = json.loads(stats.read_text())["frame_cycles"]
        then = accepted_at(rev, stats.relative_to(root).as_posix())
        change = f"{100.0 * (now - then) / then:+.1f} %" if then else "new"
        print(f"| {scene} | {config} | {then if then is not None else '—'} | {now} | {change} |")


if __name__ == "__main__":
    main()
