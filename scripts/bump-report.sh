#!/usr/bin/env bash
# The bump-mapping report: prints the Markdown tables that docs/bump-mapping.md keeps
# (blocks and costs per path, datapath ranges, error per surface, depth and view, and
# each approximation on its own). About 200 small renders, a minute or two.
# Usage: scripts/bump-report.sh [--images DIR]   (DIR: a PNG preview per path)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
exec python3 "$root/scripts/bump-report.py" "$root/build/app/shadetlm" "$@"
