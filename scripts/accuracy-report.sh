#!/usr/bin/env bash
# Maximum absolute colour error against the golden model, per golden scene, for every
# normalization × normal interpolation variant of the pipeline (a report, not a gate:
# the tests gate only the default float32 / exact / perspective configuration).
# The golden scenes whose normals reach normalize unperturbed (no bump, texturing or
# parallax material). Prints a Markdown table.
# Usage: scripts/accuracy-report.sh [--doc] [shadetlm binary]   (--doc: the table into
#   docs/pipeline.md, between its markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0
[[ ${1:-} == --doc ]] && { doc=1; shift; }
bin=${1:-$root/build/app/shadetlm}
[[ -x $bin ]] || { "$root/scripts/build.sh" >/dev/null; bin=$root/build/app/shadetlm; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

report() {
  # (mode and its settings; forward-difference twice: seeded per packet and per line)
  local modes=("exact" "forward-difference" "forward-difference --set pipeline.normalize.seed=line" rsqrt0 rsqrt1 rsqrt2)
  echo "| scene | interpolation | exact | forward-difference, per packet | forward-difference, per line | rsqrt0 | rsqrt1 | rsqrt2 |"
  echo "|---|---|---|---|---|---|---|---|"
  for scene in demo grazing-plane knot point-light sphere torus; do
    for interp in perspective affine; do
      printf '| %s | %s |' "$scene" "$interp"
      for mode in "${modes[@]}"; do
        # shellcheck disable=SC2086  # the mode's words are its settings
        err=$("$bin" render "$root/golden/$scene/scene.json" -o "$tmp/f.exr" --engine loop --compare-reference \
                --set pipeline.normal_interp.mode=$interp --set pipeline.normalize.mode=$mode |
              sed -n 's/.*error rgb: max \([^ ]*\) at.*/\1/p')
        printf ' %.2e |' "$err"
      done
      echo
    done
  done
  echo
  echo "Maximum |pipeline − golden model| over R, G, B of the covered pixels; 2^-12 = 2.44e-04."
  echo
  # The default configuration at larger frames, and on rows 1920 pixels long.
  echo "| scene | resolution | maximum colour error |"
  echo "|---|---|---|"
  local runs=("knot golden/knot/scene.json [1920,1440]" "point-light golden/point-light/scene.json [1920,1440]"
              "sphere golden/sphere/scene.json [1920,1440]" "torus golden/torus/scene.json [1920,1440]"
              "demo golden/demo/scene.json [1920,1080]" "wide-wall,_untextured scenes/wide-wall.json [1920,96] objects.0.material=plain"
              "wide-wall,_textured scenes/wide-wall.json [1920,96]")
  for run in "${runs[@]}"; do
    read -r name file res extra <<<"$run"
    local sets=(--set "camera.resolution=$res")
    [[ -n ${extra:-} ]] && sets+=(--set "$extra")
    err=$("$bin" render "$root/$file" -o "$tmp/f.exr" --engine loop --compare-reference "${sets[@]}" |
          sed -n 's/.*error rgb: max \([^ ]*\) at.*/\1/p')
    res=${res//[\[\]]/}
    printf '| %s | %s | %.2e |\n' "${name//_/ }" "${res//,/×}" "$err"
  done
}
if ((doc)); then
  report > "$tmp/report.txt"
  python3 "$root/scripts/doc-tables.py" "$tmp/report.txt" "$root/docs/pipeline.md" accuracy 2
  cat "$tmp/report.txt"
else
  report
fi
