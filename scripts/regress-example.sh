#!/usr/bin/env bash
# The picture of docs/regression.md: the regression report as a reader opens it at
# 1280 px when the sphere's light is 2 % brighter than accepted (a copy of golden/ with
# the change, so that nothing tracked is touched), by headless Chromium.
# Usage: scripts/regress-example.sh [OUT.png]   (default docs/images/regress-example.png)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/docs/images/regress-example.png}
"$root/scripts/setup.sh" chromium
"$root/scripts/build.sh" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/root"
cp -r "$root/golden" "$tmp/root/"
ln -s "$root/scenes" "$tmp/root/scenes"  # (scenes' assets, by relative paths)
sed -i 's/"intensity": 1.0/"intensity": 1.02/' "$tmp/root/golden/sphere/scene.json"
python3 "$root/scripts/regress.py" "$root/build/app/shadetlm" "$tmp/root" "$tmp/report" --scene sphere || true
"$root/scripts/screenshot.sh" "$tmp/report/index.html" "$out" 1280x900
