#!/usr/bin/env bash
# The wall-time cost of waveforms: a 64x64 region at the centre of a scene's frame traced
# into a VCD, against the same render untraced, best of N runs each (the render's own
# simulation time), as one ratio measured in one run. scripts/bench.sh calls it.
# Usage: scripts/trace-cost.sh [SHADETLM [SCENE [N]]]   (default: build/app/shadetlm,
#   scenes/bench-1080p.json, 3)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/app/shadetlm} scene=${2:-$root/scenes/bench-1080p.json} runs=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
seconds() {  # the best of $runs wall times of the SystemC render, from its own report
  for ((i = 0; i < runs; i++)); do
    "$bin" render "$scene" -o "$tmp/t.exr" "$@" | sed -n 's/.* covered, \([0-9.e+-]*\) s$/\1/p'
  done | sort -g | head -1
}
read -r width height < <("$bin" render "$scene" -o "$tmp/t.exr" | sed -n 's/.*, \([0-9]*\)x\([0-9]*\), .*/\1 \2/p')
x0=$((width / 2 - 32)) y0=$((height / 2 - 32))
plain=$(seconds)
traced=$(seconds --vcd "$tmp/t.vcd" --trace-region $x0,$y0,$((x0 + 63)),$((y0 + 63)))
awk -v a="$traced" -v b="$plain" -v w="$width" -v h="$height" -v n="$runs" 'BEGIN {
  printf "  64x64 region of %dx%d traced / untraced (wall, best of %d): %.4g s / %.4g s = %.3f (goal <= 2)\n", w, h, n, a, b, a / b }'
