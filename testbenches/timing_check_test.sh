#!/usr/bin/env bash
# The fast timing model against the clocked timing reference (docs/pipeline.md, "The
# timing check"): every golden scene, and stress configurations built to mix rates —
# many lights on few pixels, bursts of parallax iterations, FIFOs of depth 1 and 2, a
# slow block at the end — must give the same start and hand-over cycle for every pixel
# at every block, the same frame cycles and the same busy, starved, blocked and FIFO
# figures. The stress configurations must also stall (blocked cycles > 0 somewhere), or
# they would not test back-pressure; those with memory (docs/memory.md: small caches,
# little bandwidth, short miss queues) must also wait for it (memory stall cycles > 0).
# Usage: timing_check_test.sh SHADETLM SOURCE_DIR
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0
failures=0

# check NAME STALLS SCENE [--set k=v]...: STALLS=1 requires blocked cycles somewhere,
# STALLS=2 memory stall cycles too, STALLS=3 also hidden pixels whose depth read missed.
check() {
  local name=$1 stalls=$2 scene=$3
  shift 3
  if ! "$bin" render "$scene" "$@" -o "$tmp/f.exr" --timing-log "$tmp/t.log" >"$tmp/out" 2>&1; then
    echo "FAIL $name: render"; sed 's/^/    /' "$tmp/out" | tail -3; ((failures++)); return
  fi
  if ! "$bin" timing-check "$tmp/t.log" --show 5 >"$tmp/check" 2>&1; then
    echo "FAIL $name:"; sed 's/^/    /' "$tmp/check"; ((failures++)); return
  fi
  local blocked
  blocked=$(awk '$1 == "stats" { b += $5 } END { print b + 0 }' "$tmp/t.log")
  if ((stalls)) && ((blocked == 0)); then echo "FAIL $name: no block ever stalled"; ((failures++)); return; fi
  local waited
  waited=$(awk '$1 == "stats" { m += $8 } END { print m + 0 }' "$tmp/t.log")
  if ((stalls >= 2)) && ((waited == 0)); then echo "FAIL $name: no pixel waited for memory"; ((failures++)); return; fi
  if ((stalls == 3)) && ! grep -q '^h ' "$tmp/t.log"; then echo "FAIL $name: no hidden depth miss"; ((failures++)); return; fi
  echo "ok $name: $(head -1 "$tmp/check" | cut -d: -f2-), blocked cycles $blocked, memory stall cycles $waited"
  ((passes++))
}

for scene in "$src"/golden/*/scene.json; do
  check "golden $(basename "$(dirname "$scene")")" 0 "$scene"
done

# Eight lights on a small sphere: lighting takes 8 cycles a pixel, everything before it stalls.
cat >"$tmp/lights.json" <<'JSON'
{"camera": {"position": [0, 0, 4], "target": [0, 0, 0], "resolution": [48, 36]},
 "lights": [{"type": "point", "position": [2, 2, 2]}, {"type": "point", "position": [-2, 2, 2]},
            {"type": "point", "position": [2, -2, 2]}, {"type": "point", "position": [-2, -2, 2]},
            {"type": "point", "position": [0, 3, 1]}, {"type": "point", "position": [0, -3, 1]},
            {"type": "point", "position": [3, 0, 1]}, {"type": "point", "position": [-3, 0, 1]}],
 "objects": [{"shape": "sphere", "radius": 0.8, "segments": 24, "rings": 12}]}
JSON
check "eight lights, FIFOs of 1" 1 "$tmp/lights.json" --set pipeline.normalize.mode=rsqrt1 \
  --set pipeline.lighting.fifo_depth=1 --set pipeline.normalize.fifo_depth=1 --set pipeline.normal_interp.fifo_depth=1
check "eight lights, FIFOs of 2" 1 "$tmp/lights.json" --set pipeline.normalize.mode=rsqrt0 \
  --set pipeline.lighting.fifo_depth=2 --set pipeline.framebuffer.fifo_depth=2
# Bursts of parallax iterations behind a slow framebuffer.
check "parallax bursts, slow end" 1 "$src/golden/parallax-steps/scene.json" --set pipeline.parallax.fifo_depth=1 \
  --set pipeline.framebuffer.ii=4 --set pipeline.framebuffer.latency=9 --set pipeline.lighting.fifo_depth=2
# A slow block at the end of a bump path, every block elaborated (bypasses in the stream).
check "bump, all blocks, slow end" 1 "$src/golden/bump-knot/scene.json" --set pipeline.elaborate=all \
  --set pipeline.framebuffer.ii=5 --set pipeline.framebuffer.fifo_depth=1 --set pipeline.bump_fetch.fifo_depth=2
# A fast setup into a raster FIFO of one triangle, the forward-difference seed per packet.
check "setup against the raster's FIFO" 1 "$src/golden/demo/scene.json" --set pipeline.setup.ii=1 \
  --set pipeline.setup.latency=1 --set pipeline.raster.fifo_depth=1 --set pipeline.normalize.mode=forward-difference
# Long packets, timed in chunks of the shallowest FIFO (src/shadetlm/timing/main_pass.hpp): a
# steady stream, and one that back-pressure shapes.
check "sphere at 320x240, long packets" 0 "$src/golden/sphere/scene.json" --set 'camera.resolution=[320,240]'
check "long packets behind a slow lighting" 1 "$src/golden/point-light/scene.json" --set 'camera.resolution=[320,240]' \
  --set pipeline.lighting.ii=4 --set pipeline.lighting.fifo_depth=3 --set pipeline.normalize.mode=forward-difference
# Textures: taps per pixel vary with the footprint.
check "texture taps, FIFOs of 1" 1 "$src/golden/texture-screen/scene.json" --set pipeline.texture_fetch.filter=anisotropic \
  --set pipeline.texture_fetch.fifo_depth=1 --set pipeline.lighting.ii=3 --set pipeline.normalize.mode=rsqrt2

# Memory (docs/memory.md): caches, one shared DRAM, oldest pixel first.
dram=(--set pipeline.memory.model=dram)
check "bump, small caches, little bandwidth" 2 "$src/golden/bump-knot/scene.json" "${dram[@]}" \
  --set pipeline.bump_fetch.cache.size=1024 --set pipeline.memory.bytes_per_cycle=4 --set pipeline.memory.latency=50 \
  --set pipeline.bump_fetch.miss_queue=2 --set pipeline.framebuffer.cache.size=512 --set pipeline.framebuffer.fifo_depth=1
check "bump, no miss queue, linear" 2 "$src/golden/bump-sphere/scene.json" "${dram[@]}" \
  --set pipeline.bump_fetch.miss_queue=0 --set pipeline.bump_fetch.cache.layout=linear \
  --set pipeline.bump_fetch.cache.ways=1 --set pipeline.memory.bytes_per_cycle=3
check "EWA through a direct-mapped cache, morton" 2 "$src/golden/texture-screen/scene.json" "${dram[@]}" \
  --set pipeline.texture_fetch.filter=ewa --set pipeline.texture_fetch.cache.size=2048 \
  --set pipeline.texture_fetch.cache.ways=1 --set pipeline.texture_fetch.cache.layout=morton \
  --set pipeline.texture_fetch.miss_queue=4 --set pipeline.memory.bytes_per_cycle=2 --set pipeline.lighting.fifo_depth=1
check "framebuffer writes back, lines of 16 bytes" 2 "$src/golden/demo/scene.json" "${dram[@]}" \
  --set pipeline.framebuffer.cache.size=256 --set pipeline.framebuffer.cache.line=16 \
  --set pipeline.framebuffer.cache.layout=linear --set pipeline.framebuffer.miss_queue=1 --set pipeline.memory.latency=9
check "two texture clients share the DRAM" 2 "$src/golden/parallax-steps/scene.json" "${dram[@]}" \
  --set pipeline.texture_fetch.cache.size=512 --set pipeline.framebuffer.cache.size=512 --set pipeline.memory.bytes_per_cycle=1
# The parallax tracer's map reads: the refined distance map, relief and cone stepping.
check "parallax maps through a 1 KiB cache" 2 "$src/scenes/bench-parallax-1080p.json" "${dram[@]}" \
  --set 'camera.resolution=[240,135]' --set pipeline.parallax.cache.size=1024 --set pipeline.parallax.miss_queue=8 \
  --set pipeline.memory.bytes_per_cycle=8

# The raster's depth reads: hidden pixels' misses too, the walk waiting for each (no
# miss queue) or for its one miss entry.
check "depth misses stop the walk" 3 "$src/golden/knot/scene.json" "${dram[@]}" --set pipeline.raster.miss_queue=0 \
  --set pipeline.raster.cache.size=512 --set pipeline.memory.latency=30
check "one depth miss in flight, lines of 16 bytes" 3 "$src/golden/bump-knot/scene.json" "${dram[@]}" \
  --set pipeline.raster.miss_queue=1 --set pipeline.raster.cache.size=256 --set pipeline.raster.cache.line=16 \
  --set pipeline.raster.cache.layout=linear --set pipeline.memory.bytes_per_cycle=2

# The waveforms keep the same order: no pixel reaches a block before the block before
# it handed it on plus a cycle and the block's latency (scripts/vcd-causality.py) — and
# the checker itself catches a pixel that does.
# A slow framebuffer makes lighting stall: its ready must show it.
if "$bin" render "$src/golden/demo/scene.json" -o "$tmp/f.exr" --vcd "$tmp/t.vcd" --trace-region 30,20,90,50 \
     --set pipeline.framebuffer.ii=4 --stats "$tmp/s.json" >/dev/null &&
   python3 "$src/scripts/vcd-causality.py" "$tmp/t.vcd" "$tmp/s.json" >"$tmp/c" && ! grep -q "shown for 0 cycles" "$tmp/c"; then
  echo "ok waveform causality and stalls: $(tail -1 "$tmp/c")"; ((passes++))
else
  echo "FAIL waveform causality or stalls:"; sed 's/^/    /' "$tmp/c"; ((failures++))
fi
cat >"$tmp/bad.vcd" <<'VCD'
$timescale 1 ns $end
$scope module SystemC $end
$scope module a $end
$var wire 1 v valid $end
$var wire 32 x x [31:0] $end
$var wire 32 y y [31:0] $end
$var wire 32 t triangle [31:0] $end
$upscope $end
$scope module b $end
$var wire 1 w valid $end
$var wire 32 X x [31:0] $end
$var wire 32 Y y [31:0] $end
$var wire 32 T triangle [31:0] $end
$upscope $end
$upscope $end
$enddefinitions $end
#1
1w
b101 X
b11 Y
b0 T
#2
0w
1v
b101 x
b11 y
b0 t
VCD
echo '{"clock_mhz": 500, "elaborated": ["a", "b"], "blocks": {"a": {"latency": 1}, "b": {"latency": 1}}}' >"$tmp/bad.json"
if python3 "$src/scripts/vcd-causality.py" "$tmp/bad.vcd" "$tmp/bad.json" >"$tmp/c"; then
  echo "FAIL the causality checker passed a pixel that overtook"; ((failures++))
else
  echo "ok the causality checker catches an overtake: $(tail -1 "$tmp/c")"; ((passes++))
fi

# A timing log that is cut short, out of order or nonsense is refused: exit 2, the file
# and line named, no crash.
"$bin" render "$src/golden/sphere/scene.json" -o "$tmp/f.exr" --timing-log "$tmp/good.log" >/dev/null
refuse() {  # refuse NAME TEXT: the log in $tmp/bad.log
  "$bin" timing-check "$tmp/bad.log" >"$tmp/out" 2>&1
  local rc=$?
  if [[ $rc -eq 2 ]] && grep -qF -- "$2" "$tmp/out" && grep -qF "bad.log" "$tmp/out"; then
    ((passes++))
  else
    echo "FAIL bad log $1: exit $rc"; sed 's/^/    /' "$tmp/out" | head -3; ((failures++))
  fi
}
head -n 200 "$tmp/good.log" >"$tmp/bad.log";                           refuse cut-short "end"
{ head -n 13 "$tmp/good.log"; echo "block late 1 1 1"; } >"$tmp/bad.log"; refuse block-late "line 14"
sed '11s/^p \([0-9]*\) /p \1 x /' "$tmp/good.log" >"$tmp/bad.log";        refuse not-a-number "line 11"
sed '4s/ 2 1 8 0 0$/ 2 0 8 0 0/' "$tmp/good.log" >"$tmp/bad.log";        refuse zero-ii "line 4"
{ head -n 4 "$tmp/good.log"; echo "memory 200 0"; sed -n '5,$p' "$tmp/good.log"; } >"$tmp/bad.log"
                                                                      refuse zero-bandwidth "line 5"
{ head -n 4 "$tmp/good.log"; echo "memory 200 32"; sed -n '5,$p' "$tmp/good.log"; } >"$tmp/bad.log"
                                                                      refuse lines-missing "expected: p"
{ head -n 13 "$tmp/good.log"; echo "h 0 1"; sed -n '14,$p' "$tmp/good.log"; } >"$tmp/bad.log"
                                                                      refuse depth-miss-without-memory "expected: h"
printf 'block setup 16 8 0\nblock raster 4 1 99999999999\n' >"$tmp/bad.log"; refuse huge-depth "line 2"
echo "hello" >"$tmp/bad.log";                                         refuse unknown "unknown record"
printf 'block setup 16 8 0\nblock raster 4 1000000 4\nblock a 1 1 8\nt 0 0 16\nr 17\np 1 1 100000000 1 0 0 0 0 0 0\ne 0\nend 5\n' \
  >"$tmp/bad.log";                                                    refuse too-long "10^11 cycles"

sed '1d' "$tmp/good.log" >"$tmp/bad.log";                               refuse no-scene "no scene record"
{ head -n 2 "$tmp/good.log"; echo "set a=1"; sed -n '3,$p' "$tmp/good.log"; } >"$tmp/bad.log"
                                                                      refuse set-late "line 3: a set record after"

# The walk comes from the scene, not from the log (src/shadetlm/timing_reference/scene_walk.hpp): a log
# whose walk or statistics disagree with the scene's is DIFFERENT even where its times
# are consistent with themselves. Each of these passed the judge that read the walk
# from the log.
differs() {  # differs NAME TEXT [timing-check options]: the log in $tmp/bad.log
  local name=$1 text=$2
  shift 2
  "$bin" timing-check "$tmp/bad.log" "$@" >"$tmp/out" 2>&1
  local rc=$?
  if [[ $rc -eq 1 ]] && grep -qF -- "$text" "$tmp/out"; then
    ((passes++))
  else
    echo "FAIL walk $name: exit $rc, or no \"$text\""; sed 's/^/    /' "$tmp/out" | head -4; ((failures++))
  fi
}
# A packet start dropped: the times do not depend on it, the packets do.
awk '$1 == "k" && ++k == 20 { next } { print }' "$tmp/good.log" >"$tmp/bad.log"
differs packet-start "starts a packet: the log 0, the scene 1"
sed 's/^walked \([0-9]*\) /walked 1\1 /' "$tmp/good.log" >"$tmp/bad.log";  differs walked "pixels walked"
sed 's/^shaded lighting \([0-9]*\)/shaded lighting 1\1/' "$tmp/good.log" >"$tmp/bad.log"
differs shaded "lighting's pixels worked"
cp "$tmp/good.log" "$tmp/bad.log"
differs other-resolution "triangles handed on by setup" --scene "$src/golden/sphere/scene.json" --set camera.resolution=[64,48]
sed 's/^frame_end \([0-9]*\)/frame_end 1\1/' "$tmp/good.log" >"$tmp/bad.log";  differs frame-end "the frame's cycles"

echo "$passes passed, $failures failed"
[[ $failures -eq 0 && $passes -ge 20 ]]
