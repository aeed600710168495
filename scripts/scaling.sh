#!/usr/bin/env bash
# Scaling of the pipeline's run time and memory with pixels and triangles, with linear
# fits (docs/benchmarks.md). One run each: these machines are noisy; read the fits' R².
# Usage: scripts/scaling.sh [--doc]   (--doc: its four tables into docs/benchmarks.md)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[[ $# == 0 || ($# == 1 && $1 == --doc) ]] || { echo "usage: scripts/scaling.sh [--doc]" >&2; exit 2; }
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
report=(python3 "$root/scripts/scaling.py" "$root/build/app/shadetlm" "$root")
if [[ ${1:-} == --doc ]]; then
  exec python3 "$root/scripts/doc-tables.py" --run "$root/docs/benchmarks.md" scaling 4 -- "${report[@]}"
fi
exec "${report[@]}"
