#!/usr/bin/env bash
# RTL in the loop (docs/rtl.md): the verilated normalize unit against the C++ kernel and
# the clocked timing reference.
#  1. Bit-exact: every golden scene in every mode, the RTL in the loop
#     (pipeline.normalize.impl=rtl, which also checks the unit's pin timing pixel by
#     pixel) against the fixed-point kernel in the same format: RGB, Z and N identical —
#     and different from the float32 frame (the format is in force).
#  2. Cycle-exact: the clocked reference with the RTL as its normalize unit, in lockstep
#     (timing-check --rtl-normalize), against the fast model's times for every pixel at
#     every block: the golden scenes in every mode, and configurations where the unit's
#     output stalls (FIFOs of one, a slow lighting block). And the check fails where it
#     must: a forward-difference log with half its packet starts taken out.
#  3. Refusals: another format, another latency, the loop engine, logs that do not fit
#     the unit — exit 2, the setting named. The waveforms: the unit's, and merged.
#  4. Test vectors through the RTL testbench, at the build's format and at a narrow one.
#  5. Yosys synthesizes the RTL without latches (skipped, said, without Yosys).
# Usage: rtl_test.sh SHADETLM SOURCE_DIR. Exit 77 (skipped) when the build has no RTL.
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0
failures=0
ok() { echo "ok $*"; ((passes++)); }
fail() { echo "FAIL $*"; ((failures++)); }

format=$("$bin" --version 2>/dev/null | sed -n 's/^rtl: \(fixed:[0-9.]*\);.*/\1/p')
if [[ -z $format ]]; then
  echo "SKIP: this build has no RTL normalize unit ($("$bin" --version | grep '^rtl:'))"
  exit 77
fi
modes=(exact forward-difference rsqrt0 rsqrt1 rsqrt2)
# Under AddressSanitizer (scripts/test.sh --sanitize) three golden scenes, not all: the
# same code paths (Phong, bump, mesh) at a third of the time, within CI's budget.
scenes=("$src"/golden/*/scene.json)
if ldd "$bin" | grep -q libasan; then
  scenes=("$src/golden/sphere/scene.json" "$src/golden/bump-knot/scene.json" "$src/golden/knot/scene.json")
fi

# 1. Bit-exact frames.
for scene in "${scenes[@]}"; do
  name=$(basename "$(dirname "$scene")")
  for mode in "${modes[@]}"; do
    # (a narrow format saturates on some scenes, exit 3 unless allowed: the frames' bits are what is compared)
    set_=(--set pipeline.normalize.mode=$mode --set pipeline.normalize.format=$format --allow-overflow)
    if ! "$bin" render "$scene" "${set_[@]}" -o "$tmp/kernel.exr" >"$tmp/out" 2>&1 ||
       ! "$bin" render "$scene" "${set_[@]}" --set pipeline.normalize.impl=rtl -o "$tmp/rtl.exr" >"$tmp/out" 2>&1; then
      fail "$name $mode: render"; tail -3 "$tmp/out" | sed 's/^/    /'; continue
    fi
    if "$bin" compare "$tmp/rtl.exr" "$tmp/kernel.exr" --fail 0 >"$tmp/cmp" 2>&1; then
      ok "$name $mode: RTL frame identical to the $format kernel's"
    else
      fail "$name $mode: RTL frame differs from the kernel's"; tail -4 "$tmp/cmp" | sed 's/^/    /'
    fi
  done
done
"$bin" render "$src/golden/sphere/scene.json" -o "$tmp/float.exr" >/dev/null 2>&1
"$bin" render "$src/golden/sphere/scene.json" --set pipeline.normalize.format="$format" \
  --set pipeline.normalize.impl=rtl -o "$tmp/rtl.exr" >/dev/null 2>&1
if ! "$bin" compare "$tmp/rtl.exr" "$tmp/float.exr" --fail 0 --layer N >/dev/null 2>&1; then
  ok "control: the RTL's $format normals differ from float32's"
else
  fail "control: the RTL frame equals the float32 frame (is the format in force?)"
fi

# 2. Cycle-exact against the clocked reference, the RTL in lockstep.
# lockstep NAME MODE SCENE [--set k=v]...: render with MODE's kernel, check with its RTL.
lockstep() {
  local name=$1 mode=$2 scene=$3
  shift 3
  if ! "$bin" render "$scene" --set pipeline.normalize.mode="$mode" "$@" -o "$tmp/f.exr" \
       --timing-log "$tmp/t.log" >"$tmp/out" 2>&1; then
    fail "$name: render"; tail -3 "$tmp/out" | sed 's/^/    /'; return
  fi
  if "$bin" timing-check "$tmp/t.log" --rtl-normalize "$mode" --show 5 >"$tmp/check" 2>&1; then
    ok "$name: $(head -1 "$tmp/check" | cut -d: -f2-)"
  else
    fail "$name:"; sed 's/^/    /' "$tmp/check"
  fi
}
for scene in "${scenes[@]}"; do
  for mode in "${modes[@]}"; do lockstep "lockstep $(basename "$(dirname "$scene")") $mode" "$mode" "$scene"; done
done
stall=(--set pipeline.normalize.fifo_depth=1 --set pipeline.lighting.fifo_depth=1 --set pipeline.lighting.ii=5)
for mode in "${modes[@]}"; do
  lockstep "lockstep $mode, its output stalled" "$mode" "$src/golden/knot/scene.json" "${stall[@]}"
done
blocked=$(awk '$1 == "stats" && $2 == "normalize" { print $5 }' "$tmp/t.log")
if ((blocked > 0)); then ok "the stalled configuration stalls normalize ($blocked blocked cycles)"
else fail "the stalled configuration never blocked normalize"; fi
lockstep "lockstep forward-difference, bump packets" forward-difference "$src/golden/bump-knot/scene.json" "${stall[@]}"

# The RTL did run in the loop: its clock cycles are in the statistics.
"$bin" render "$src/golden/torus/scene.json" --set pipeline.normalize.format="$format" \
  --set pipeline.normalize.impl=rtl -o "$tmp/f.exr" --stats "$tmp/s.json" >/dev/null 2>&1
cycles=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["blocks"]["normalize"]["details"]["rtl_cycles"])' \
  "$tmp/s.json" 2>/dev/null || echo 0)
if ((cycles > 0)); then ok "the RTL in the loop clocked $cycles cycles on the torus"
else fail "the statistics show no RTL cycles"; fi

# The check fails where the RTL does not do what the log says: with every other packet
# start (k record) taken out, the forward-difference unit seeds less often than the
# fast model did (a seed is a cycle of work), and the times part.
"$bin" render "$src/golden/sphere/scene.json" --set pipeline.normalize.mode=forward-difference -o "$tmp/f.exr" \
  --timing-log "$tmp/t.log" >/dev/null 2>&1
cp "$tmp/t.log" "$tmp/fd.log"
awk '$1 == "k" && n++ % 2 { next } { print }' "$tmp/fd.log" >"$tmp/fewer-k.log"
"$bin" timing-check "$tmp/fewer-k.log" --rtl-normalize forward-difference >"$tmp/check" 2>&1
status=$?
if ((status == 1)) && grep -q DIFFERENT "$tmp/check"; then ok "control: the RTL seeding where the log does not differs"
else fail "control: the RTL against a log with half its packet starts: exit $status"; fi

# 3. Refusals, each naming its setting, and the waveform.
# refuse NAME FIELD ARGS...: exit 2, FIELD in the message, no frame.
refuse() {
  local name=$1 field=$2
  shift 2
  rm -f "$tmp/r.exr"
  "$bin" "$@" >"$tmp/out" 2>&1
  local status=$?
  if ((status == 2)) && grep -q -- "$field" "$tmp/out" && [[ ! -e $tmp/r.exr ]]; then ok "refused: $name"
  else fail "refused: $name (exit $status)"; sed 's/^/    /' "$tmp/out" | tail -3; fi
}
refuse "another format" pipeline.normalize.format render "$src/golden/sphere/scene.json" -o "$tmp/r.exr" \
  --set pipeline.normalize.impl=rtl --set pipeline.normalize.format=fixed:4.20
refuse "another latency" pipeline.normalize.impl render "$src/golden/sphere/scene.json" -o "$tmp/r.exr" \
  --set pipeline.normalize.impl=rtl --set pipeline.normalize.format="$format" --set pipeline.normalize.latency=2
refuse "the loop engine" pipeline.normalize.impl render "$src/golden/sphere/scene.json" -o "$tmp/r.exr" \
  --set pipeline.normalize.impl=rtl --set pipeline.normalize.format="$format" --engine loop
"$bin" render "$src/golden/sphere/scene.json" -o "$tmp/f.exr" --timing-log "$tmp/t.log" >/dev/null 2>&1
sed 's/normalize/normalise/' "$tmp/t.log" >"$tmp/no-normalize.log"
refuse "a log without normalize" block timing-check "$tmp/no-normalize.log" --rtl-normalize exact
refuse "a log of another mode" "block normalize" timing-check "$tmp/t.log" --rtl-normalize rsqrt1
grep -v '^k$' "$tmp/fd.log" >"$tmp/no-k.log"
refuse "a forward-difference log without packet starts" "no k records" timing-check "$tmp/no-k.log" \
  --rtl-normalize forward-difference

"$bin" render "$src/golden/sphere/scene.json" -o "$tmp/f.exr" --timing-log "$tmp/t.log" >/dev/null 2>&1
if "$bin" timing-check "$tmp/t.log" --rtl-normalize exact --rtl-vcd "$tmp/rtl.vcd" >/dev/null 2>&1 &&
   grep -q 'normalize_unit' "$tmp/rtl.vcd" && grep -q ' held_due' "$tmp/rtl.vcd" && grep -q ' out_valid' "$tmp/rtl.vcd" &&
   ! ls "$tmp"/rtl.vcd.tmp.* >/dev/null 2>&1; then
  ok "the RTL's waveform: $(grep -c '\$var' "$tmp/rtl.vcd") signals, $(grep -c '^#' "$tmp/rtl.vcd") time steps"
else
  fail "the RTL's waveform"
fi

# One waveform of the pipeline's blocks and the RTL (scripts/merge-vcd.py), its times in order.
"$bin" render "$src/golden/sphere/scene.json" -o "$tmp/f.exr" --vcd "$tmp/tlm.vcd" --trace-region 40,30,48,34 \
  --timing-log "$tmp/t.log" >/dev/null 2>&1
"$bin" timing-check "$tmp/t.log" --rtl-normalize exact --rtl-vcd "$tmp/rtl.vcd" >/dev/null 2>&1
if python3 "$src/scripts/merge-vcd.py" "$tmp/tlm.vcd" "$tmp/rtl.vcd" "$tmp/both.vcd" >"$tmp/m" 2>&1 &&
   grep -q 'scope module normalize ' "$tmp/both.vcd" && grep -q 'normalize_unit' "$tmp/both.vcd" &&
   grep '^#' "$tmp/both.vcd" | tr -d '#' | sort -n -c 2>/dev/null && grep -q 'normalize_unit.out_valid' "$tmp/both.gtkw"; then
  ok "one waveform, pipeline and RTL: $(cat "$tmp/m")"
else
  fail "the merged waveform:"; sed 's/^/    /' "$tmp/m"
fi

# 4. Test vectors: the kernel's words, through the RTL testbench (Verilator --binary).
"$bin" render "$src/golden/bump-sphere/scene.json" -o "$tmp/f.exr" --set pipeline.normalize.format="$format" \
  --set pipeline.normalize.mode=forward-difference --vectors "$tmp/vec" --trace-region 40,30,80,60 >/dev/null 2>&1
lines=$(grep -vc '^//' "$tmp/vec/normalize.in.hex")
export RTL_TB_DIR=$tmp/tb-build
if ((lines > 500)) && "$src/scripts/rtl-vectors.sh" "$tmp/vec" >"$tmp/tb" 2>&1 && grep -q " 0 different" "$tmp/tb"; then
  ok "test vectors through the RTL testbench: $(cat "$tmp/tb")"
else
  fail "test vectors through the RTL testbench:"; sed 's/^/    /' "$tmp/tb" | tail -5
fi
# A narrow format, simulated (the build's RTL is fixed:3.20; the testbench is built for
# the vectors' format): the float32 estimate's conversions and saturating constants
# (1.5 and 1 past a format of no integer bits) at 7 bits.
rm -rf "$tmp/vec-narrow"
"$bin" render "$src/golden/torus/scene.json" -o "$tmp/f.exr" --set pipeline.normalize.format=fixed:0.6 \
  --set pipeline.normalize.mode=rsqrt1 --vectors "$tmp/vec-narrow" --trace-region 30,20,90,60 >/dev/null 2>&1
if "$src/scripts/rtl-vectors.sh" "$tmp/vec-narrow" >"$tmp/tb" 2>&1 && grep -q " 0 different" "$tmp/tb"; then
  ok "fixed:0.6 vectors through the RTL testbench: $(cat "$tmp/tb")"
else
  fail "fixed:0.6 vectors through the RTL testbench:"; sed 's/^/    /' "$tmp/tb" | tail -5
fi
# One output word changed (its first digit), the rest as they were.
awk '!/^\/\// && !done { $0 = (substr($0, 1, 1) == "0" ? "1" : "0") substr($0, 2); done = 1 } { print }' \
  "$tmp/vec/normalize.out.hex" >"$tmp/changed" && mv "$tmp/changed" "$tmp/vec/normalize.out.hex"
if "$src/scripts/rtl-vectors.sh" "$tmp/vec" >"$tmp/tb" 2>&1; then fail "control: a changed vector went unnoticed"
else ok "control: a changed vector is found ($(grep -c 'pixel' "$tmp/tb") reported)"; fi

# 5. Synthesis (scripts/synth.sh makes the table): Yosys reads the RTL and maps it to
# generic cells without latches; the unit keeps its latency's pixels in flip-flops.
if command -v yosys >/dev/null; then
  r=$src/src/shadetlm/rtl/normalize
  yosys -q -l "$tmp/dp.log" -p "read_verilog -sv $r/normalize_datapath.sv $r/fx_isqrt.sv;
    chparam -set IBITS 1 -set FBITS 12 -set MODE 2 normalize_datapath; synth -top normalize_datapath -flatten;
    stat -tech cmos" >/dev/null 2>&1
  yosys -q -l "$tmp/unit.log" -p "read_verilog -sv -lib $r/normalize_datapath.sv; read_verilog -sv $r/normalize_unit.sv;
    chparam -set IBITS 1 -set FBITS 12 -set MODE 2 -set LATENCY 21 -set II 1 -set TAG_W 1 normalize_unit;
    synth -top normalize_unit -flatten; stat" >/dev/null 2>&1
  cells=$(grep -o 'Number of cells: *[0-9]*' "$tmp/dp.log" | tail -1 | grep -o '[0-9]*$')
  flops=$(awk '/\$_(S?DFF)[A-Z_0-9]*_ / { n += $2 } END { print n + 0 }' "$tmp/unit.log")
  # 22 pixels held (⌈(21 + 1) / 1⌉), each 3 words of 14 bits: 924 flip-flops at least.
  if ((${cells:-0} > 100 && flops >= 924)) && ! grep -q '\$_DLATCH\|Latch inferred' "$tmp/dp.log" "$tmp/unit.log"; then
    ok "synthesis: rsqrt0 at fixed:1.12, datapath $cells cells, unit $flops flip-flops, no latches"
  else
    fail "synthesis: datapath ${cells:-no} cells, unit $flops flip-flops"; tail -5 "$tmp/dp.log" | sed 's/^/    /'
  fi
else
  echo "skip synthesis: no yosys (scripts/setup.sh installs it)"
fi

echo "$passes passed, $failures failed"
((failures == 0))
