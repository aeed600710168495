#!/usr/bin/env bash
# Draws out/sweep/sweep.csv (scripts/sweep.sh) with gnuplot: per block family, error
# against wall time and against simulated cycles, Pareto fronts marked, as PNGs in
# out/plots; prints the table of Pareto-optimal configurations per scene.
# Usage: scripts/plot.sh [SWEEP_CSV]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" gnuplot-nox
exec python3 "$root/scripts/plot.py" "${1:-$root/out/sweep/sweep.csv}" "$root/out/plots"
