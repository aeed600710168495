#!/usr/bin/env bash
# The bump-mapping report: prints the Markdown tables that docs/bump-mapping.md keeps
# (blocks and costs per path, datapath ranges, error per surface, depth and view, and
# each approximation on its own). About 200 small renders, a minute or two.
# Usage: scripts/bump-report.sh [--doc] [--images DIR]   (DIR: a PNG preview per path;
#   --doc: the tables into docs/bump-mapping.md, between their markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
doc=0 args=()
for arg in "$@"; do
  if [[ $arg == --doc ]]; then doc=1; else args+=("$arg"); fi
done
report=(python3 "$root/scripts/bump-report.py" "$root/build/app/shadetlm" ${args[@]+"${args[@]}"})
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/bump-mapping.md" bump 10 -- "${report[@]}"; else "${report[@]}"; fi
