#!/usr/bin/env bash
# The RTL normalize unit's silicon cost (docs/rtl.md, "Silicon cost"), every figure
# printed here: Yosys synthesizes src/shadetlm/rtl/normalize to generic cells for each mode at the
# widths the format report names (docs/numerical-stability.md: fixed:1.12, the fewest
# bits that keep the long-spans scene within 1/255; fixed:3.16, tiny normals within
# 2^-12), and prints
#   - the datapath alone (normalize_datapath: one pixel's arithmetic, combinational):
#     cells and Yosys's CMOS transistor estimate (`stat -tech cmos`);
#   - the unit around it at the mode's latency and II (the datapath a black box, no tag
#     bits): its flip-flops — the radicand's registers and the pixels held for the
#     latency, ⌈(latency + 1) / II⌉ of them;
#   - beside them, from renders of the same configuration: the model's operations a
#     pixel (the block's declared counts) and the normal's largest error against the
#     golden model on the long-spans stress scene (`render --compare-reference`, layer N).
# Usage: scripts/synth.sh [--quick] [--doc] [--formats "fixed:I.F …"]
#   --quick    fixed:1.12 only (about 10 minutes on 2 cores; the table about 40: Yosys's
#              ABC pass on the dividers and square roots dominates, and grows fast with
#              the width)
#   --doc      the table into docs/rtl.md between its <!-- synth:1 --> markers
# A datapath's synthesis is kept in out/synth and reused while the RTL is unchanged.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" yosys
bin=${SHADETLM:-$root/build/app/shadetlm}
[[ -x $bin ]] || "$root/scripts/build.sh" >/dev/null
formats="fixed:1.12 fixed:3.16"
doc=0
while (($#)); do
  case $1 in
    --quick) formats="fixed:1.12" ;;
    --doc) doc=1 ;;
    --formats) formats=${2:?--formats needs a list}; shift ;;
    *) echo "usage: scripts/synth.sh [--quick] [--doc] [--formats \"fixed:I.F …\"]" >&2; exit 2 ;;
  esac
  shift
done
for f in $formats; do
  [[ $f =~ ^fixed:[0-9]+\.[1-9][0-9]*$ ]] || { echo "synth.sh: $f: formats are fixed:I.F" >&2; exit 2; }
done
out=$root/out/synth
mkdir -p "$out"
rtl=$root/src/shadetlm/rtl/normalize
# mode index latency II, as the build has them
mapfile -t modes < <(grep '^[a-z]' "$rtl/modes.txt" | tr -s ' ')

# synth FORMAT MODE INDEX LATENCY II: Yosys's statistics of the datapath (reused while
# the RTL is older than its log) and of the unit around it.
synth() {
  local format=$1 mode=$2 index=$3 latency=$4 ii=$5 ib fb
  ib=${format#fixed:}; ib=${ib%.*}; fb=${format#*.}
  local tag="$mode.$format" log
  log=$out/$tag.normalize_datapath.log
  if [[ ! -s $log || $rtl/normalize_datapath.sv -nt $log || $rtl/fx_isqrt.sv -nt $log ]] ||
     ! grep -q "Estimated number of transistors" "$log"; then
    cat >"$out/$tag.normalize_datapath.ys" <<EOF
read_verilog -sv $rtl/normalize_datapath.sv $rtl/fx_isqrt.sv
chparam -set IBITS $ib -set FBITS $fb -set MODE $index normalize_datapath
synth -top normalize_datapath -flatten
stat -tech cmos
EOF
    yosys -q -l "$log.tmp" "$out/$tag.normalize_datapath.ys" >/dev/null && mv "$log.tmp" "$log"
  fi
  cat >"$out/$tag.normalize_unit.ys" <<EOF
read_verilog -sv -lib $rtl/normalize_datapath.sv
read_verilog -sv $rtl/normalize_unit.sv
chparam -set IBITS $ib -set FBITS $fb -set MODE $index -set LATENCY $latency -set II $ii -set TAG_W 1 normalize_unit
synth -top normalize_unit -flatten
stat -tech cmos
EOF
  yosys -q -l "$out/$tag.normalize_unit.log" "$out/$tag.normalize_unit.ys" >/dev/null
}
export -f synth
export out rtl
jobs=()
for f in $formats; do for m in "${modes[@]}"; do jobs+=("$f $m"); done; done
printf '%s\n' "${jobs[@]}" | xargs -P "$(nproc)" -L 1 bash -c 'synth "$@"' _

python3 - "$bin" "$root" "$out" "$formats" <<'PY' | tee "$out/synth.txt"
import json, re, subprocess, sys
bin, root, out, formats = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split()
modes = ["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]
scene = f"{root}/scenes/stress/long-spans.json"

def stat(path):
    text = open(path).read()
    cells = int(re.findall(r"Number of cells:\s+(\d+)", text)[-1])
    transistors = int(re.findall(r"Estimated number of transistors:\s+(\d+)", text)[-1])
    flops = sum(int(n) for n in re.findall(r"\$_(?:S?DFF\w*)_\s+(\d+)", text.split("Number of cells")[-1]))
    return cells, transistors, flops

def render(mode, fmt):
    subprocess.run([bin, "render", scene, "-o", f"{out}/f.exr", "--stats", f"{out}/s.json", "--compare-reference",
                    "--set", f"pipeline.normalize.mode={mode}", "--set", f"pipeline.normalize.format={fmt}",
                    "--allow-overflow"],  # (its saturations are counted in the stats)
                   check=True, capture_output=True)
    s = json.load(open(f"{out}/s.json"))
    block = s["blocks"]["normalize"]
    ops = sum(v for k, v in block["ops"].items()) / block["pixels"]
    return ops, s["error"]["n"]["max"]

print("| mode | format | datapath cells | datapath transistors | unit flip-flops | latency / II |"
      " model ops a pixel | normal error, max (long-spans) |")
print("|---|---|---:|---:|---:|---|---:|---:|")
timing = {w[0]: f"{w[2]} / {w[3]}" for w in (l.split() for l in open(f"{root}/src/shadetlm/rtl/normalize/modes.txt")) if w[0][0].isalpha()}
for fmt in formats:
    for mode in modes:
        cells, transistors, _ = stat(f"{out}/{mode}.{fmt}.normalize_datapath.log")
        _, _, flops = stat(f"{out}/{mode}.{fmt}.normalize_unit.log")
        ops, err = render(mode, fmt)
        print(f"| {mode} | `{fmt}` | {cells} | {transistors} | {flops} | {timing[mode]} | {ops:.2f} | {err:.2e} |")
PY
if ((doc)); then
  python3 "$root/scripts/doc-tables.py" "$out/synth.txt" "$root/docs/rtl.md" synth 1
  echo "docs/rtl.md updated"
fi
