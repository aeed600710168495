#!/usr/bin/env bash
# The pictures of docs/inspecting.md's timeline section: the golden demo scene's
# timeline (render --timeline t.html), as the offline viewer shows it in a 1400x900
# window — the whole frame, then its first cycles with one packet selected.
# Usage: scripts/timeline-shots.sh [OUT_DIR]   (default docs/images)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/docs/images}
"$root/scripts/setup.sh" chromium
"$root/scripts/build.sh" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$root/build/app/shadetlm" render "$root/golden/demo/scene.json" -o "$tmp/demo.exr" --timeline "$tmp/demo.html" >/dev/null
"$root/scripts/screenshot.sh" "$tmp/demo.html" "$out/timeline.png" 1400x900
"$root/scripts/screenshot.sh" "$tmp/demo.html" "$out/timeline-zoom.png" 1400x900 "view=0-1500&select=3"
# The size of a whole frame's timeline, for the doc's words: the built-in demo at 640x360.
"$root/build/app/shadetlm" render -o "$tmp/big.exr" --timeline "$tmp/big.json" >/dev/null
python3 - "$tmp/big.json" <<'PY'
import json, os, sys
events = json.load(open(sys.argv[1]))["traceEvents"]
slices = sum(e["ph"] == "X" for e in events)
print("built-in demo at 640x360: %d slices, %.0f MB" % (slices, os.path.getsize(sys.argv[1]) / 1e6))
PY
