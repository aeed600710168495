#!/usr/bin/env bash
# A headless screenshot of a local HTML page (a report, a timeline) with Debian's chromium,
# to look at a page without a browser: scripts/setup.sh chromium installs it.
# Usage: scripts/screenshot.sh PAGE.html OUT.png [WIDTHxHEIGHT [FRAGMENT]]   (default 1280x900;
#   FRAGMENT: the address's #part, e.g. a timeline's view=0-3000&select=5)
# Exit 0 with OUT.png written; 2 on bad arguments or a missing page; 1 when chromium is
# missing, fails, or writes no PNG.
set -euo pipefail
usage="usage: scripts/screenshot.sh PAGE.html OUT.png [WIDTHxHEIGHT [FRAGMENT]]"
(($# >= 2 && $# <= 4)) || { echo "$usage" >&2; exit 2; }
page=$1 out=$2 size=${3:-1280x900} fragment=${4:-}
[[ -f $page ]] || { echo "screenshot.sh: no page $page" >&2; exit 2; }
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "screenshot.sh: size $size is not WIDTHxHEIGHT" >&2; exit 2; }
width=${BASH_REMATCH[1]} height=${BASH_REMATCH[2]}
command -v chromium >/dev/null || { echo "screenshot.sh: no chromium (scripts/setup.sh chromium)" >&2; exit 1; }

url=$(python3 -c 'import pathlib, sys; print(pathlib.Path(sys.argv[1]).resolve().as_uri())' "$page")  # spaces, #, %
[[ -z $fragment ]] || url+="#$fragment"
mkdir -p "$(dirname "$out")"
out=$(realpath "$out")
rm -f "$out"  # so that a PNG left from an earlier run does not pass for this one
# A profile of its own: chromium refuses a second instance on a profile in use, and the
# screenshot should not depend on (or change) the user's.
profile=$(mktemp -d)
log=$(mktemp)
trap 'rm -rf "$profile" "$log"' EXIT
status=0
# --run-all-compositor-stages-before-draw: without it a tile was once left white on a loaded machine.
timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$profile" \
  --no-first-run --run-all-compositor-stages-before-draw --window-size="$width,$height" --screenshot="$out" \
  "$url" >"$log" 2>&1 || status=$?
if ((status != 0)) || [[ ! -s $out ]]; then
  cat "$log" >&2  # chromium's own words only when they matter: it is chatty when it works
  echo "screenshot.sh: chromium exited $status$([[ -s $out ]] || echo ", no PNG at $out")" >&2
  exit 1
fi
echo "$out"
