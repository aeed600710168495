#!/usr/bin/env bash
# The parallax report: prints the Markdown tables that docs/parallax.md keeps — every
# tracer (offset limiting, steep, POM, relief, Donnelly's map as published, the box-gap
# map, the refined map at margin 0 and at the headline margin, classic and relaxed cone
# stepping) on six height maps at view elevations of 60°, 30°, 15° and 5°, against the
# golden model's exact hit, in iterations, cycles and operations; the paper's claim at a
# safe margin and at margin 0; the maps' precompute time and size for 256², 512² and
# 1024² height maps; relaxed cones against classic ones — and writes the heat maps of
# iterations per pixel into out/parallax/. Two real height maps, downloaded, never
# committed: a USGS elevation model (matplotlib's sample data, scripts/dem-asset.sh) and
# skimage's moon (a photograph of lunar terrain, public domain, scripts/skimage-asset.sh);
# without them their tables are left out. About ten minutes.
# Usage: scripts/parallax-report.sh [--doc]   (--doc: the tables into docs/parallax.md,
#   between their markers, and the heat maps into docs/images)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
doc=0
[[ ${1:-} == --doc ]] && doc=1
dem=$("$root/scripts/dem-asset.sh")
moon=$("$root/scripts/skimage-asset.sh" moon.png)
reals=()
[[ -n $dem ]] && reals+=("terrain (USGS elevation model, Jacksboro fault, 512²)=$dem")
[[ -n $moon ]] && reals+=("moon (skimage photograph, 512²)=$moon")
report=(python3 "$root/scripts/parallax-report.py" "$root/build/app/shadetlm" "$root" ${reals[@]+"${reals[@]}"})
if ((doc)); then
  python3 "$root/scripts/doc-tables.py" --run "$root/docs/parallax.md" parallax 12 -- "${report[@]}"
  for m in donnelly box-gap refined cone relaxed-cone relief; do
    cp "$root/out/parallax/steps-$m-heat.png" "$root/docs/images/parallax-steps-$m-heat.png"
  done
else
  "${report[@]}"
fi
