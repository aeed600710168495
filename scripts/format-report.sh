#!/usr/bin/env bash
# The number formats per block on the stress scenes: float16's colour difference and
# events, and the fewest fixed-point bits per block that keep the colour within 1/255
# and 2^-12 of float32 (docs/numerical-stability.md). Prints a Markdown table.
# With --bump, the bump-mapping paper's classic and proposed datapaths on scenes/bump
# instead (into docs/bump-mapping.md with --doc).
# Usage: scripts/format-report.sh [--doc] [--bump] [shadetlm binary]   (--doc: the tables
#   into their page, between its markers)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
doc=0 bump=0 bin=$root/build/app/shadetlm
for arg in "$@"; do
  case $arg in
    --doc) doc=1 ;;
    --bump) bump=1 ;;
    -*) echo "format-report.sh: unknown option $arg (--doc, --bump)" >&2; exit 2 ;;
    *) bin=$arg ;;
  esac
done
[[ -x $bin ]] || { "$root/scripts/build.sh" >/dev/null; bin=$root/build/app/shadetlm; }
report=(python3 "$root/scripts/format-report.py" "$bin" "$root")
target=("$root/docs/numerical-stability.md" formats 2)
((bump)) && report+=(--bump) && target=("$root/docs/bump-mapping.md" bump-formats 2)
if ((doc)); then python3 "$root/scripts/doc-tables.py" --run "${target[@]}" -- "${report[@]}"; else "${report[@]}"; fi
