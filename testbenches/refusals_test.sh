#!/usr/bin/env bash
# What the program says aloud or refuses before it runs (docs/robustness.md): a number
# format that saturated exits 3 like a NaN; a map cache entry that does not read is built
# again with a warning naming it; the map cache folder may not collide with an output;
# an output's format follows its extension or is refused; the default memory budget
# keeps inside an address-space limit (ulimit -v).
# Usage: refusals_test.sh SHADETLM SOURCE_DIR
set -u
bin=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
passes=0
failures=0
# check NAME EXIT COMMAND...: COMMAND exits EXIT; its stdout in out.txt, stderr in err.txt.
check() {
  local name=$1 want=$2 rc
  shift 2
  "$@" >out.txt 2>err.txt
  rc=$?
  if ((rc == want)); then ((passes++)); else
    echo "FAIL $name: exit $rc, expected $want"; sed 's/^/    /' err.txt | head -5; ((failures++))
  fi
}
says() {  # says NAME TEXT: the last command's stderr holds TEXT
  if grep -qF -- "$2" err.txt; then ((passes++)); else
    echo "FAIL $1: stderr lacks '$2'"; sed 's/^/    /' err.txt | head -5; ((failures++)); fi
}
silent() {  # silent NAME TEXT: the last command's stderr does not hold TEXT
  if grep -qF -- "$2" err.txt; then echo "FAIL $1: stderr holds '$2'"; ((failures++)); else ((passes++)); fi
}
absent() {  # absent NAME PATH...: none of them exists
  local name=$1 f
  shift
  for f in "$@"; do [[ ! -e $f ]] || { echo "FAIL $name: $f exists"; ((failures++)); return; }; done
  ((passes++))
}
small=(--set 'camera.resolution=[48,32]')
steps=$src/scenes/parallax/steps.json

# --- Saturation is as loud as a NaN: said per block, exit 3, unless --allow-overflow.
saturating=("${small[@]}" --set pipeline.number_format=fixed:2.8 --set 'materials.red.diffuse=[1e3,1e3,1e3]')
cat >sat.json <<'JSON'
{ "camera": { "position": [0, 0, 4], "target": [0, 0, 0], "resolution": [48, 32] },
  "lights": [ { "type": "directional", "direction": [0, 0, -1] } ],
  "materials": { "red": { "diffuse": [0.8, 0.2, 0.1] } },
  "objects": [ { "shape": "sphere", "material": "red" } ] }
JSON
check saturation-exit-3 3 "$bin" render sat.json "${saturating[@]}" -o sat.exr --stats sat-stats.json
says saturation-per-block "lighting (fixed:2.8):"
says saturation-says-how "results saturated or overflowed"
says saturation-names-flag "--allow-overflow"
[[ -s sat.exr && -s sat-stats.json ]] && ((passes++)) || { echo "FAIL saturation-outputs: not written"; ((failures++)); }
check saturation-allowed 0 "$bin" render sat.json "${saturating[@]}" -o sat.exr --allow-overflow
says saturation-allowed-still-said "lighting (fixed:2.8):"
check no-saturation 0 "$bin" render sat.json "${small[@]}" --set pipeline.number_format=fixed:9.22 -o ok.exr
silent no-saturation-silent "saturated"

# --- The map cache: an entry that does not read (truncated, garbage, damaged) is built
# again with a warning naming it; the frame is the one a good entry gives.
check cache-fill 0 "$bin" render "$steps" "${small[@]}" -o first.exr --map-cache cache
entry=$(find cache -name '*.exr' | head -1)
[[ -n $entry ]] && ((passes++)) || { echo "FAIL cache-fill: no entry in cache/"; ((failures++)); }
check cache-reused 0 "$bin" render "$steps" "${small[@]}" -o again.exr --map-cache cache
silent cache-reused-quiet "warning"
size=$(stat -c %s "$entry")
for damage in truncated garbage flipped; do
  case $damage in
    truncated) truncate -s 100 "$entry" ;;
    garbage) head -c 5000 /dev/urandom >"$entry" ;;
    flipped)  # one byte in the middle of the compressed data changed
      printf '\x5a' | dd of="$entry" bs=1 seek=$((size / 2)) conv=notrunc status=none ;;
  esac
  check "cache-$damage" 0 "$bin" render "$steps" "${small[@]}" -o rebuilt.exr --map-cache cache
  says "cache-$damage-warns" "$entry"
  says "cache-$damage-rebuilt" "built again"
  check "cache-$damage-same-frame" 0 "$bin" compare rebuilt.exr first.exr --fail 0
  check "cache-$damage-healed" 0 "$bin" render "$steps" "${small[@]}" -o healed.exr --map-cache cache
  silent "cache-$damage-healed-quiet" "warning"
  size=$(stat -c %s "$entry")
done

# --- Every path collision is refused before the run, the map cache folder included:
# exit 2, naming the option, nothing made.
check cache-is-output 2 "$bin" render "$steps" "${small[@]}" -o mc.exr --map-cache mc.exr
says cache-is-output-named "--map-cache"
absent cache-is-output-nothing mc.exr
check cache-inside-output 2 "$bin" render "$steps" "${small[@]}" -o a.exr --map-cache a.exr/maps
says cache-inside-output-named "--map-cache"
absent cache-inside-output-nothing a.exr
echo text >plain
check cache-is-a-file 2 "$bin" render "$steps" "${small[@]}" -o b.exr --map-cache plain
says cache-is-a-file-named "--map-cache"
absent cache-is-a-file-nothing b.exr

# --- An output's format follows its extension (any case), or the run is refused.
check render-png-output 2 "$bin" render "${small[@]}" -o out.png
says render-png-output-named "--output"
absent render-png-output-nothing out.png
check render-upper-exr 0 "$bin" render "${small[@]}" -o OUT.EXR
check reference-tiff-output 2 "$bin" reference "${small[@]}" -o out.tiff
absent reference-tiff-output-nothing out.tiff
check compare-diff-png 2 "$bin" compare first.exr first.exr --diff d.png
absent compare-diff-png-nothing d.png
python3 - <<'PY'
import struct, zlib
def chunk(kind, data): return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
def png(path, w, h, rows):
    raw = b"".join(b"\0" + bytes(r) for r in rows)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
png("h.png", 16, 16, [[(x * 16 + y * 7) % 256 for x in range(16)] for y in range(16)])
# A 16000x16000 grey image in a few hundred bytes: its rows all zero.
w = h = 16000
co = zlib.compressobj(9)
data = b"".join(co.compress(b"\0" * (w + 1)) for _ in range(h)) + co.flush()
open("bomb.png", "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                             + chunk(b"IDAT", data) + chunk(b"IEND", b""))
PY
check precompute-map-png 2 "$bin" precompute distancemap h.png -o m.png
says precompute-map-png-named "--output"
absent precompute-map-png-nothing m.png
check precompute-normalmap-jpg 2 "$bin" precompute normalmap h.png -o n.jpg
absent precompute-normalmap-jpg-nothing n.jpg
check precompute-normalmap-png 0 "$bin" precompute normalmap h.png -o n.png

# --- --threads and --compression: every lossless method writes a frame that reads back
# as the same pixels, on one thread or several; bad counts and names refused (exit 2).
check frame-default 0 "$bin" render "${small[@]}" -o c-default.exr --compare-reference
for c in none rle zips zip piz zip:1 zips:9; do
  for t in 1 3; do
    check "compression-$c-threads-$t" 0 "$bin" --threads "$t" --compression "$c" render "${small[@]}" -o "c-$c.exr" \
      --compare-reference
    check "compression-$c-threads-$t-same" 0 "$bin" compare "c-$c.exr" c-default.exr --fail 0
  done
done
[[ $(stat -c %s c-none.exr) -gt $(stat -c %s c-zip.exr) ]] && ((passes++)) ||
  { echo "FAIL compression-zip-smaller: zip no smaller than none"; ((failures++)); }
# zlib's level changes the file, not the pixels (checked above): level 1 is larger.
[[ $(stat -c %s c-zip:1.exr) -gt $(stat -c %s c-zip.exr) ]] && ((passes++)) ||
  { echo "FAIL compression-zip-level: zip:1 no larger than zip"; ((failures++)); }
# Each method wrote its own kind of file: five sizes, all different.
sizes=$(for c in none rle zips zip piz; do stat -c %s "c-$c.exr"; done | sort -u | wc -l)
((sizes == 5)) && ((passes++)) || { echo "FAIL compression-methods-differ: $sizes sizes for 5 methods"; ((failures++)); }
check threads-twice 2 "$bin" --threads 1 render "${small[@]}" -o bad.exr --threads 2
says threads-twice-named "--threads"
for bad in 0 -1 1025 two 1.5 ''; do
  check "threads-$bad" 2 "$bin" --threads "$bad" render "${small[@]}" -o bad.exr
  says "threads-$bad-named" "--threads"
  absent "threads-$bad-nothing" bad.exr
done
check compression-typo 2 "$bin" render "${small[@]}" -o bad.exr --compression pizz
says compression-typo-suggests "did you mean 'piz'"
check compression-lossy 2 "$bin" render "${small[@]}" -o bad.exr --compression dwaa
says compression-lossy-why "lossy"
for bad in zip:0 zip:10 zip: zips:x rle:2 piz:1; do
  check "compression-level-$bad" 2 "$bin" render "${small[@]}" -o bad.exr --compression "$bad"
  says "compression-level-$bad-named" "--compression"
  says "compression-level-$bad-why" "from 1 to 9"
  absent "compression-level-$bad-nothing" bad.exr
done
check compression-unknown 2 "$bin" render "${small[@]}" -o bad.exr --compression brotli
says compression-unknown-named "--compression"
absent compression-nothing bad.exr

# --- An address-space limit (ulimit -v) below the default budget: the budget follows it,
# and an image too large for it is refused by name (exit 2), not met as an allocation
# that fails. (Not under AddressSanitizer, whose shadow memory no ulimit -v leaves room for.)
if ldd "$bin" | grep -q libasan; then
  echo "note: the address-space limit is skipped under AddressSanitizer"
else
  cat >bomb.json <<'JSON'
{ "camera": { "position": [0, 0, 4], "target": [0, 0, 0], "resolution": [16, 16] },
  "lights": [ { "type": "directional", "direction": [0, 0, -1] } ],
  "textures": { "t": { "type": "image", "file": "bomb.png" } },
  "materials": { "m": { "texture": "t" } },
  "objects": [ { "shape": "sphere", "material": "m" } ] }
JSON
  check address-space-limit 2 bash -c 'ulimit -v 3000000 && exec "$0" render bomb.json -o bomb.exr' "$bin"
  says address-space-limit-named "bomb.json: textures.t.file"
  says address-space-limit-budget "budget"
  absent address-space-limit-nothing bomb.exr
fi

echo "$passes passed, $failures failed"
((failures == 0))
