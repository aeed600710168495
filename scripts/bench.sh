#!/usr/bin/env bash
# The pipeline's speed, in figures that can be compared across runs:
#  1. wall time of the SystemC pipeline against the same kernels in a plain loop,
#     measured in one process (ratio, ns per shaded pixel) on the 1920×1080 scene;
#  2. instructions per shaded pixel from callgrind (repeatable, unlike seconds),
#     counted inside the render only (not scene loading or file output), for the
#     pipeline and for the loop: on a smaller frame of the same scene, and on the
#     leanest Phong configuration.
# Usage: scripts/bench.sh [SCENE] [extra --set arguments ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
command -v valgrind >/dev/null || { echo "bench.sh: valgrind is missing (scripts/setup.sh installs it)" >&2; exit 1; }
"$root/scripts/build.sh" >/dev/null
bin=$root/build/app/shadetlm
scene=${1:-$root/scenes/bench-1080p.json}
shift || true
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "== wall time, one run =="
"$bin" bench "$scene" "$@"

echo
echo "== instructions per shaded pixel (callgrind) =="
count() {  # count LABEL SCENE RESOLUTION
  local label=$1 file=$2 res=$3
  for engine in systemc loop; do
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$engine" --toggle-collect="modules::render_$engine*" \
      "$bin" render "$file" -o "$tmp/f.exr" --engine $engine --set "camera.resolution=$res" "${extra[@]}" \
      >"$tmp/out.$engine" 2>"$tmp/err.$engine" || { cat "$tmp/err.$engine" >&2; exit 1; }
    ir=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$tmp/cg.$engine")
    pixels=$(sed -n 's/.* \([0-9]*\) shaded pixels.*/\1/p' "$tmp/out.$engine")
    awk -v l="$label" -v e=$engine -v ir="$ir" -v px="$pixels" \
      'BEGIN { printf "  %-44s %-8s %11d instructions / %7d shaded pixels = %6.1f\n", l, e, ir, px, ir / px }'
  done
}
extra=("$@")
count "benchmark scene at 480x270 (3 lights, texture)" "$scene" "[480,270]"
# The leanest Phong configuration: one directional light, viewer at infinity, no
# texture (vector_interp and texture_fetch are not elaborated).
count "golden/sphere at 960x720 (minimal Phong)" "$root/golden/sphere/scene.json" "[960,720]"
