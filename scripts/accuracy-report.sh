#!/usr/bin/env bash
# Maximum absolute colour error against the golden model, per golden scene, for every
# normalization × normal interpolation variant of the pipeline (a report, not a gate:
# the tests gate only the default float32 / exact / perspective configuration).
# Prints a Markdown table. Usage: scripts/accuracy-report.sh [shadetlm binary]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/app/shadetlm}
[[ -x $bin ]] || { "$root/scripts/build.sh" >/dev/null; bin=$root/build/app/shadetlm; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

modes=(exact forward-difference rsqrt0 rsqrt1 rsqrt2)
printf '| scene | interpolation |'; printf ' %s |' "${modes[@]}"; echo
printf '|---|---|'; printf -- '---|%.0s' "${modes[@]}"; echo
for dir in "$root"/golden/*/; do
  scene=$(basename "$dir")
  for interp in perspective affine; do
    printf '| %s | %s |' "$scene" "$interp"
    for mode in "${modes[@]}"; do
      err=$("$bin" render "$dir/scene.json" -o "$tmp/f.exr" --compare-reference \
              --set pipeline.normal_interp.mode=$interp --set pipeline.normalize.mode=$mode |
            sed -n 's/.*error rgb: max \([^ ]*\) at.*/\1/p')
      printf ' %.2e |' "$err"
    done
    echo
  done
done
echo
echo "Maximum |pipeline − golden model| over R, G, B; 2^-12 = 2.44e-04."
