#!/usr/bin/env python3
"""Puts the Markdown tables a report script printed into its doc, table N between
<!-- NAME:N --> and <!-- /NAME:N --> (scripts/architect.sh, scripts/memory.sh --doc).
Leaves the doc as it was, and exits 1 naming why, if the count or a marker is wrong.
With --run it runs the report itself, passes its output on as it comes, and touches the
doc only if the report exits 0 (else it exits with the report's status).
Usage: scripts/doc-tables.py REPORT.txt DOC.md NAME COUNT
       scripts/doc-tables.py --run DOC.md NAME COUNT -- COMMAND [ARG ...]
Bad arguments, or a file that cannot be read: one line, exit 2, the doc as it was."""
import re
import subprocess
import sys


def fail(message):
    print("doc-tables: " + message, file=sys.stderr)
    sys.exit(2)


def read(path):
    try:
        with open(path) as f:
            return f.read()
    except (OSError, ValueError) as e:  # ValueError: bytes that are not text
        fail("%s: cannot read it: %s" % (path, e.strerror if isinstance(e, OSError) else e))


run = sys.argv[1:2] == ["--run"]
if not (len(sys.argv) > 6 and sys.argv[5] == "--" if run else len(sys.argv) == 5) or \
        not re.fullmatch("[0-9]+", sys.argv[4]):
    fail("usage: scripts/doc-tables.py REPORT.txt DOC.md NAME COUNT, or --run DOC.md NAME COUNT -- COMMAND [ARG ...]")
if run:
    doc, name, count, command = sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[6:]
    read(doc)  # readable, before the report runs (minutes, some of them)
    try:
        report = subprocess.Popen(command, stdout=subprocess.PIPE, text=True)
    except OSError as e:
        fail("%s: cannot run it: %s" % (command[0], e.strerror or e))
    text = ""
    for line in report.stdout:
        sys.stdout.write(line)
        sys.stdout.flush()
        text += line
    if report.wait() != 0:
        sys.exit(report.returncode)
else:
    doc, name, count = sys.argv[2], sys.argv[3], int(sys.argv[4])
    text = read(sys.argv[1])
page = read(doc)
tables = [t.strip() for t in re.findall(r"((?:^\|.*\n)+)", text, re.M)]
if len(tables) != count:
    sys.exit(f"{name}: {len(tables)} tables printed, {count} expected; {doc} left as it was")
for n, table in enumerate(tables, 1):
    page, found = re.subn(rf"(<!-- {name}:{n} -->\n).*?(<!-- /{name}:{n} -->)",
                          lambda m: m.group(1) + table + "\n" + m.group(2), page, flags=re.S)
    if found != 1:
        sys.exit(f"{name}: {doc} lacks the markers of table {n}; left as it was")
open(doc, "w").write(page)
