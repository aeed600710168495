#!/usr/bin/env bash
# The normal walker's error growth against span length and triangle height, per
# re-seeding and per number format (docs/numerical-stability.md): prints the Markdown
# tables and draws the plots into docs/images/. About 15 s.
# Usage: scripts/stability-report.sh [--doc] [shadetlm binary]   (--doc: the tables into
#   docs/numerical-stability.md, between their markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && { doc=1; shift; }
"$root/scripts/setup.sh" gnuplot-nox
bin=${1:-$root/build/app/shadetlm}
[[ -x $bin ]] || { "$root/scripts/build.sh" >/dev/null; bin=$root/build/app/shadetlm; }
report=(python3 "$root/scripts/stability-report.py" "$bin" "$root" "$root/docs/images")
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/numerical-stability.md" stability 4 -- "${report[@]}"; else "${report[@]}"; fi
