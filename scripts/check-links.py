#!/usr/bin/env python3
"""Every relative link of the repository's Markdown files leads somewhere: the file or
folder exists, and an anchor (#part) names a heading of the target as GitHub makes its
ids (lowercase, punctuation dropped, spaces as hyphens, repeats numbered -1, -2, ...).
Links to the web (http, https, mailto) are not followed: CI has no network.
Usage: scripts/check-links.py [ROOT]   (default: the repository holding this script)
Prints each broken link as FILE:LINE: TARGET: why; exit 1 if any, 2 on bad arguments."""
import os
import re
import subprocess
import sys

LINK = re.compile(r"(?<!\!)\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)|!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def fail(message):
    print("check-links: " + message, file=sys.stderr)
    sys.exit(2)


def slug(text):
    """GitHub's id of a heading: inline code and links read as their text."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = text.replace("`", "").strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def lines_outside_code(path):
    """(line number, text) of a Markdown file, fenced code blocks left out."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if not fenced:
                yield number, line


def anchors(path, cache={}):
    """The heading ids of a Markdown file (and any explicit <a id=...> or name=...)."""
    if path not in cache:
        ids, seen = set(), {}
        for _, line in lines_outside_code(path):
            m = HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = seen.get(base, 0)
                ids.add(base if n == 0 else "%s-%d" % (base, n))
                seen[base] = n + 1
            ids.update(re.findall(r"<a\s+(?:id|name)=\"([^\"]+)\"", line))
        cache[path] = ids
    return cache[path]


def check(root, md):
    """The broken links of one file, and how many relative links it has."""
    problems, count = [], 0
    for number, line in lines_outside_code(os.path.join(root, md)):
        line = re.sub(r"`[^`]*`", "", line)  # inline code is not a link
        for m in LINK.finditer(line):
            target = m.group(1) or m.group(2)
            if re.match(r"^[a-z]+:", target):  # http:, https:, mailto:
                continue
            count += 1
            file_part, _, anchor = target.partition("#")
            where = os.path.normpath(os.path.join(root, os.path.dirname(md), file_part)) if file_part else \
                os.path.join(root, md)
            if not os.path.exists(where):
                problems.append("%s:%d: %s: no such file" % (md, number, target))
            elif anchor and where.endswith(".md") and anchor not in anchors(where):
                problems.append("%s:%d: %s: %s has no heading #%s" % (md, number, target, file_part or md, anchor))
    return problems, count


def main():
    if len(sys.argv) > 2:
        fail("usage: scripts/check-links.py [ROOT]")
    root = sys.argv[1] if len(sys.argv) == 2 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if not os.path.isdir(root):
        fail("%s: not a folder" % root)
    try:  # the files git knows (no build trees or downloads); a plain walk outside a checkout
        files = [f for f in subprocess.run(["git", "-C", root, "ls-files", "-z", "*.md"], capture_output=True,
                                           text=True, check=True).stdout.split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = [os.path.relpath(os.path.join(d, f), root) for d, _, names in os.walk(root) for f in names
                 if f.endswith(".md") and "build" not in os.path.relpath(d, root).split(os.sep)]
    if not files:  # (a root git does not track, or no documents: nothing would be checked)
        fail("%s: no Markdown files found" % root)
    problems, links = [], 0
    for md in sorted(files):
        found, count = check(root, md)
        problems += found
        links += count
    for p in problems:
        print(p)
    print("%d Markdown files, %d relative links, %d broken" % (len(files), links, len(problems)), file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
