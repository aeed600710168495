#!/usr/bin/env bash
# The forward-difference radicand's cost on real spans (docs/pipeline.md, "The radicand
# on real spans"): normalize's operations per pixel, direct against forward differences
# seeded per packet and per raster line, on the golden and benchmark scenes, and the
# span length from which forward differences win. About 10 s.
# Usage: scripts/radicand-report.sh [--doc]   (--doc: the two tables into docs/pipeline.md)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && doc=1
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
report=(python3 "$root/scripts/radicand-report.py" "$root/build/app/shadetlm" "$root")
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/pipeline.md" radicand 2 -- "${report[@]}"; else "${report[@]}"; fi
