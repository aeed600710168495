#!/usr/bin/env bash
# Golden-image regression with an HTML report: every golden scene under each of its
# configurations (golden/<scene>/golden.json), through the SystemC pipeline, compared per
# layer and per block's cycles with what was accepted, and with the golden model.
# Writes out/report/index.html (failures first). Exit 0 when everything passes.
# REGEN_GOLDEN=1 rewrites only what fails or is missing, and prints what changed (never
# under CI). ctest -L golden runs the same checks as tests (docs/regression.md).
# Usage: scripts/regress.sh [--no-build] [--scene NAME ...]   (options in any order)
#   --no-build: the program as built (build/app/shadetlm), no setup and no build first: the
#   report's accept commands use it, since the run they accept has just built it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=1
args=()
for a in "$@"; do [[ $a == --no-build ]] && build=0 || args+=("$a"); done
set -- "${args[@]}"
if ((build == 0)); then
  [[ -x $root/build/app/shadetlm ]] ||
    { echo "regress.sh: --no-build: $root/build/app/shadetlm is not built (scripts/build.sh builds it)" >&2; exit 2; }
else
  "$root/scripts/setup.sh"
  "$root/scripts/build.sh" >/dev/null
fi
out=$root/out/report
rm -rf "$out"
mkdir -p "$out"
exec python3 "$root/scripts/regress.py" "$root/build/app/shadetlm" "$root" "$out" "$@"
