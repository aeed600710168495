#!/usr/bin/env bash
# Runs the RTL normalize unit on test vectors (docs/rtl.md, "Test vectors"): builds
# src/shadetlm/rtl/normalize/normalize_tb.sv with Verilator (--binary) for the format and mode the
# vectors' header names — the mode's latency and II the model's defaults — and checks
# every output word against the vectors.
# Usage: scripts/rtl-vectors.sh FOLDER   (FOLDER holds normalize.in.hex and .out.hex,
#        as `shadetlm render --vectors FOLDER` writes them)
# Exit 0: every word equal; 1: some differ; 2: no vectors, or a header it cannot read.
# The testbench is built once per mode and format (about 20 s) in out/rtl-tb.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:?usage: scripts/rtl-vectors.sh FOLDER}
in=$dir/normalize.in.hex
out=$dir/normalize.out.hex
for f in "$in" "$out"; do
  [[ -r $f ]] || { echo "rtl-vectors.sh: $f: no such vectors file" >&2; exit 2; }
done
command -v verilator >/dev/null || "$root/scripts/setup.sh" verilator
about=$(sed -n '2s|^// ||p' "$in")  # "format fixed:3.20, mode exact"
if [[ ! $about =~ ^format\ fixed:([0-9]+)\.([0-9]+),\ mode\ ([a-z0-9-]+)$ ]]; then
  echo "rtl-vectors.sh: $in: line 2 should read 'format fixed:I.F, mode M' (the RTL is fixed point), not '$about'" >&2
  exit 2
fi
ibits=${BASH_REMATCH[1]} fbits=${BASH_REMATCH[2]} mode=${BASH_REMATCH[3]}
# mode: index latency II, as the build has them
read -r -a params < <(awk -v m="$mode" '$1 == m { print $2, $3, $4 }' "$root/src/shadetlm/rtl/normalize/modes.txt")
((${#params[@]} == 3)) || { echo "rtl-vectors.sh: $in: unknown mode $mode" >&2; exit 2; }
pixels=$(grep -vc '^//' "$in" || true)
if ((pixels < 1 || pixels > 1048576)) || [[ $pixels != "$(grep -vc '^//' "$out" || true)" ]]; then
  echo "rtl-vectors.sh: $dir: 1 … 1048576 pixels, as many out as in (a --trace-region keeps them few)" >&2
  exit 2
fi
# The testbench's build, kept per mode and format (RTL_TB_DIR: elsewhere than out/).
obj=${RTL_TB_DIR:-$root/out/rtl-tb}/$mode.fixed-$ibits.$fbits  # (no colon: make reads the path)
rtl=$root/src/shadetlm/rtl/normalize
sources=("$rtl/normalize_tb.sv" "$rtl/normalize_unit.sv" "$rtl/normalize_datapath.sv" "$rtl/fx_isqrt.sv")
stale=0
for s in "${sources[@]}"; do [[ $s -nt $obj/Vnormalize_tb ]] && stale=1; done
if [[ ! -x $obj/Vnormalize_tb ]] || ((stale)); then
  mkdir -p "$obj"
  verilator --binary -Wall -Wno-DECLFILENAME --Mdir "$obj" -j "$(nproc)" --top-module normalize_tb \
    -GIBITS="$ibits" -GFBITS="$fbits" -GMODE="${params[0]}" -GLATENCY="${params[1]}" -GII="${params[2]}" \
    "${sources[@]}" >"$obj/build.log" 2>&1 ||
    { tail -20 "$obj/build.log" >&2; exit 2; }
fi
status=0
("$obj/Vnormalize_tb" +in="$in" +out="$out" +pixels="$pixels") >"$obj/run.log" 2>&1 || status=$?
grep '^normalize_tb' "$obj/run.log" || tail -3 "$obj/run.log"
((status == 0)) || exit 1
