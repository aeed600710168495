#!/usr/bin/env bash
# Draws out/sweep/sweep.csv (scripts/sweep.sh) with gnuplot: per block family, error
# against wall time and against simulated cycles, Pareto fronts marked, as PNGs in
# out/plots; prints the table of Pareto-optimal configurations per scene.
# Usage: scripts/plot.sh [--doc] [SWEEP_CSV]   (--doc: the table into docs/benchmarks.md,
#   between its markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && { doc=1; shift; }
"$root/scripts/setup.sh" gnuplot-nox
report=(python3 "$root/scripts/plot.py" "${1:-$root/out/sweep/sweep.csv}" "$root/out/plots")
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/benchmarks.md" pareto 1 -- "${report[@]}"; else "${report[@]}"; fi
