#!/usr/bin/env bash
# Draws out/sweep/sweep.csv (scripts/sweep.sh) with gnuplot: per block family, error
# against wall time, simulated cycles, operations and texture bytes, each point labelled,
# the Pareto fronts as staircases, as PNGs in out/plots, all of them with every run on
# one page, out/plots/index.html; prints the tables of Pareto-optimal configurations per
# scene (against wall time, against cycles).
# Usage: scripts/plot.sh [--doc] [SWEEP_CSV]   (--doc: the tables into docs/benchmarks.md,
#   between its markers, with the figures its prose draws on (scripts/sweep-findings.py),
#   and the PNGs to docs/images/sweep-*.png, which it shows)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && { doc=1; shift; }
"$root/scripts/setup.sh" gnuplot-nox
plots=$root/out/plots
rm -f "$plots"/*.png  # only this run's plots, for --doc to copy
csv=${1:-$root/out/sweep/sweep.csv}
report=(python3 "$root/scripts/plot.py" "$csv" "$plots")
if ((doc)); then
  # (The findings first: a CSV they refuse leaves the page as it was.)
  python3 "$root/scripts/doc-tables.py" --run "$root/docs/benchmarks.md" findings 5 -- \
    python3 "$root/scripts/sweep-findings.py" "$csv" >/dev/null
  python3 "$root/scripts/doc-tables.py" --run "$root/docs/benchmarks.md" pareto 2 -- "${report[@]}"
  # The plots the page shows (the rest stay in out/plots, on its index.html).
  for png in "$plots"/*.png; do
    name=sweep-$(basename "$png")
    if grep -qF "images/$name" "$root/docs/benchmarks.md"; then cp "$png" "$root/docs/images/$name"; fi
  done
else
  "${report[@]}"
fi
