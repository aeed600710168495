#!/usr/bin/env bash
# Set-up command 1: installs what is missing, builds, and renders the built-in demo
# scene to out/demo.exr and out/demo.png.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
cd "$root"
# The SystemC pipeline arrives with the next issue; until then the golden model
# renders the demo.
build/app/shadetlm reference -o out/demo.exr --preview out/demo.png "$@"
echo "demo frame: $root/out/demo.exr (preview $root/out/demo.png)"
