#!/usr/bin/env bash
# An architect's walk-through (docs/architect.md), every figure printed here:
#  1. the bottleneck of a scene: each block's busy, starved and blocked cycles;
#  2. sizing the FIFOs: frame cycles against one depth for every span block's FIFO,
#     on the golden scenes (a table, and out/architect/fifo-depth.png);
#  3. two normalization units compared in cycles and in error (every normalize mode on
#     a scene: frame cycles, normalize's latency and II, RGB error against the golden
#     model; a table, and out/architect/normalize-units.png).
# Usage: scripts/architect.sh [--doc] [SCENE]   (default: golden/sphere/scene.json)
#   --doc: also put the three tables into docs/architect.md, between its markers.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" gnuplot-nox
bin=$root/build/app/shadetlm
[[ -x $bin ]] || "$root/scripts/build.sh" >/dev/null
doc=0
[[ ${1:-} == --doc ]] && { doc=1; shift; }
# docs/architect.md reads its tables as golden/sphere's.
((doc)) && [[ $# -gt 0 ]] && { echo "architect.sh: --doc takes no SCENE (the page is about golden/sphere)" >&2; exit 2; }
scene=${1:-$root/golden/sphere/scene.json}
out=$root/out/architect
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
spans=(normal_interp bump_fetch bump_perturb normal_mux normalize vector_interp texture_fetch lighting framebuffer parallax)

report() {
echo "## 1. The bottleneck of $(basename "$(dirname "$scene")")"
"$bin" render "$scene" -o "$tmp/f.exr" --stats "$tmp/s.json" >/dev/null
python3 - "$tmp/s.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"\nframe cycles {s['frame_cycles']}, bottleneck {s['bottleneck']}\n")
print("| block | latency | ii | busy | starved | blocked | utilization | FIFO peak | FIFO mean |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for name in s["elaborated"]:
    b = s["blocks"][name]
    fifo = f"{b['fifo_peak']} | {b['fifo_mean']:.2f}" if "fifo_peak" in b else "— | —"  # setup, the raster: none measured
    print(f"| {name} | {b['latency']} | {b['ii']} | {b['busy_cycles']} | {b['starved_cycles']} | "
          f"{b['blocked_cycles']} | {b['utilization']:.2f} | {fifo} |")
PY

echo
echo "## 2. Frame cycles against the FIFO depth (every span block's FIFO)"
depths=(1 2 3 4 6 8 12 16 32)
scenes=(sphere demo bump-knot texture-screen parallax-steps)
printf "\n| depth |"; for s in "${scenes[@]}"; do printf " %s |" "$s"; done; printf "\n|---:|"
for s in "${scenes[@]}"; do printf -- "---:|"; done; echo
: >"$tmp/fifo.dat"
for d in "${depths[@]}"; do
  args=()
  for b in "${spans[@]}"; do args+=(--set "pipeline.$b.fifo_depth=$d"); done
  printf "| %s |" "$d"; printf "%s" "$d" >>"$tmp/fifo.dat"
  for s in "${scenes[@]}"; do
    cycles=$("$bin" render "$root/golden/$s/scene.json" "${args[@]}" -o "$tmp/f.exr" --stats "$tmp/s.json" >/dev/null &&
             python3 -c "import json; print(json.load(open('$tmp/s.json'))['frame_cycles'])")
    printf " %s |" "$cycles"; printf " %s" "$cycles" >>"$tmp/fifo.dat"
  done
  echo; echo >>"$tmp/fifo.dat"
done
{
  echo "set terminal png size 900,600 noenhanced"
  echo "set output '$out/fifo-depth.png'"
  echo "set title 'Frame cycles against the FIFO depth of every span block (relative to depth 1)'"
  echo "set xlabel 'FIFO depth (pixels)'; set ylabel 'frame cycles / frame cycles at depth 1'; set logscale x 2; set key outside"
  printf "plot "
  for i in "${!scenes[@]}"; do
    c=$((i + 2)); printf "'%s' using 1:(\$%d/first%d) with linespoints title '%s'" "$tmp/fifo.dat" "$c" "$c" "${scenes[$i]}"
    [[ $i -lt $((${#scenes[@]} - 1)) ]] && printf ", "
  done
  echo
} >"$tmp/fifo.gp"
# gnuplot has no "first row" variable: normalize by each column's first value.
for i in "${!scenes[@]}"; do
  c=$((i + 2)); first=$(head -1 "$tmp/fifo.dat" | awk -v c="$c" '{print $c}')
  sed -i "s/first$c)/$first)/" "$tmp/fifo.gp"
done
gnuplot "$tmp/fifo.gp"

echo
echo "## 3. Normalization units: cycles and error ($(basename "$(dirname "$scene")"))"
printf "\n| normalize.mode | latency | ii | frame cycles | RGB PSNR (dB) | RGB max error |\n|---|---:|---:|---:|---:|---:|\n"
: >"$tmp/units.dat"
for m in exact forward-difference rsqrt0 rsqrt1 rsqrt2; do
  "$bin" render "$scene" --set pipeline.normalize.mode=$m --compare-reference -o "$tmp/f.exr" --stats "$tmp/s.json" >/dev/null
  python3 - "$tmp/s.json" "$m" >>"$tmp/units.dat" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); n = s["blocks"]["normalize"]; e = s["error"]["rgb"]
print(f"{sys.argv[2]} {n['latency']} {n['ii']} {s['frame_cycles']} {e['psnr']} {e['max']}")
PY
  tail -1 "$tmp/units.dat" | awk '{printf "| %s | %s | %s | %s | %.1f | %.2e |\n", $1, $2, $3, $4, $5, $6}'
done
gnuplot <<GP
set terminal png size 900,600 noenhanced
set output '$out/normalize-units.png'
set title 'normalize: frame cycles against RGB error, $(basename "$(dirname "$scene")")'
set xlabel 'frame cycles'; set ylabel 'RGB PSNR against the golden model (dB)'; set key off
set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1
plot '$tmp/units.dat' using 4:5 with points pt 7 ps 2, '' using 4:5:1 with labels offset 0,1.2
GP
echo
echo "plots: $out/fifo-depth.png, $out/normalize-units.png"
}
report | tee "$out/architect.txt"
if ((doc)); then
  # Each table of the output between <!-- architect:N --> and <!-- /architect:N -->.
  cp "$out/fifo-depth.png" "$out/normalize-units.png" "$root/docs/images/"
  python3 "$root/scripts/doc-tables.py" "$out/architect.txt" "$root/docs/architect.md" architect 3
fi
