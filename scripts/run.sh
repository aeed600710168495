#!/usr/bin/env bash
# Set-up command 1: installs what is missing, builds, and renders the built-in demo
# scene through the SystemC pipeline to out/demo.exr and out/demo.png, with its
# statistics in out/demo-stats.json and its error against the golden model.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
cd "$root"
build/app/shadetlm render -o out/demo.exr --preview out/demo.png --stats out/demo-stats.json \
  --compare-reference "$@"
echo "demo frame: $root/out/demo.exr (preview $root/out/demo.png, statistics $root/out/demo-stats.json)"
