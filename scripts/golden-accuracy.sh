#!/usr/bin/env bash
# Every golden configuration against the golden model, under the headline metric
# (R, G, B over the covered pixels) and frame-wide, with its gate and margin; then the
# ten PSNRs the metric moved most (scripts/golden-accuracy.py). Exit 1 when a gate fails.
# Usage: scripts/golden-accuracy.sh [--doc]   (--doc: the two tables into docs/regression.md)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && doc=1
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
report=(python3 "$root/scripts/golden-accuracy.py" "$root/build/app/shadetlm" "$root" "$work")
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/regression.md" golden-accuracy 2 -- "${report[@]}"; else "${report[@]}"; fi
