#!/usr/bin/env bash
# A screenshot of GTKWave on a waveform view (a render's trace.gtkw), as a user first sees
# it, under a virtual X server: docs/inspecting.md's picture. Installs what it needs.
# Usage: scripts/gtkwave-shot.sh VIEW.gtkw OUT.png [WIDTHxHEIGHT]   (default 1400x900)
# The docs' picture: scripts/gtkwave-shot.sh --doc (the built-in demo's trace of the
# README's region, into docs/images/gtkwave.png).
# Exit 0 with OUT.png written; 2 on bad arguments or a missing view; 1 when GTKWave shows
# no window or the picture does not settle.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
usage="usage: scripts/gtkwave-shot.sh VIEW.gtkw OUT.png [WIDTHxHEIGHT], or --doc"
if [[ ${1:-} == --doc ]]; then
  (($# == 1)) || { echo "$usage" >&2; exit 2; }
  "$root/scripts/setup.sh"
  "$root/scripts/build.sh" >/dev/null
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  "$root/build/app/shadetlm" render -o "$work/demo.exr" --vcd "$work/trace.vcd" --trace-region 250,170,265,170 >/dev/null
  "$0" "$work/trace.gtkw" "$root/docs/images/gtkwave.png"
  exit
fi
(($# >= 2 && $# <= 3)) || { echo "$usage" >&2; exit 2; }
view=$1 out=$2 size=${3:-1400x900}
[[ -f $view ]] || { echo "gtkwave-shot.sh: no view $view" >&2; exit 2; }
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "gtkwave-shot.sh: size $size is not WIDTHxHEIGHT" >&2; exit 2; }
"$root/scripts/setup.sh" gtkwave xvfb xdotool imagemagick
view=$(realpath "$view")
mkdir -p "$(dirname "$out")"
out=$(realpath "$out")
rm -f "$out"
# In the virtual display: GTKWave from the view's folder (it finds its VCD beside it);
# wait for its window, fill the screen with it, then take a picture every half second
# until two in a row are the same (it has drawn the waves), at most 60.
xvfb-run -a -s "-screen 0 ${size}x24" bash -c '
  set -o pipefail
  view=$1 out=$2 size=$3
  cd "$(dirname "$view")"
  gtkwave "$view" >/dev/null 2>&1 &
  gtkwave=$!
  trap "kill $gtkwave 2>/dev/null" EXIT
  window=$(timeout 60 xdotool search --sync --onlyvisible --name "GTKWave" | head -1) || exit 1
  xdotool windowmove "$window" 0 0 windowsize "$window" "${size%x*}" "${size#*x}"
  before=
  for try in $(seq 60); do
    sleep 0.5  # (the interval between pictures that must agree)
    import -window root "$out.try.png"
    now=$(md5sum <"$out.try.png")
    [[ $now == "$before" ]] && { mv "$out.try.png" "$out"; exit 0; }
    before=$now
  done
  exit 1' bash "$view" "$out" "$size" || {
  rm -f "$out.try.png"
  echo "gtkwave-shot.sh: GTKWave showed no window, or its picture did not settle" >&2
  exit 1
}
echo "$out"
