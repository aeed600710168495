#!/usr/bin/env bash
# The texturing report: prints the Markdown tables that docs/object-space-texturing.md
# keeps (accuracy of object-space texturing and of each screen-space filter against the
# footprint-averaged golden model; texel fetches, arithmetic, LOD computations and holes
# per pixel; parallel splat units; the plane every 5° against 16-probe anisotropic
# filtering, and the crossover angles). The photograph is skimage's astronaut (CC0), taken
# from the Debian package python3-skimage into out/assets (downloaded, not installed;
# without it the photograph's table is left out). About 300 renders (the angle sweep: 162), several minutes.
# Usage: scripts/texture-report.sh [--doc] [--images DIR]   (--doc: the tables into
#   docs/object-space-texturing.md, between their markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
doc=0 args=()
for arg in "$@"; do
  if [[ $arg == --doc ]]; then doc=1; else args+=("$arg"); fi
done
photo=$("$root/scripts/skimage-asset.sh" astronaut.png)
report=(python3 "$root/scripts/texture-report.py" "$root/build/app/shadetlm" "$photo" ${args[@]+"${args[@]}"})
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "$root/docs/object-space-texturing.md" texture 9 -- "${report[@]}"; else "${report[@]}"; fi
