#!/usr/bin/env bash
# Hostile input: malformed scenes, meshes, images and frames, and bad options. Each
# must give a clear message that names the file (or option), exit code 2, no output
# file, and no crash. Usage: hostile_test.sh SHADETLM SOURCE_DIR
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
passes=0
failures=0

# hostile NAME EXPECTED_TEXT COMMAND...: exit 2, stderr names EXPECTED_TEXT, no out.exr
hostile() {
  local name=$1 text=$2
  shift 2
  rm -f out.exr out.png
  "$@" >stdout 2>stderr
  local rc=$?
  local ok=1
  [[ $rc -eq 2 ]] || { echo "FAIL $name: exit $rc, expected 2"; ok=0; }
  grep -qF -- "$text" stderr || { echo "FAIL $name: message lacks '$text'"; ok=0; }
  [[ ! -e out.exr && ! -e out.png ]] || { echo "FAIL $name: output written"; ok=0; }
  if ((ok)); then ((passes++)); else sed 's/^/    /' stderr | head -5; ((failures++)); fi
}
scene() {  # scene FILE JSON-of-the-objects-array [extra top-level JSON]: a scene around them
  printf '{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [32,24]},
           "lights": [{"type": "directional", "direction": [0,0,-1]}],
           "textures": %s, "objects": %s}' "${3:-{\}}" "$2" >"$1"
}
render() { "$bin" render "$1" -o out.exr --preview out.png "${@:2}"; }

# Good material to break: a frame and a PNG.
"$bin" reference --set 'camera.resolution=[16,8]' -o good.exr --preview good.png >/dev/null || { echo "setup failed"; exit 1; }

# Scene files.
: >empty.json;                                  hostile empty-scene "empty.json" render empty.json
printf '{"camera": {"position": [0,0' >trunc.json; hostile truncated-json "trunc.json: line 1" render trunc.json
echo '[1, 2, 3]' >array.json;                   hostile not-an-object "array.json" render array.json
printf '%.0s[' $(seq 1 100000) >deep.json;      hostile deeply-nested "deep.json" render deep.json
{ printf '{"camera": '; printf '%.0s[' $(seq 1 200000); printf '%.0s]' $(seq 1 200000); printf '}'; } >deepvalid.json
hostile deeply-nested-valid "nested deeper than" render deepvalid.json
{ printf '{"camera": "'; head -c 20000000 /dev/zero | tr '\0' 'a'; printf '"}'; } >huge.json
hostile enormous-json "huge.json: camera" render huge.json
scene nan.json '[{"shape": "sphere", "radius": NaN}]'; hostile nan-literal "nan.json" render nan.json
scene big.json '[{"shape": "sphere", "radius": 1e999}]'; hostile overflowing-number "big.json" render big.json
scene type.json '[{"shape": "sphere", "radius": "large"}]'; hostile wrong-type "objects.0.radius" render type.json
scene key.json '[{"shape": "sphere", "radiuss": 1}]'; hostile unknown-key "objects.0.radiuss" render key.json
scene neg.json '[{"shape": "sphere"}]';          hostile negative-resolution "camera.resolution.0" render neg.json --set 'camera.resolution=[-5,24]'
hostile zero-resolution "camera.resolution.1" render neg.json --set 'camera.resolution=[32,0]'
hostile huge-resolution "camera.resolution.0" render neg.json --set 'camera.resolution=[1000000,24]'
hostile degenerate-camera "camera.target" render neg.json --set 'camera.target=[0,0,4]'
hostile bad-override "--set" render neg.json --set 'objects.7.radius=1'
hostile bad-number-format "pipeline.number_format" render neg.json --set 'pipeline.number_format=float64'
hostile too-wide-fixed "pipeline.normalize.format" render neg.json --set 'pipeline.normalize.format=fixed:20.40'
hostile number-format-type "pipeline.lighting.format" render neg.json --set 'pipeline.lighting.format=16'
# Timing settings (docs/configuration.md): a FIFO of no room would deadlock, fractions
# and absurd sizes are no design, units take at least a cycle.
hostile fifo-zero "pipeline.lighting.fifo_depth" render neg.json --set 'pipeline.lighting.fifo_depth=0'
hostile fifo-negative "pipeline.normalize.fifo_depth" render neg.json --set 'pipeline.normalize.fifo_depth=-2'
hostile fifo-fraction "pipeline.framebuffer.fifo_depth" render neg.json --set 'pipeline.framebuffer.fifo_depth=1.5'
hostile fifo-huge "pipeline.raster.fifo_depth" render neg.json --set 'pipeline.raster.fifo_depth=1000000000'
hostile fifo-of-setup "pipeline.setup.fifo_depth" render neg.json --set 'pipeline.setup.fifo_depth=4'
hostile latency-zero "pipeline.lighting.latency" render neg.json --set 'pipeline.lighting.latency=0'
hostile unit-zero "pipeline.unit.div.ii" render neg.json --set 'pipeline.unit.div.ii=0'
hostile unit-huge "pipeline.unit.sqrt.latency" render neg.json --set 'pipeline.unit.sqrt.latency=99999999'
hostile unit-text "pipeline.unit.mul.latency" render neg.json --set 'pipeline.unit.mul.latency="four"'
# Memory settings (docs/memory.md): caches of powers of two whose ways divide their
# lines, a DRAM that moves something and answers within its range.
mem=(--set pipeline.memory.model=dram)
hostile cache-not-pow2 "pipeline.framebuffer.cache.size" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.cache.size=1000'
hostile line-not-pow2 "pipeline.framebuffer.cache.line" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.cache.line=48'
hostile line-over-cache "pipeline.framebuffer.cache.line" render neg.json "${mem[@]}" \
  --set 'pipeline.framebuffer.cache.size=256' --set 'pipeline.framebuffer.cache.line=512'
hostile ways-not-dividing "pipeline.framebuffer.cache.ways" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.cache.ways=3'
hostile ways-zero "pipeline.framebuffer.cache.ways" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.cache.ways=0'
hostile cache-huge "pipeline.raster.cache.size" render neg.json "${mem[@]}" --set 'pipeline.raster.cache.size=1073741824'
hostile line-tiny "pipeline.raster.cache.line" render neg.json "${mem[@]}" --set 'pipeline.raster.cache.line=1'
hostile ways-huge "pipeline.raster.cache.ways" render neg.json "${mem[@]}" --set 'pipeline.raster.cache.ways=65536'
hostile bandwidth-zero "pipeline.memory.bytes_per_cycle" render neg.json "${mem[@]}" --set 'pipeline.memory.bytes_per_cycle=0'
hostile dram-latency-zero "pipeline.memory.latency" render neg.json "${mem[@]}" --set 'pipeline.memory.latency=0'
hostile dram-latency-huge "pipeline.memory.latency" render neg.json "${mem[@]}" --set 'pipeline.memory.latency=1e9'
hostile memory-model "pipeline.memory.model" render neg.json --set 'pipeline.memory.model=sram'
hostile layout "pipeline.framebuffer.cache.layout" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.cache.layout=hilbert'
hostile miss-queue-negative "pipeline.framebuffer.miss_queue" render neg.json "${mem[@]}" --set 'pipeline.framebuffer.miss_queue=-1'
# The timing log is kept in memory: large frames are refused before the run.
hostile timing-log-huge "--timing-log" render neg.json --set 'camera.resolution=[2048,1024]' --timing-log t.log
[[ ! -e t.log ]] && ((passes++)) || { echo "FAIL: a refused timing log was written"; ((failures++)); }
nine='{"type": "directional", "direction": [0,-1,0]}'
hostile too-many-lights "at most 8 lights" render neg.json --set "lights=[$nine,$nine,$nine,$nine,$nine,$nine,$nine,$nine,$nine]"

# Meshes.
scene nomesh.json '[{"shape": "mesh", "file": "missing.obj"}]'; hostile missing-mesh "objects.0.file" render nomesh.json
head -c 3000 /dev/urandom >noise.obj
scene noise.json '[{"shape": "mesh", "file": "noise.obj"}]'; hostile garbage-mesh "noise.obj" render noise.json
: >empty.obj
scene emptyobj.json '[{"shape": "mesh", "file": "empty.obj"}]'; hostile empty-mesh "empty.obj" render emptyobj.json
printf 'v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n' >nan.obj
scene nanobj.json '[{"shape": "mesh", "file": "nan.obj"}]'; hostile mesh-with-nan "nan.obj" render nanobj.json
printf 'f 1 2 3\n' >novert.obj
scene novert.json '[{"shape": "mesh", "file": "novert.obj"}]'; hostile mesh-without-vertices "novert.obj" render novert.json
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >index.obj
scene index.json '[{"shape": "mesh", "file": "index.obj"}]'; hostile index-out-of-range "index.obj" render index.json
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0\n' >trunc.ply
scene ply.json '[{"shape": "mesh", "file": "trunc.ply"}]'; hostile truncated-ply "trunc.ply" render ply.json
echo '{"asset": {"version": "2.0"}, "meshes": [' >bad.gltf
scene gltf.json '[{"shape": "mesh", "file": "bad.gltf"}]'; hostile broken-gltf "bad.gltf" render gltf.json
mkdir -p dir.obj
scene dirmesh.json '[{"shape": "mesh", "file": "dir.obj"}]'; hostile mesh-is-a-folder "objects.0.file" render dirmesh.json

# Images.
tex() {  # tex SCENE FILE: a scene whose sphere wears image FILE
  scene "$1" '[{"shape": "sphere", "material": "m"}]' "{\"t\": {\"type\": \"image\", \"file\": \"$2\"}}"
  sed -i 's/"objects"/"materials": {"m": {"texture": "t"}}, "objects"/' "$1"
}
head -c 60 good.png >trunc.png;   tex tpng.json trunc.png;   hostile truncated-png "trunc.png" render tpng.json
: >zero.png;                      tex zpng.json zero.png;    hostile empty-png "zero.png" render zpng.json
# A PNG header claiming 2^30 × 2^30 pixels.
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x40\x00\x00\x00\x40\x00\x00\x00\x08\x06\x00\x00\x00\x00\x00\x00\x00' >huge.png
tex hpng.json huge.png;           hostile huge-png "huge.png" render hpng.json
head -c 120 good.exr >trunc.exr;  tex texr.json trunc.exr;   hostile truncated-exr "trunc.exr" render texr.json
head -c 4000 /dev/urandom >noise.exr; tex nexr.json noise.exr; hostile garbage-exr "noise.exr" render nexr.json
head -c 4000 /dev/urandom >noise.jpg; tex njpg.json noise.jpg; hostile garbage-jpeg "noise.jpg" render njpg.json
cp good.png picture.bmp;          tex bmp.json picture.bmp;  hostile unknown-image-type "picture.bmp" render bmp.json
mkdir -p dir.png;                 tex dpng.json dir.png;     hostile image-is-a-folder "textures.t.file" render dpng.json

# Bump mapping: materials and height maps, and `precompute normalmap`.
bump() {  # bump SCENE MATERIAL-JSON [TEXTURE-SIZE]: a sphere of that material, a noise height map
  scene "$1" '[{"shape": "sphere", "material": "m"}]' \
    "{\"h\": {\"type\": \"value-noise\", \"size\": ${3:-[16,16]}}}"
  sed -i "s/\"objects\"/\"materials\": {\"m\": $2}, \"objects\"/" "$1"
}
bump nomap.json '{"path": "bump-tangent"}';  hostile bump-without-map 'materials.m.path: bump-tangent needs a height_map' render nomap.json
bump npot.json '{"path": "bump-classic", "height_map": "h"}' '[12,16]'
hostile bump-height-not-power-of-two "materials.m.height_map" render npot.json
bump phongnm.json '{"normal_map": "h"}';     hostile normal-map-on-phong "materials.m.normal_map" render phongnm.json
bump classicnm.json '{"path": "bump-classic", "normal_map": "h"}'; hostile normal-map-on-classic "materials.m.normal_map" render classicnm.json
bump stretched.json '{"path": "bump-object", "height_map": "h"}'
sed -i 's/"material": "m"}/"material": "m", "transform": {"scale": [1, 2, 1]}}/' stretched.json
hostile bump-object-stretched "objects.0.transform" render stretched.json
bump notex.json '{"path": "texture-object"}'; hostile texture-path-without-texture 'materials.m.path: texture-object needs a texture' render notex.json
"$bin" reference --set 'camera.resolution=[12,8]' -o odd.exr --preview odd.png >/dev/null
hostile precompute-missing-height "absent.png" "$bin" precompute normalmap absent.png -o out.exr
hostile precompute-truncated-height "trunc.png" "$bin" precompute normalmap trunc.png -o out.exr
hostile precompute-not-power-of-two "powers of two" "$bin" precompute normalmap odd.png -o out.exr
hostile precompute-form-needs-surface "--surface" "$bin" precompute normalmap good.png -o out.exr --form tangent
hostile precompute-missing-surface "absent.obj" "$bin" precompute normalmap good.png -o out.exr --surface absent.obj
mkdir -p nmdir.exr
hostile precompute-output-is-a-folder "--output" "$bin" precompute normalmap good.png -o nmdir.exr

# Frames given to compare, and options.
hostile compare-truncated "trunc.exr" "$bin" compare trunc.exr good.exr --diff out.exr
hostile compare-garbage "noise.exr" "$bin" compare good.exr noise.exr --diff out.exr
hostile compare-missing "absent.exr" "$bin" compare absent.exr good.exr --diff out.exr
hostile bad-trace-region "--trace-region" "$bin" render -o out.exr --vcd t.vcd --trace-region 1,2,3
hostile bad-trace-triangles "--trace-triangles" "$bin" render -o out.exr --vcd t.vcd --trace-triangles 9..2
hostile vcd-without-extension "--vcd" "$bin" render -o out.exr --vcd trace.txt
mkdir -p taken.vcd folder.exr
hostile vcd-is-a-folder "--vcd" "$bin" render -o out.exr --vcd taken.vcd --timeline t.json
hostile vcd-unwritable "--vcd" "$bin" render -o out.exr --vcd /proc/trace.vcd
hostile output-is-a-folder "--output" "$bin" render -o folder.exr --vcd t.vcd --timeline t.json
[[ ! -e t.vcd && ! -e t.gtkw && ! -e t.json ]] && ((passes++)) || { echo "FAIL: inspection files left behind"; ((failures++)); }

echo "$passes passed, $failures failed"
[[ $failures -eq 0 && $passes -ge 30 ]]
