#!/usr/bin/env bash
# Scaling of the pipeline's run time and memory with pixels and triangles, with linear
# fits (docs/benchmarks.md). One run each: these machines are noisy; read the fits' R².
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
exec python3 "$root/scripts/scaling.py" "$root/build/app/shadetlm" "$root"
