#!/usr/bin/env bash
# The command line as a user meets it: exit codes (0 ok, 1 frames differ, 2 bad input),
# messages that name the file and the field, and no output file when
# the input is bad. Usage: cli_test.sh SHADETLM SOURCE_DIR
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0

check() {  # check NAME EXPECTED_EXIT COMMAND...; stderr+stdout go to $tmp/out
  local name=$1 want=$2
  shift 2
  "$@" >"$tmp/out" 2>&1
  local got=$?
  if [[ $got -ne $want ]]; then
    echo "FAIL $name: exit $got, expected $want"; sed 's/^/    /' "$tmp/out"; ((failures++))
  else
    ((passes++))
  fi
}
expect_output() {  # expect_output NAME TEXT: the last command printed TEXT
  if grep -qF -- "$2" "$tmp/out"; then ((passes++)); else
    echo "FAIL $1: output lacks '$2'"; sed 's/^/    /' "$tmp/out"; ((failures++)); fi
}
expect_no_file() {
  if [[ -e $2 ]]; then echo "FAIL $1: $2 was written"; ((failures++)); else ((passes++)); fi
}

check version 0 "$bin" --version
# --help names what an option takes, not CLI11's type words (TEXT:NOT EMPTY:FILE.exr).
for command in "" render reference compare bench precompute parallax-bench timing-check "precompute normalmap" \
    "precompute boxgapmap" "precompute donnellymap" "precompute refinedmap" "precompute conemap" \
    "precompute relaxedconemap"; do
  check "help $command" 0 "$bin" $command --help
  if grep -qE 'NOT EMPTY|TEXT:|FLOAT:|FINITE' "$tmp/out"; then
    echo "FAIL help $command: CLI11's type words:"; grep -E 'NOT EMPTY|TEXT:|FLOAT:|FINITE' "$tmp/out" | sed 's/^/    /'; ((failures++))
  else ((passes++)); fi
done
check help-output 0 "$bin" render --help
expect_output help-output "-o,--output FILE.exr=out/frame.exr"
expect_output help-output "--heat-max FLOAT in [1, 1e+06]=32"
check demo 0 "$bin" reference -o "$tmp/demo.exr" --preview "$tmp/demo.png"
[[ -s $tmp/demo.exr && -s $tmp/demo.png ]] && ((passes++)) || { echo "FAIL demo: no frame"; ((failures++)); }
check same 0 "$bin" compare "$tmp/demo.exr" "$tmp/demo.exr"
expect_output same PASS

# A different frame of the same scene: brighter light.
check brighter 0 "$bin" reference -o "$tmp/bright.exr" --set lights.0.intensity=2
check differs 1 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --diff "$tmp/diff.exr"
expect_output differs FAIL
[[ -s $tmp/diff.exr ]] && ((passes++)) || { echo "FAIL differs: no diff frame"; ((failures++)); }
check tolerated 0 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --layer Z --layer N
check tolerant 0 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --failpercent 100
check json 1 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --json
expect_output json '"psnr"'

# Bad input: exit 2, the file and field named, nothing written.
cat >"$tmp/bad.json" <<'JSON'
{ "camera": { "position": [0, 0, 5], "target": [0, 0, 0], "resolution": [8, 8], "fovy": 30 },
  "objects": [ { "shape": "sphere" } ] }
JSON
check unknown-key 2 "$bin" reference "$tmp/bad.json" -o "$tmp/bad.exr"
expect_output unknown-key "bad.json: camera.fovy: unknown key"
expect_no_file unknown-key "$tmp/bad.exr"
check bad-setting 2 "$bin" reference -o "$tmp/bad2.exr" --set pipeline.normalize.mode=bogus
expect_output bad-setting "pipeline.normalize.mode"
expect_no_file bad-setting "$tmp/bad2.exr"
check missing-scene 2 "$bin" reference "$tmp/nowhere.json" -o "$tmp/bad3.exr"
expect_output missing-scene "nowhere.json"
expect_no_file missing-scene "$tmp/bad3.exr"
check missing-frame 2 "$bin" compare "$tmp/nowhere.exr" "$tmp/demo.exr"
expect_output missing-frame "nowhere.exr"
check nan-threshold 2 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --fail nan
check negative-threshold 2 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --hardfail -1
# An override before the scene leaves the scene a scene.
check set-then-scene 0 "$bin" reference --set camera.resolution=[32,24] "$src/scenes/knot.json" -o "$tmp/k.exr"
check bad-option 2 "$bin" reference --frobnicate
check typo-command 2 "$bin" rendr
expect_output typo-command "did you mean 'render'"
check typo-subcommand 2 "$bin" precompute normalmp
expect_output typo-subcommand "did you mean 'normalmap'"
check typo-option 2 "$bin" render --vdc "$tmp/t.vcd"
expect_output typo-option "did you mean --vcd"
# The silicon of a render's arithmetic (docs/silicon.md): on the console, and per operation.
check silicon-line 0 "$bin" render "$src/golden/sphere/scene.json" -o "$tmp/si.exr"
expect_output silicon-line "silicon (OSU 0.18 um"
expect_output silicon-line "area by block, mm2: lighting"
check silicon-unpriced 0 "$bin" render "$src/golden/sphere/scene.json" -o "$tmp/si.exr" --allow-overflow \
  --set pipeline.normalize.format=fixed:12.40
expect_output silicon-unpriced "silicon of normalize not priced: fixed:12.40 (pipeline.normalize.format) is a 53-bit word"
check cost-json 0 "$bin" cost float32 fixed:1.12 --json
python3 -c 'import json, sys; f = json.load(open(sys.argv[1]))["formats"]; assert f["float32"]["div"]["area_um2"] > f["fixed:1.12"]["div"]["area_um2"] > 0, f' \
  "$tmp/out" && ((passes++)) || { echo "FAIL cost-json: see above"; ((failures++)); }
check cost-wide 2 "$bin" cost fixed:12.40
expect_output cost-wide "shadetlm: cost: FORMAT: fixed:12.40 is a 53-bit word"
check cost-unknown 2 "$bin" cost flaot32
expect_output cost-unknown 'unknown number format "flaot32"'
# Frames that cannot be compared are trouble (2), said on stderr; a difference is 1.
check small 0 "$bin" reference -o "$tmp/small.exr" --set camera.resolution=[32,24]
check other-resolution 2 "$bin" compare "$tmp/small.exr" "$tmp/demo.exr"
expect_output other-resolution "resolutions differ"
[[ -z $("$bin" compare "$tmp/small.exr" "$tmp/demo.exr" 2>/dev/null) ]] && ((passes++)) ||
  { echo "FAIL other-resolution: a message on stdout"; ((failures++)); }
check no-command 2 "$bin"

# The SystemC pipeline: frame, preview and statistics, the same frame as the kernel
# loop, and bad input stopped before anything is written.
check render 0 "$bin" render -o "$tmp/p.exr" --preview "$tmp/p.png" --stats "$tmp/p.json" --compare-reference
expect_output render "(0 covered in one only)"
[[ -s $tmp/p.exr && -s $tmp/p.png && -s $tmp/p.json ]] && ((passes++)) || { echo "FAIL render: missing output"; ((failures++)); }
grep -q '"bottleneck"' "$tmp/p.json" && grep -q '"utilization"' "$tmp/p.json" && grep -q '"rmse"' "$tmp/p.json" \
  && ((passes++)) || { echo "FAIL render: statistics lack fields"; ((failures++)); }
check render-loop 0 "$bin" render --engine loop -o "$tmp/l.exr"
check loop-equals-systemc 0 "$bin" compare "$tmp/l.exr" "$tmp/p.exr" --fail 0
check render-bad-mode 2 "$bin" render -o "$tmp/bad4.exr" --stats "$tmp/bad4.json" --set pipeline.normalize.mode=fast
expect_no_file render-bad-mode "$tmp/bad4.exr"
expect_no_file render-bad-mode "$tmp/bad4.json"
nine_lights=$(printf '{"type":"directional","direction":[0,-1,0]},%.0s' 1 2 3 4 5 6 7 8)
check render-too-many-lights 2 "$bin" render -o "$tmp/bad5.exr" --set "lights=[${nine_lights}{\"type\":\"point\",\"position\":[0,1,0]}]"
expect_output render-too-many-lights "at most 8 lights"
expect_no_file render-too-many-lights "$tmp/bad5.exr"
mkdir -p "$tmp/taken.json"  # a folder where the statistics should go: nothing is written
check render-stats-fail 2 "$bin" render -o "$tmp/half.exr" --stats "$tmp/taken.json"
expect_no_file render-stats-fail "$tmp/half.exr"
check bench 0 "$bin" bench --set camera.resolution=[64,36]
expect_output bench "ratio systemc / loop"

# Bump mapping: a precomputed normal map, read back by a scene, gives the frame that the
# same map computed on load gives (the EXR keeps the float texels and the mip chain).
check height-png 0 "$bin" reference -o "$tmp/h64.exr" --preview "$tmp/h64.png" --set camera.resolution=[64,64]
check precompute 0 "$bin" precompute normalmap "$tmp/h64.png" -o "$tmp/nm/bumps.exr" --scale 0.02 --k 2
expect_output precompute "square form"
sed -e 's#"height_map": "dimples", "height_scale": 0.05, "path": "bump-classic"#"normal_map": "nm", "path": "bump-square"#' \
    -e "s#\"textures\": {#\"textures\": {\"nm\": {\"type\": \"image\", \"file\": \"$tmp/nm/bumps.exr\"},#" \
    "$src/golden/bump-sphere/scene.json" >"$tmp/nm.json"
check render-normal-map 0 "$bin" render "$tmp/nm.json" -o "$tmp/nm.exr" --stats "$tmp/nm-stats.json" --compare-reference
grep -q '"bump_fetch"' "$tmp/nm-stats.json" && ((passes++)) || { echo "FAIL render-normal-map: no bump_fetch block"; ((failures++)); }
# A 16-bit grey PNG height map (a 32×32 ramp; stb reads 16-bit PNGs).
python3 - "$tmp/h16.png" <<'PY'
import struct, sys, zlib
w = h = 32
rows = b"".join(b"\0" + b"".join(struct.pack(">H", (x * 65535) // (w - 1)) for x in range(w)) for _ in range(h))
chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0)) + \
      chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(png)
PY
sed -e "s#\"textures\": {#\"textures\": {\"h16\": {\"type\": \"image\", \"file\": \"$tmp/h16.png\"},#" \
    -e 's#"height_map": "dimples"#"height_map": "h16"#' "$src/golden/bump-sphere/scene.json" >"$tmp/h16.json"
check height-16-bit 0 "$bin" render "$tmp/h16.json" -o "$tmp/h16.exr" --compare-reference
for path in bump-classic bump-tangent bump-square bump-object; do
  check "bump-$path" 0 "$bin" render "$src/golden/bump-sphere/scene.json" -o "$tmp/$path.exr" --set materials.red.path=$path \
    --set camera.resolution=[48,36]
done

# Parallax maps: written with their parameters in the header; bad input exits 2, no file.
for kind in boxgapmap distancemap donnellymap refinedmap conemap relaxedconemap; do  # distancemap: boxgapmap's old name
  check "precompute-$kind" 0 "$bin" precompute $kind "$tmp/h64.png" -o "$tmp/px/$kind.exr" --slices 8
  expect_output "precompute-$kind" "8 slices"
  check "precompute-$kind-missing" 2 "$bin" precompute $kind "$tmp/none.png" -o "$tmp/px/none-$kind.exr"
  expect_no_file "precompute-$kind-missing" "$tmp/px/none-$kind.exr"
done
check parallax-bench 0 "$bin" parallax-bench "$src/scenes/parallax/steps.json" --elevations 30 --rays 16 --json "$tmp/px/b.json"
expect_output parallax-bench "refined: iterations"
check parallax-bench-no-material 2 "$bin" parallax-bench "$src/golden/sphere/scene.json" --json "$tmp/px/none.json"
expect_output parallax-bench-no-material "no parallax material"
expect_no_file parallax-bench-no-material "$tmp/px/none.json"
check parallax-heat-map 0 "$bin" render "$src/scenes/parallax/steps.json" -o "$tmp/px/steps.exr" --heat-map "$tmp/px/heat.png" \
  --set camera.resolution=[48,32]
[[ -s "$tmp/px/heat.png" ]] && ((passes++)) || { echo "FAIL parallax-heat-map: no heat map"; ((failures++)); }
check heat-map-without-parallax 2 "$bin" render -o "$tmp/px/demo.exr" --heat-map "$tmp/px/demo-heat.png" \
  --set camera.resolution=[48,32]
expect_no_file heat-map-without-parallax "$tmp/px/demo.exr"
check parallax-no-height-map 2 "$bin" render "$src/scenes/parallax/steps.json" -o "$tmp/px/bad.exr" \
  --set materials.carved.height_map=checker --set materials.carved.parallax.slices=0
expect_output parallax-no-height-map "slices"

# Parallax maps read, not rebuilt: one precomputed and named by the scene (map_file), or
# kept in a map cache; the frame is the one the maps built on load give. A map for
# other settings or another height map is refused naming the field (exit 2, no frame).
px=("$src/scenes/parallax/steps.json" --set "textures.relief={\"type\":\"image\",\"file\":\"$tmp/h64.png\"}"
    --set camera.resolution=[48,32])
check px-built 0 "$bin" render "${px[@]}" -o "$tmp/px/built.exr"
check px-precompute 0 "$bin" precompute refinedmap "$tmp/h64.png" -o "$tmp/px/refined.exr"
check px-map-file 0 "$bin" render "${px[@]}" -o "$tmp/px/read.exr" --set "materials.carved.parallax.map_file=$tmp/px/refined.exr"
check px-map-file-same 0 "$bin" compare "$tmp/px/read.exr" "$tmp/px/built.exr" --fail 0
check px-map-file-margin 2 "$bin" render "${px[@]}" -o "$tmp/px/bad.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/refined.exr" --set materials.carved.parallax.margin=0.25
expect_output px-map-file-margin "shadetlm:margin"
expect_output px-map-file-margin "refined.exr"
check px-map-file-other-height 2 "$bin" render "$src/scenes/parallax/steps.json" -o "$tmp/px/bad.exr" \
  --set camera.resolution=[48,32] --set textures.relief.size=[64,64] --set "materials.carved.parallax.map_file=$tmp/px/refined.exr"
expect_output px-map-file-other-height "shadetlm:height_checksum"
check px-map-file-donnelly 2 "$bin" render "${px[@]}" -o "$tmp/px/bad.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/refined.exr" --set materials.carved.parallax.map=donnelly
expect_output px-map-file-donnelly "shadetlm:map"
check px-donnelly-built 0 "$bin" render "${px[@]}" -o "$tmp/px/donnelly-built.exr" \
  --set materials.carved.parallax.map=donnelly --set materials.carved.parallax.slices=8 --set materials.carved.parallax.steps=24
check px-donnelly-map-file 0 "$bin" render "${px[@]}" -o "$tmp/px/donnelly.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/donnellymap.exr" --set materials.carved.parallax.map=donnelly \
  --set materials.carved.parallax.slices=8 --set materials.carved.parallax.steps=24
check px-donnelly-map-file-same 0 "$bin" compare "$tmp/px/donnelly.exr" "$tmp/px/donnelly-built.exr" --fail 0
rc=(--set materials.carved.parallax.method=cone --set materials.carved.parallax.cones=relaxed
    --set materials.carved.parallax.slices=8)
check px-relaxed-built 0 "$bin" render "${px[@]}" "${rc[@]}" -o "$tmp/px/relaxed-built.exr"
check px-relaxed-map-file 0 "$bin" render "${px[@]}" "${rc[@]}" -o "$tmp/px/relaxed.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/relaxedconemap.exr"
check px-relaxed-map-file-same 0 "$bin" compare "$tmp/px/relaxed.exr" "$tmp/px/relaxed-built.exr" --fail 0
check px-relaxed-map-file-elevation 2 "$bin" render "${px[@]}" "${rc[@]}" -o "$tmp/px/bad.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/relaxedconemap.exr" --set materials.carved.parallax.min_elevation_deg=20
expect_output px-relaxed-map-file-elevation "shadetlm:min_elevation_deg"
check px-relaxed-map-file-classic 2 "$bin" render "${px[@]}" "${rc[@]}" -o "$tmp/px/bad.exr" \
  --set "materials.carved.parallax.map_file=$tmp/px/relaxedconemap.exr" --set materials.carved.parallax.cones=classic
expect_output px-relaxed-map-file-classic "shadetlm:map"
check px-steps-not-donnelly 2 "$bin" render "${px[@]}" -o "$tmp/px/bad.exr" --set materials.carved.parallax.steps=8
expect_output px-steps-not-donnelly "steps"
expect_no_file px-map-file-refused "$tmp/px/bad.exr"
check px-map-file-missing 2 "$bin" render "${px[@]}" -o "$tmp/px/bad.exr" --set "materials.carved.parallax.map_file=$tmp/none.exr"
expect_output px-map-file-missing "none.exr"
check px-map-file-steep 2 "$bin" render "${px[@]}" -o "$tmp/px/bad.exr" --set materials.carved.parallax.method=steep \
  --set "materials.carved.parallax.map_file=$tmp/px/refined.exr"
expect_output px-map-file-steep "map_file"
check px-cache-build 0 "$bin" render "${px[@]}" -o "$tmp/px/c1.exr" --map-cache "$tmp/px/cache"
cached=$(ls "$tmp/px/cache")
[[ $cached == refined-*.exr ]] && ((passes++)) || { echo "FAIL px-cache-build: the cache holds '$cached'"; ((failures++)); }
touch -d @946684800 "$tmp/px/cache/$cached"
SHADETLM_MAP_CACHE=$tmp/px/cache check px-cache-read 0 "$bin" render "${px[@]}" -o "$tmp/px/c2.exr"
[[ $(ls "$tmp/px/cache") == "$cached" && $(stat -c %Y "$tmp/px/cache/$cached") == 946684800 ]] && ((passes++)) ||
  { echo "FAIL px-cache-read: the cached map was built again"; ((failures++)); }
check px-cache-same 0 "$bin" compare "$tmp/px/c2.exr" "$tmp/px/built.exr" --fail 0
check px-cache-cone 0 "$bin" render "${px[@]}" -o "$tmp/px/c3.exr" --map-cache "$tmp/px/cache" \
  --set materials.carved.parallax.method=cone
[[ $(ls "$tmp/px/cache" | wc -l) == 2 ]] && ((passes++)) || { echo "FAIL px-cache-cone: no second map"; ((failures++)); }
check px-cache-relaxed 0 "$bin" render "${px[@]}" -o "$tmp/px/c4.exr" --map-cache "$tmp/px/cache" \
  --set materials.carved.parallax.method=cone --set materials.carved.parallax.cones=relaxed
[[ $(ls "$tmp/px/cache" | wc -l) == 3 ]] && ((passes++)) || { echo "FAIL px-cache-relaxed: no third map"; ((failures++)); }

# A mesh through assimp, from the scenes folder.
check mesh 0 "$bin" reference "$src/scenes/knot.json" -o "$tmp/knot.exr" --set camera.resolution=[96,64]

# The timeline's counters do not depend on --stats (its bins were 10 000 cycles with it,
# 256 without); every FIFO track is full at its depth; a region's trace names the frame's
# cycles too; the waveforms carry the time in cycles, their tree open.
sphere=$src/golden/sphere/scene.json
check timeline-alone 0 "$bin" render "$sphere" -o "$tmp/t1.exr" --timeline "$tmp/t1.json"
check timeline-stats 0 "$bin" render "$sphere" -o "$tmp/t2.exr" --timeline "$tmp/t2.json" --stats "$tmp/t2-stats.json"
counters() { grep '"ph": "C"' "$1"; }
if [[ -n $(counters "$tmp/t1.json") && "$(counters "$tmp/t1.json")" == "$(counters "$tmp/t2.json")" ]]; then ((passes++))
else echo "FAIL timeline-bins: the counters differ with --stats"; ((failures++)); fi
python3 - "$tmp/t2.json" "$tmp/t2-stats.json" <<'PY' && ((passes++)) || { echo "FAIL timeline-scale: see above"; ((failures++)); }
import json, sys
t, s = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
o = t["otherData"]
fifos = {e["name"] for e in t["traceEvents"] if e["ph"] == "C" and e["name"].endswith(" FIFO")}
assert fifos and set(o["counter_full"]) == fifos, (fifos, o["counter_full"])
depths = {name + " FIFO": b["fifo_depth"] for name, b in s["blocks"].items() if name + " FIFO" in fifos}
assert o["counter_full"] == depths, (o["counter_full"], depths)
assert o["frame_cycles"] == s["frame_cycles"] and o["region"] is False, o
assert s["utilization_over_time"]["bin_cycles"] == 10000
PY
# ... and the stats' utilization over time (blocks and DRAM) do not change with --timeline
# (its 250-cycle bins summed into the stats' 10 000).
check stats-dram 0 "$bin" render "$sphere" -o "$tmp/t4.exr" --stats "$tmp/t4.json" --set pipeline.memory.model=dram
check stats-dram-timeline 0 "$bin" render "$sphere" -o "$tmp/t5.exr" --stats "$tmp/t5.json" --timeline "$tmp/t5.html" \
  --set pipeline.memory.model=dram
python3 - "$tmp/t4.json" "$tmp/t5.json" <<'PY' && ((passes++)) || { echo "FAIL stats-over-time: see above"; ((failures++)); }
import json, sys
a, b = (json.load(open(f))["utilization_over_time"] for f in sys.argv[1:])
assert a["bin_cycles"] == b["bin_cycles"] == 10000
assert a["dram"] and len(a["blocks"]) > 3 and sum(map(len, a["blocks"].values())) > 10, a
assert a == b, "the stats' utilization over time changed with --timeline"
PY
check region-trace 0 "$bin" render "$sphere" -o "$tmp/t3.exr" --timeline "$tmp/t3.json" --vcd "$tmp/w.vcd" \
  --trace-region 10,10,40,40
python3 - "$tmp/t3.json" "$tmp/t1.json" "$tmp/w.vcd" "$tmp/w.gtkw" <<'PY' && ((passes++)) || { echo "FAIL region-trace: see above"; ((failures++)); }
import json, re, sys
t, whole = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
o = t["otherData"]
last = max(e["ts"] + e["dur"] for e in t["traceEvents"] if e["ph"] == "X")
assert o["region"] is True and o["frame_cycles"] == whole["otherData"]["frame_cycles"] > last, (o, last)
vcd, gtkw = open(sys.argv[3]).read(), open(sys.argv[4]).read()
ident = re.search(r"\$var wire 64 (\S+) cycle \[63:0\] \$end", vcd).group(1)
# The time unit is a cycle, written as 1 ns, the clock named in a comment; at every time
# step the cycle signal is the time (but the last, the dump's end, which changes nothing).
assert "$timescale 1 ns $end" in vcd, vcd[:200]
assert "one cycle of the model's clock (%g ps)" % (1e6 / o["clock_mhz"]) in vcd, vcd[:300]
steps = re.findall(r"^#(\d+)\n((?:[^#].*\n)*)", vcd, re.M)
checked = 0
for time, changes in steps[:-1]:
    m = re.search(r"^b([01]+) " + re.escape(ident) + "$", changes, re.M)
    assert m, time
    assert int(m.group(1), 2) == int(time), (time, m.group(1))
    checked += 1
assert checked > 10, checked
assert "[treeopen] shadetlm." in gtkw and "shadetlm.cycle[63:0]" in gtkw
# The view opens on the first traced pixels: its start is a time step of the VCD (in cycles).
start = re.search(r"^\[timestart\] (\d+)$", gtkw, re.M).group(1)
assert int(start) > 0 and ("\n#%s\n" % start) in vcd, start
PY

echo "$passes passed, $failures failed"
[[ $failures -eq 0 ]]
