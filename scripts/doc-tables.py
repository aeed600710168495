#!/usr/bin/env python3
"""Puts the Markdown tables a report script printed into its doc, table N between
<!-- NAME:N --> and <!-- /NAME:N --> (scripts/architect.sh, scripts/memory.sh --doc).
Leaves the doc as it was, and exits 1 naming why, if the count or a marker is wrong.
With --run it runs the report itself, passes its output on as it comes, and touches the
doc only if the report exits 0 (else it exits with the report's status).
Usage: scripts/doc-tables.py REPORT.txt DOC.md NAME COUNT
       scripts/doc-tables.py --run DOC.md NAME COUNT -- COMMAND [ARG ...]"""
import re
import subprocess
import sys

if sys.argv[1] == "--run":
    doc, name, count, command = sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[6:]
    report = subprocess.Popen(command, stdout=subprocess.PIPE, text=True)
    text = ""
    for line in report.stdout:
        sys.stdout.write(line)
        sys.stdout.flush()
        text += line
    if report.wait() != 0:
        sys.exit(report.returncode)
else:
    doc, name, count = sys.argv[2], sys.argv[3], int(sys.argv[4])
    text = open(sys.argv[1]).read()
tables = [t.strip() for t in re.findall(r"((?:^\|.*\n)+)", text, re.M)]
page = open(doc).read()
if len(tables) != count:
    sys.exit(f"{name}: {len(tables)} tables printed, {count} expected; {doc} left as it was")
for n, table in enumerate(tables, 1):
    page, found = re.subn(rf"(<!-- {name}:{n} -->\n).*?(<!-- /{name}:{n} -->)",
                          lambda m: m.group(1) + table + "\n" + m.group(2), page, flags=re.S)
    if found != 1:
        sys.exit(f"{name}: {doc} lacks the markers of table {n}; left as it was")
open(doc, "w").write(page)
