#!/usr/bin/env bash
# The number formats per block on the stress scenes: float16's colour difference and
# events, and the fewest fixed-point bits per block that keep the colour within 1/255
# and 2^-12 of float32 (docs/numerical-stability.md). Prints a Markdown table.
# Usage: scripts/format-report.sh [shadetlm binary]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/app/shadetlm}
[[ -x $bin ]] || { "$root/scripts/build.sh" >/dev/null; bin=$root/build/app/shadetlm; }
python3 "$root/scripts/format-report.py" "$bin" "$root"
