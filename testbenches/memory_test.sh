#!/usr/bin/env bash
# The DRAM model on whole frames (docs/memory.md): against the default caches and DRAM,
# a smaller cache misses more and costs cycles, less bandwidth and a shorter miss queue
# cost cycles, a cache that holds the whole map misses only once per line, and ideal
# memory is what the golden cycles were measured under (no memory figures, the same
# cycles as a DRAM that never misses cannot give). Usage: memory_test.sh SHADETLM SOURCE_DIR
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$src/golden/bump-plane/scene.json

# run NAME [--set k=v]...: the stats of the frame with the DRAM model, in $tmp/NAME.json
run() {
  local name=$1
  shift
  "$bin" render "$scene" -o "$tmp/f.exr" --stats "$tmp/$name.json" "$@" >/dev/null 2>"$tmp/err" ||
    { echo "FAIL $name: render"; cat "$tmp/err"; exit 1; }
}
dram=(--set pipeline.memory.model=dram)
run ideal
run base "${dram[@]}"
run small "${dram[@]}" --set pipeline.bump_fetch.cache.size=1024
run whole "${dram[@]}" --set pipeline.bump_fetch.cache.size=4194304 --set pipeline.bump_fetch.cache.ways=1
run narrow "${dram[@]}" --set pipeline.memory.bytes_per_cycle=2
run unhidden "${dram[@]}" --set pipeline.bump_fetch.miss_queue=0 --set pipeline.framebuffer.miss_queue=0
run slow "${dram[@]}" --set pipeline.memory.latency=2000
"$bin" render "$src/golden/bump-knot/scene.json" -o "$tmp/f.exr" --stats "$tmp/timeline-stats.json" \
  --timeline "$tmp/timeline.json" "${dram[@]}" --set pipeline.bump_fetch.cache.size=1024 >/dev/null
# A texture-object material on a 1×1 texture (no mip levels), 64-bit accumulators in
# lines of 16 bytes (each pixel's four numbers span two lines): rendered, counted.
cat >"$tmp/tiny.json" <<'JSON'
{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [64,48]},
 "lights": [{"type": "directional", "direction": [0,0,-1]}],
 "textures": {"t": {"type": "checker", "size": [1, 1], "cells": 1}},
 "materials": {"m": {"texture": "t", "path": "texture-object"}},
 "objects": [{"shape": "plane", "size": [3, 3], "material": "m"}]}
JSON
for bits in 32 64; do
  "$bin" render "$tmp/tiny.json" -o "$tmp/f.exr" --stats "$tmp/tiny$bits.json" "${dram[@]}" \
    --set pipeline.texel_project.cache.line=16 --set pipeline.texel_project.accumulator_bits=$bits >/dev/null 2>"$tmp/err" ||
    { echo "FAIL a 1x1 texture-object texture under the DRAM model:"; cat "$tmp/err"; exit 1; }
done

python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
j = {n: json.load(open(f"{d}/{n}.json")) for n in ["ideal", "base", "small", "whole", "narrow", "unhidden", "slow"]}
cycles = {n: v["frame_cycles"] for n, v in j.items()}
bump = {n: v["blocks"]["bump_fetch"].get("memory") for n, v in j.items()}
checks = [
    ("ideal memory reports no caches", j["ideal"]["memory"] == {"model": "ideal"} and bump["ideal"] is None),
    ("the DRAM costs cycles over ideal memory", cycles["base"] > cycles["ideal"]),
    ("a 1 KiB cache misses more than 16 KiB", bump["small"]["misses"] > bump["base"]["misses"]),
    ("and costs cycles", cycles["small"] > cycles["base"]),
    ("a cache holding the map misses once per line it touches", bump["whole"]["misses"] <= bump["base"]["misses"]
     and bump["whole"]["writebacks"] == 0),
    ("2 bytes a cycle cost cycles over 32", cycles["narrow"] > cycles["base"]),
    ("no miss queue costs cycles", cycles["unhidden"] > cycles["base"]),
    ("a 2000-cycle DRAM costs cycles over 200", cycles["slow"] > cycles["base"]),
    ("the ten-times latency stalls the bump fetch longer", bump["slow"]["stall_cycles"] > bump["base"]["stall_cycles"]),
]
# The timeline's DRAM counter: every byte the main pass's clients moved while it ran
# (the lines dirty at the frame's end are written back after it).
timeline = json.load(open(f"{d}/timeline.json"))["traceEvents"]
stats = json.load(open(f"{d}/timeline-stats.json"))
counted = sum(e["args"]["bytes_per_cycle"] * e["args"]["cycles"] for e in timeline if e.get("name") == "DRAM bandwidth")
moved = sum((m["misses"] + m["writebacks"] - m["writebacks_at_end"]) * m["cache"]["line"]
            for b in stats["blocks"].values() if (m := b.get("memory")))
checks.append((f"the timeline's DRAM counter holds the bytes the caches moved ({counted:.0f} of {moved})",
               moved > 0 and abs(counted - moved) < 1e-6 * moved))
# 64-bit accumulators: 32 bytes a pixel, two 16-byte lines; 32-bit ones: 16 bytes, one.
acc = {b: json.load(open(f"{d}/tiny{b}.json"))["blocks"]["texel_project"]["details"]["accumulator_dram_bytes"]
       for b in (32, 64)}
checks.append((f"64-bit accumulators move twice the bytes of 32-bit ones ({acc[64]} against {acc[32]})",
               acc[32] > 0 and acc[64] == 2 * acc[32]))
failed = 0
for name, ok in checks:
    print(("ok " if ok else "FAIL ") + name)
    failed += not ok
print("cycles:", cycles)
sys.exit(1 if failed else 0)
PY
