#!/usr/bin/env bash
# The parallax report: prints the Markdown tables that docs/parallax.md keeps — every
# tracer (offset limiting, steep, POM, relief, Donnelly's distance map, the refined map,
# cone stepping) on five height maps at view elevations of 60°, 30°, 15° and 5°, against
# the golden model's exact hit; the paper's claim as a figure; the maps' precompute time
# and size for 256², 512² and 1024² height maps — and writes the heat maps of
# iterations per pixel into out/parallax/. The real height map is skimage's moon (a
# photograph of lunar terrain, public domain), taken from the Debian package
# python3-skimage into out/assets (downloaded, not installed; without it that map is
# left out). A few minutes.
# Usage: scripts/parallax-report.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
real=$("$root/scripts/skimage-asset.sh" moon.png)
exec python3 "$root/scripts/parallax-report.py" "$root/build/app/shadetlm" "$root" "$real"
