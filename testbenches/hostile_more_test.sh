#!/usr/bin/env bash
# More hostile input, beyond hostile_test.sh: every scene field with wrong types, out of
# range, non-finite and repeated values; broken meshes and images; numeric options given
# nan, inf and text; outputs that clash with inputs or with each other; values that
# overflow float32 at render time. Bad input must give exit code 2, a message naming the
# file and the field (or the option), no output file, no crash and no temporary left
# behind. Usage: hostile_more_test.sh SHADETLM SOURCE_DIR
set -u
export LC_ALL=C  # messages compared byte for byte
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
passes=0
failures=0
py=$(python3 -c 'import sys; print(sys.executable)') || { echo "setup failed: python3"; exit 1; }

S() { timeout -k 5 30 "$bin" "$@"; }  # a hung run ends as exit 124: a failure, not a stall
# big COMMAND...: under a 4 GB address-space limit; the child's peak RSS (kB) into ./rss.
# Under AddressSanitizer (scripts/test.sh --sanitize), which reserves terabytes of address
# space for its shadow memory and adds to the resident size, neither the limit nor the
# peak is measured (./rss reads 0): the plain build's run holds them.
asan=0
ldd "$bin" | grep -q libasan && asan=1
big() {
  if ((asan)); then
    echo 0 >rss
    timeout -k 5 30 "$bin" "$@"
    return
  fi
  (ulimit -v 4000000; exec "$py" -c 'import resource, subprocess, sys
r = subprocess.call(sys.argv[1:])
open("rss", "w").write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss))
sys.exit(r if r >= 0 else 128 - r)' timeout -k 5 30 "$bin" "$@")
}
render() { S render "$1" -o out.exr --preview out.png "${@:2}"; }

# leftovers NAME: no "*.tmp.*" anywhere (prints and removes them)
leftovers() {
  shopt -s globstar nullglob dotglob
  local left=(**/*.tmp.*)
  shopt -u globstar nullglob dotglob
  ((${#left[@]} == 0)) && return 0
  echo "FAIL $1: temporaries left: ${left[*]:0:3}"
  rm -rf "${left[@]}"
  return 1
}
verdict() {  # verdict OK: count the case, showing the first lines of stderr when it failed
  if (($1)); then ((passes++)); else sed 's/^/    /' stderr | head -3 | cut -c1-300; ((failures++)); fi
}

# hostile [-a TEXT] [-n TEXT] [-x FILE] [-u FILE] [-m KB] [-s] [-U] NAME TEXT COMMAND...:
# exit 2, stderr holds TEXT (and each -a TEXT, and no -n TEXT), no out.* (nor -x FILE)
# written, -u FILE unchanged, no temporaries; -m: peak RSS at most KB (needs `big`);
# -s: a short message (<= 300 bytes) without ESC or BEL; -U: stderr is valid UTF-8.
hostile() {
  local also=() lacks=() absent=(out.exr out.png out.json heat.png) keep=() short=0 utf8=0 rss=0
  while [[ $1 == -? ]]; do
    case $1 in
      -a) also+=("$2") ;; -n) lacks+=("$2") ;; -x) absent+=("$2") ;; -u) keep+=("$2") ;; -m) rss=$2 ;;
      -s) short=1; shift; continue ;; -U) utf8=1; shift; continue ;;
    esac
    shift 2
  done
  local name=$1 text=$2 f t err
  shift 2
  rm -rf "${absent[@]}" rss
  for f in "${keep[@]}"; do cp -p "$f" "$f.keep"; done
  "$@" >stdout 2>stderr
  local rc=$? ok=1
  err=$(<stderr)
  if ((rc >= 128)); then echo "FAIL $name: crashed (status $rc)"; ok=0
  elif ((rc != 2)); then echo "FAIL $name: exit $rc, expected 2"; ok=0; fi
  for t in "$text" "${also[@]}"; do [[ $err == *"$t"* ]] || { echo "FAIL $name: message lacks '$t'"; ok=0; }; done
  for t in "${lacks[@]}"; do [[ $err != *"$t"* ]] || { echo "FAIL $name: message holds '$t'"; ok=0; }; done
  for f in "${absent[@]}"; do [[ ! -e $f ]] || { echo "FAIL $name: $f written"; ok=0; rm -rf "$f"; }; done
  for f in "${keep[@]}"; do
    cmp -s "$f" "$f.keep" || { echo "FAIL $name: input $f changed"; ok=0; cp -p "$f.keep" "$f"; }
    rm -f "$f.keep"
  done
  if ((short)); then
    ((${#err} <= 300)) || { echo "FAIL $name: message of ${#err} bytes"; ok=0; }
    [[ $err != *[$'\x1b\x07']* ]] || { echo "FAIL $name: raw ESC or BEL in the message"; ok=0; }
  fi
  if ((utf8)); then
    "$py" -c 'import sys; open(sys.argv[1], "rb").read().decode("utf-8")' stderr 2>/dev/null ||
      { echo "FAIL $name: message is not valid UTF-8"; ok=0; }
  fi
  if ((rss)); then
    [[ -s rss ]] && (($(<rss) <= rss)) || { echo "FAIL $name: peak RSS $(cat rss 2>/dev/null) kB > $rss kB"; ok=0; }
  fi
  leftovers "$name" || ok=0
  verdict $ok
}

# either NAME REGEX CHECK COMMAND...: refused (exit 2, stderr matches REGEX, no out.*),
# or accepted (exit 0 and `eval CHECK` succeeds). Prints which, for the record.
either() {
  local name=$1 re=$2 check=$3 ok=1
  shift 3
  rm -f out.exr out.png out.json
  "$@" >stdout 2>stderr
  local rc=$?
  if ((rc == 2)) && grep -qE -- "$re" stderr && [[ ! -e out.exr && ! -e out.png && ! -e out.json ]]; then
    echo "NOTE $name: refused: $(head -1 stderr | cut -c1-160)"
  elif ((rc == 0)) && eval "$check"; then
    echo "NOTE $name: accepted${check:+ ($check)}"
  else
    echo "FAIL $name: exit $rc, neither refused naming /$re/ nor accepted with ($check)"; ok=0
  fi
  leftovers "$name" || ok=0
  verdict $ok
}

# renders NAME COMMAND...: good input: exit 0 and a finite out.exr
renders() {
  local name=$1 ok=1
  shift
  rm -f out.exr
  "$@" >stdout 2>stderr
  local rc=$?
  ((rc == 0)) || { echo "FAIL $name: exit $rc, expected 0"; ok=0; }
  [[ -s out.exr ]] && "$py" tools.py finite out.exr || { echo "FAIL $name: no finite frame"; ok=0; }
  leftovers "$name" || ok=0
  verdict $ok
}

# finite NAME REGEX COMMAND...: the command writes out.exr (and, for render, --stats
# out.json). Refused naming REGEX: fine. Otherwise the frame must hold no NaN or infinity
# (depth +inf excepted), and a run that replaced non-finite values must say so and exit
# non-zero (stats nonfinite_replaced > 0 with exit 0 is a silent repair).
finite() {
  local name=$1 re=$2 ok=1
  shift 2
  rm -f out.exr out.json
  "$@" >stdout 2>stderr
  local rc=$?
  if ((rc >= 128)); then echo "FAIL $name: crashed (status $rc)"; ok=0
  elif ((rc == 2)) && grep -qE -- "$re" stderr && [[ ! -e out.exr ]]; then
    echo "NOTE $name: refused: $(head -1 stderr | cut -c1-160)"
  else
    if [[ -e out.exr ]]; then
      "$py" tools.py finite out.exr || { echo "FAIL $name: non-finite values in the frame (exit $rc)"; ok=0; }
    elif ((rc == 0)); then echo "FAIL $name: exit 0 and no frame"; ok=0; fi
    local replaced=0 overflows=0
    [[ -e out.json ]] && replaced=$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1])).get("nonfinite_replaced", 0))' out.json)
    [[ -e out.json ]] && overflows=$("$py" -c 'import json, sys; n = json.load(open(sys.argv[1])).get("numbers", {}); print(n.get("overflows", 0) + n.get("invalid", 0))' out.json)
    if ((rc == 0 && replaced > 0)); then
      echo "FAIL $name: $replaced non-finite values replaced, yet exit 0"; ok=0
    elif ((rc == 0 && overflows > 0)); then  # saturation is as loud as a NaN (issue 38)
      echo "FAIL $name: $overflows overflows or invalid operations counted, yet exit 0"; ok=0
    elif ((rc != 0)) && ! grep -qiE 'non-finite|nan|infinit|replaced|saturated|overflow' stderr; then
      echo "FAIL $name: exit $rc without naming /$re/ or the non-finite values"; ok=0
    fi
    ((ok)) && echo "NOTE $name: rendered (exit $rc, $replaced replaced)"
  fi
  leftovers "$name" || ok=0
  verdict $ok
}

scene() {  # scene FILE OBJECTS [TEXTURES [MATERIALS]]: a scene around them
  printf '{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [32,24]},
           "lights": [{"type": "directional", "direction": [0,0,-1]}],
           "textures": %s, "materials": %s, "objects": %s}' "${3:-{\}}" "${4:-{\}}" "$2" >"$1"
}
# bad NAME FIELD KEY=VALUE...: base.json with these overrides is refused naming base.json and FIELD
bad() {
  local name=$1 field=$2 sets=() s
  shift 2
  for s; do sets+=(--set "$s"); done
  hostile "$name" "base.json: $field" render base.json "${sets[@]}"
}

# Fixtures: PNGs with their chunks and CRCs written here, uncompressed EXRs, a JPEG, and a
# reader of the frames' EXRs (scanline; none, ZIPS or ZIP) for the non-finite check.
cat >tools.py <<'PY'
import base64, math, struct, sys, zlib

def chunk(kind, data, crc_ok=True):
    crc = zlib.crc32(kind + data) & 0xffffffff
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc if crc_ok else crc ^ 0xdeadbeef)

def png(path, w, h, ctype=0, depth=8, rows=None, plte=None, bad_ihdr=False, bad_idat=False, iend=True,
        interlace=0, raw=None, extra=b""):
    ch = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ctype]
    if raw is None:
        rows = rows or [[(x * 16 + y * 7) % 256 for x in range(w * ch)] for y in range(h)]
        raw = b"".join(b"\0" + bytes(r) for r in rows)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, interlace), not bad_ihdr)
    out += extra
    if plte is not None:
        out += chunk(b"PLTE", bytes(plte))
    out += chunk(b"IDAT", zlib.compress(raw), not bad_idat)
    if iend:
        out += chunk(b"IEND", b"")
    open(path, "wb").write(out)

HALF, FLOAT = 1, 2

def exr(path, w, h, channels, value, ptype=FLOAT, window=None):
    """An uncompressed scanline EXR; value(channel, x, y) gives each sample."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chans = sorted(channels)
    chl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", ptype, 0, 1, 1) for c in chans) + b"\0"
    x1, y1 = window or (w - 1, h - 1)
    box = struct.pack("<4i", 0, 0, x1, y1)
    hdr = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chl) +
           attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
           attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
           attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
           attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) +
           attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    fmt = "<e" if ptype == HALF else "<f"
    lines = []
    for y in range(h):
        data = b"".join(struct.pack(fmt, value(c, x, y)) for c in chans for x in range(w))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    offsets, offset = [], len(hdr) + 8 * len(lines)  # (a window larger than the data: a table as short)
    for line in lines:
        offsets.append(offset)
        offset += len(line)
    open(path, "wb").write(hdr + struct.pack("<%dQ" % len(lines), *offsets) + b"".join(lines))

JPEG = ("/9j/4AAQSkZJRgABAQEAAQABAAD/2wBDAAMCAgICAgMCAgIDAwMDBAYEBAQEBAgGBgUGCQgKCgkICQkKDA8MCgsOCwkJDRENDg8Q"
        "EBEQCgwSExIQEw8QEBD/2wBDAQMDAwQDBAgEBAgQCwkLEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQEBAQ"
        "EBAQEBAQEBD/wAARCAAQABADASIAAhEBAxEB/8QAFgABAQEAAAAAAAAAAAAAAAAABwQF/8QAJBAAAQQBBAICAwAAAAAAAAAAAQID"
        "BAYFBwgSExEiABQJMTL/xAAVAQEBAAAAAAAAAAAAAAAAAAAABv/EACMRAAECBQMFAAAAAAAAAAAAAAECEQMEBQYhABIxFRZhgeH/"
        "2gAMAwEAAhEDEQA/ABSm0mobc8HmExLUlRzzEWPkJWW+ulrsaUVAseUgslSlH9LKuPryIKuWPZdskzXmm3fX5m2nF4GlVxx/HOpx"
        "4ks51+MiU/Iaad7UcUo4tILoS4kqcWkezS0hO/HvuRp0rO6hWnWO1UisZVuFi4GFeyEpmGepa5S5SWVPuciFKRFLgSrwetnyPIB+"
        "Vb4N9mKhQMzo5po9XLdDs9d6ZVix2VEhiL9kuNPxw2gEKcDQ/rs8AuA8VAe0vdl7VOYn+27flGAUgmITjbhSmCg3BYlyeWDkMolv"
        "w4KOp1KM6iCNvngZHwetf//Z")  # a 16x16 baseline JPEG (CPython's test image)

def fixtures():
    png("h16.png", 16, 16)                            # good: a 16x16 grey height map
    png("rgb16.png", 16, 16, ctype=2)                 # good: a 16x16 colour image
    png("one.png", 1, 1, ctype=2, rows=[[200, 100, 50]])
    png("crc-ihdr.png", 16, 16, bad_ihdr=True)
    png("crc-idat.png", 16, 16, bad_idat=True)
    png("crc-text.png", 16, 16, extra=chunk(b"tEXt", b"Comment\0hello", False))
    png("noiend.png", 16, 16, iend=False)
    png("zerow.png", 0, 16, raw=b"\0" * 16)
    png("badpal.png", 16, 16, ctype=3, plte=[255, 0, 0, 0, 0, 255],  # 2 colours, indices up to 255
        rows=[[(x * 16 + y) % 256 for x in range(16)] for y in range(16)])
    png("baddepth.png", 16, 16, ctype=2, depth=3)
    png("badinterlace.png", 16, 16, interlace=7)
    png("shortidat.png", 16, 16, raw=b"\0" * 40)
    png("badfilter.png", 16, 16, raw=b"".join(b"\x09" + bytes(16) for _ in range(16)))
    png("alpha.png", 16, 16, ctype=4, rows=[[v for x in range(16) for v in ((x * 16) % 256, y * 16)] for y in range(16)])
    png("claim16k.png", 16000, 16000, ctype=6, raw=b"\0" * 64)  # 16000x16000 RGBA in 69 bytes
    exr("h16.exr", 16, 16, ["Y"], lambda c, x, y: ((x * 5 + y * 3) % 16) / 15)
    exr("depth-only.exr", 8, 8, ["Z"], lambda c, x, y: 1.0)
    exr("nan.exr", 16, 16, ["B", "G", "R"], lambda c, x, y: float("nan") if (x, y) == (3, 4) else 0.5)
    exr("inf-half.exr", 16, 16, ["B", "G", "R"], lambda c, x, y: float("inf") if (x, y) == (5, 5) else 0.5, HALF)
    exr("nan-height.exr", 16, 16, ["Y"], lambda c, x, y: float("nan") if (x, y) == (7, 1) else 0.5)
    exr("neg-inf-height.exr", 16, 16, ["Y"], lambda c, x, y: float("-inf") if (x, y) == (0, 0) else 0.5)
    exr("window-huge.exr", 4, 1, ["R"], lambda c, x, y: 0.5, window=(99999, 99999))
    jpeg = base64.b64decode(JPEG)
    open("good.jpg", "wb").write(jpeg)
    open("trunc.jpg", "wb").write(jpeg[:300])
    open("nohead.jpg", "wb").write(jpeg[:2] + jpeg[200:])

def read_exr(path):
    """Every sample of a scanline EXR (none, ZIPS or ZIP) by channel: name -> [float]."""
    d = open(path, "rb").read()
    assert d[:4] == b"\x76\x2f\x31\x01", "not an EXR"
    pos, attrs = 8, {}
    while d[pos] != 0:
        name = d[pos:d.index(b"\0", pos)]; pos += len(name) + 1
        kind = d[pos:d.index(b"\0", pos)]; pos += len(kind) + 1
        size, = struct.unpack_from("<i", d, pos); pos += 4
        attrs[name.decode()] = d[pos:pos + size]; pos += size
    pos += 1
    if "tiles" in attrs:
        sys.exit(path + ": a tiled EXR, not checked")
    chans, c, i = [], attrs["channels"], 0
    while c[i] != 0:
        n = c[i:c.index(b"\0", i)]; i += len(n) + 1
        t, = struct.unpack_from("<i", c, i); i += 16
        chans.append((n.decode(), t))
    comp = attrs["compression"][0]
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    per = {0: 1, 2: 1, 3: 16}.get(comp) or sys.exit(path + ": compression %d, not checked" % comp)
    out = {n: [] for n, _ in chans}
    for off in struct.unpack_from("<%dQ" % ((h + per - 1) // per), d, pos):
        y, size = struct.unpack_from("<ii", d, off)
        data, lines = d[off + 8:off + 8 + size], min(per, y1 - y + 1)
        if comp and size < sum(w * (2 if t == 1 else 4) for _, t in chans) * lines:
            t = bytearray(zlib.decompress(data))
            for k in range(1, len(t)):
                t[k] = (t[k - 1] + t[k] - 128) & 0xff
            data = bytearray(len(t))
            data[0::2], data[1::2] = t[:(len(t) + 1) // 2], t[(len(t) + 1) // 2:]
        p = 0
        for _ in range(lines):
            for n, t in chans:
                out[n].extend(struct.unpack_from({0: "<%dI", 1: "<%de", 2: "<%df"}[t] % w, data, p))
                p += w * (2 if t == 1 else 4)
    return out

def finite(path):
    bad = []
    for n, vals in read_exr(path).items():
        nf = [v for v in vals if not math.isfinite(v) and not (n == "Z" and v == math.inf)]
        if nf:
            bad.append("%s: %d non-finite (%r)" % (n, len(nf), nf[0]))
    if bad:
        sys.exit(path + ": " + "; ".join(bad))

{"fixtures": fixtures, "finite": lambda: finite(sys.argv[2])}[sys.argv[1]]()
PY
"$py" tools.py fixtures || { echo "setup failed: fixtures"; exit 1; }

scene base.json '[{"shape": "sphere", "material": "m"}]' '{"t": {"type": "checker", "size": [16,16]}}' '{"m": {}}'
scene pb.json '[{"shape": "plane", "material": "p"}]' '{"h": {"type": "value-noise", "size": [16,16]}}' \
  '{"p": {"path": "parallax", "height_map": "h"}}'
S reference base.json -o a.exr >/dev/null && S reference base.json -o b.exr --set lights.0.intensity=0.5 >/dev/null &&
  S render base.json -o t.exr --timing-log t.log >/dev/null || { echo "setup failed: frames"; exit 1; }
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj  # a good triangle without texture coordinates

# ------------------------------------------------------------------------------------------
# 1. Scenes
# ------------------------------------------------------------------------------------------
# Top level: format, wrong types, unknown keys, arrays that need an element.
bad format-string "format" 'format="1"'
bad format-two "format" 'format=2'
bad format-fraction "format" 'format=1.5'
hostile -n '-1' format-2to64 "base.json: format" render base.json --set 'format=18446744073709551615'
bad camera-not-object "camera" 'camera=[0,0,4]'
bad camera-null "camera" 'camera=null'
bad unknown-top-level "lightz" 'lightz=[]'
bad objects-empty "objects" 'objects=[]'
bad objects-object "objects" 'objects={}'
bad objects-element-number "objects.0" 'objects=[42]'
bad lights-string "lights" 'lights="sun"'
bad lights-null-element "lights.0" 'lights=[null]'
bad textures-array "textures" 'textures=[]'
bad materials-array "materials" 'materials=[]'
bad pipeline-array "pipeline" 'pipeline=[]'
bad pipeline-unknown "pipeline.nosuch" 'pipeline.nosuch=1'
bad pipeline-clock-zero "pipeline.clock_mhz" 'pipeline.clock_mhz=0'
bad pipeline-clock-nan "pipeline.clock_mhz" 'pipeline.clock_mhz=NaN'
hostile -n '-1' fifo-2to64 "base.json: pipeline.lighting.fifo_depth" render base.json --set 'pipeline.lighting.fifo_depth=18446744073709551615'
# Camera: field of view, clipping planes, resolution, vectors.
bad fov-zero "camera.fov_y" 'camera.fov_y=0'
bad fov-180 "camera.fov_y" 'camera.fov_y=180'
bad fov-negative "camera.fov_y" 'camera.fov_y=-45'
bad fov-NaN "camera.fov_y" 'camera.fov_y=NaN'
bad fov-huge "camera.fov_y" 'camera.fov_y=1e308'
bad fov-string "camera.fov_y" 'camera.fov_y="wide"'
bad near-zero "camera.near" 'camera.near=0'
bad near-negative "camera.near" 'camera.near=-1'
bad near-equals-far "camera.far" 'camera.near=10' 'camera.far=10'
bad near-beyond-far "camera.far" 'camera.near=100' 'camera.far=1'
bad far-huge "camera.far" 'camera.far=1e308'
hostile -n '-2147483648' resolution-2to31 "base.json: camera.resolution.0" render base.json --set 'camera.resolution=[2147483648,24]'
hostile -n '-1' resolution-2to64 "base.json: camera.resolution.0" render base.json --set 'camera.resolution=[18446744073709551615,24]'
bad resolution-min-int "camera.resolution.0" 'camera.resolution=[-2147483648,24]'
bad resolution-fraction "camera.resolution.0" 'camera.resolution=[32.5,24]'
bad resolution-one-element "camera.resolution" 'camera.resolution=[32]'
bad resolution-empty "camera.resolution" 'camera.resolution=[]'
bad resolution-string "camera.resolution" 'camera.resolution="32x24"'
bad resolution-too-many-pixels "camera.resolution" 'camera.resolution=[16384,16384]'
bad position-string-element "camera.position.2" 'camera.position=[0,0,"4"]'
bad position-two-elements "camera.position" 'camera.position=[0,0]'
bad position-empty "camera.position" 'camera.position=[]'
bad position-far "camera.position" 'camera.position=[0,0,1e7]'
bad position-huge "camera.position" 'camera.position=[0,0,1e308]'
bad target-far "camera.target" 'camera.target=[1e300,0,0]'
bad up-zero "camera.up" 'camera.up=[0,0,0]'
bad up-parallel "camera.up" 'camera.up=[0,0,1]'
bad up-NaN "camera.up" 'camera.up=["NaN",1,0]'
bad local-viewer-string "camera.local_viewer" 'camera.local_viewer="yes"'
bad local-viewer-number "camera.local_viewer" 'camera.local_viewer=1'
bad camera-unknown "camera.zoom" 'camera.zoom=2'
scene notarget.json '[{"shape": "sphere"}]'; sed -i 's/"target": \[0,0,0\], //' notarget.json
hostile camera-no-target "notarget.json: camera.target" render notarget.json
# Ambient and background colours: negative, non-finite, beyond float32, wrong shape.
bad ambient-negative "ambient" 'ambient=[-0.5,0,0]'
bad ambient-float32-overflow "ambient" 'ambient=[1e39,0,0]'
bad ambient-string "ambient" 'ambient="grey"'
bad ambient-NaN "ambient" 'ambient=[0,"NaN",0]'
bad background-float32-overflow "background" 'background=[1e39,0,0]'
bad background-huge "background" 'background=[0,0,1e308]'
bad background-negative "background" 'background=[0,0,-1]'
bad background-two "background" 'background=[1,1]'
bad background-inf-string "background" 'background=["Infinity",0,0]'
# Lights.
bad light-type-spot "lights.0.type" 'lights.0.type="spot"'
bad light-type-number "lights.0.type" 'lights.0.type=3'
bad light-no-type "lights.0.type" 'lights.0={"direction": [0,0,-1]}'
bad light-direction-zero "lights.0.direction" 'lights.0.direction=[0,0,0]'
bad light-direction-negative-zero "lights.0.direction" 'lights.0.direction=[-0.0,0,-0.0]'
bad light-direction-empty "lights.0.direction" 'lights.0.direction=[]'
bad light-direction-missing "lights.0.direction" 'lights.0={"type": "directional"}'
bad light-point-no-position "lights.0.position" 'lights.0={"type": "point"}'
bad light-point-far "lights.0.position" 'lights.0={"type": "point", "position": [0,0,2e6]}'
bad light-directional-position "lights.0.position" 'lights.0.position=[0,0,4]'
bad light-color-negative "lights.0.color" 'lights.0.color=[-1,1,1]'
bad light-color-1e300 "lights.0.color" 'lights.0.color=[1e300,1,1]'
bad light-color-float32-overflow "lights.0.color" 'lights.0.color=[1,1e39,1]'
bad light-color-NaN "lights.0.color" 'lights.0.color="NaN"'
bad light-intensity-negative "lights.0.intensity" 'lights.0.intensity=-1'
bad light-intensity-1e300 "lights.0.intensity" 'lights.0.intensity=1e300'
bad light-intensity-string "lights.0.intensity" 'lights.0.intensity="bright"'
bad light-unknown "lights.0.falloff" 'lights.0.falloff=2'
# Lights of 1e200 (and 1e-200) on each axis: refused naming the field, or rendered
# exactly as the unit direction.
for case in 'z [0,0,-1e200] [0,0,-1]' 'x [1e200,0,0] [1,0,0]' 'y [0,-1e200,0] [0,-1,0]' \
  'xyz [1e200,1e200,-1e200] [1,1,-1]' 'tiny [0,0,-1e-200] [0,0,-1]'; do
  read -r axis huge unit <<<"$case"
  S render base.json -o unit.exr --set "lights.0.direction=$unit" >/dev/null 2>&1
  either "light-direction-$axis" 'base.json: lights\.0\.direction' \
    'S compare out.exr unit.exr --layer RGB --fail 1e-5 >/dev/null 2>&1' render base.json --set "lights.0.direction=$huge"
done
# Textures (procedural and image).
bad texture-type "textures.t.type" 'textures.t.type="marble"'
bad texture-no-type "textures.t.type" 'textures.t={"size": [16,16]}'
bad checker-colors-one "textures.t.colors" 'textures.t.colors=[[1,0,0]]'
bad checker-colors-empty "textures.t.colors" 'textures.t.colors=[]'
bad checker-color-negative "textures.t.colors.0" 'textures.t.colors=[[-1,0,0],[0,0,0]]'
bad checker-color-float32-overflow "textures.t.colors.0" 'textures.t.colors=[[1e39,0,0],[0,0,0]]'
bad checker-color-1e300 "textures.t.colors.1" 'textures.t.colors=[[1,1,1],[0,1e300,0]]'
bad checker-color-string "textures.t.colors.1.0" 'textures.t.colors=[[1,0,0],["x",0,0]]'
bad texture-size-zero "textures.t.size.0" 'textures.t.size=[0,16]'
bad texture-size-8193 "textures.t.size.0" 'textures.t.size=[8193,16]'
bad texture-size-one "textures.t.size" 'textures.t.size=[16]'
bad texture-size-huge "textures.t.size.1" 'textures.t.size=[16,1e308]'
bad texture-size-2to32 "textures.t.size.0" 'textures.t.size=[4294967296,16]'
bad cells-zero "textures.t.cells" 'textures.t.cells=0'
bad cells-negative "textures.t.cells" 'textures.t.cells=-3'
bad cells-pair-zero "textures.t.cells.0" 'textures.t.cells=[0,4]'
hostile -n '-1' cells-2to64 "base.json: textures.t.cells" render base.json --set 'textures.t.cells=18446744073709551615'
bad octaves-zero "textures.t.octaves" 'textures.t.type="value-noise"' 'textures.t.octaves=0'
bad octaves-13 "textures.t.octaves" 'textures.t.type="value-noise"' 'textures.t.octaves=13'
bad levels-zero "textures.t.levels" 'textures.t.type="steps"' 'textures.t.levels=0'
bad gap-over-half "textures.t.gap" 'textures.t.type="bricks"' 'textures.t.gap=0.6'
bad gap-negative "textures.t.gap" 'textures.t.type="tiles"' 'textures.t.gap=-0.1'
bad seed-negative "textures.t.seed" 'textures.t.seed=-1'
bad seed-2to32 "textures.t.seed" 'textures.t.seed=4294967296'
hostile -n '-1' seed-2to64 "base.json: textures.t.seed" render base.json --set 'textures.t.seed=18446744073709551615'
bad seed-fraction "textures.t.seed" 'textures.t.seed=1.5'
bad wrap-mirror "textures.t.wrap" 'textures.t.wrap="mirror"'
bad texture-unknown "textures.t.tint" 'textures.t.tint=[1,1,1]'
bad image-no-file "textures.t.file" 'textures.t={"type": "image"}'
bad image-file-number "textures.t.file" 'textures.t={"type": "image", "file": 42}'
bad image-colorspace "textures.t.colorspace" 'textures.t={"type": "image", "file": "rgb16.png", "colorspace": "rec709"}'
# Materials.
bad material-diffuse-negative "materials.m.diffuse" 'materials.m.diffuse=[-0.1,0,0]'
bad material-diffuse-float32-overflow "materials.m.diffuse" 'materials.m.diffuse=[1e39,0,0]'
bad material-specular-1e300 "materials.m.specular" 'materials.m.specular=[1e300,1e300,1e300]'
bad material-ambient-two "materials.m.ambient" 'materials.m.ambient=[1,1]'
bad material-ambient-NaN "materials.m.ambient" 'materials.m.ambient=[1,"nan",1]'
bad shininess-negative "materials.m.shininess" 'materials.m.shininess=-1'
bad shininess-huge "materials.m.shininess" 'materials.m.shininess=1e308'
bad shininess-string "materials.m.shininess" 'materials.m.shininess="shiny"'
bad material-texture-missing "materials.m.texture" 'materials.m.texture="nosuch"'
bad material-texture-number "materials.m.texture" 'materials.m.texture=0'
bad material-path "materials.m.path" 'materials.m.path="toon"'
bad height-scale-negative "materials.m.height_scale" 'materials.m={"height_map": "t", "height_scale": -1}'
bad height-scale-without-map "materials.m.height_scale" 'materials.m.height_scale=0.1'
bad square-k-zero "materials.m.square_k" 'materials.m={"path": "bump-square", "height_map": "t", "square_k": 0}'
bad material-unknown "materials.m.emissive" 'materials.m.emissive=[1,1,1]'
bad material-not-object "materials.m" 'materials.m="red"'
bad parallax-on-phong "materials.m.parallax" 'materials.m.parallax={"method": "pom"}'
px() { bad "parallax-$1" "materials.m.parallax.$2" "materials.m={\"path\": \"parallax\", \"height_map\": \"t\", \"parallax\": $3}"; }
px method method '{"method": "raymarch"}'
px slices-zero slices '{"slices": 0}'
px slices-257 slices '{"slices": 257}'
px iterations-zero max_iterations '{"max_iterations": 0}'
px layers-min-zero layers_min '{"method": "steep", "layers_min": 0}'
px layers-max-below-min layers_max '{"method": "pom", "layers_min": 16, "layers_max": 8}'
px binary-steps-negative binary_steps '{"method": "relief", "binary_steps": -1}'
px elevation-90 min_elevation_deg '{"min_elevation_deg": 90}'
px margin-negative margin '{"margin": -1}'
px margin-65 margin '{"margin": 65}'
px depth-huge depth '{"depth": 1e308}'
px early-exit-string early_exit '{"early_exit": "no"}'
px map-on-cone map '{"method": "cone", "map": "refined"}'
px map-value map '{"map": "cone"}'
px cones-on-distance cones '{"method": "distance", "cones": "relaxed"}'
px cones-value cones '{"method": "cone", "cones": "loose"}'
px unknown speed '{"speed": 2}'
# Objects.
bad shape-cylinder "objects.0.shape" 'objects.0.shape="cylinder"'
bad shape-missing "objects.0.shape" 'objects.0={"radius": 1}'
bad shape-number "objects.0.shape" 'objects.0.shape=7'
bad radius-zero "objects.0.radius" 'objects.0.radius=0'
bad radius-negative "objects.0.radius" 'objects.0.radius=-1'
bad radius-huge "objects.0.radius" 'objects.0.radius=1e308'
bad radius-tiny "objects.0.radius" 'objects.0.radius=1e-7'
bad radius-NaN "objects.0.radius" 'objects.0.radius=NaN'
bad radius-nan "objects.0.radius" 'objects.0.radius=nan'
bad radius-Infinity "objects.0.radius" 'objects.0.radius=Infinity'
bad radius-minus-inf "objects.0.radius" 'objects.0.radius=-inf'
bad radius-1e400 "objects.0.radius" 'objects.0.radius=1e400'
bad segments-two "objects.0.segments" 'objects.0.segments=2'
bad segments-2049 "objects.0.segments" 'objects.0.segments=2049'
hostile -n '-1' segments-2to64 "base.json: objects.0.segments" render base.json --set 'objects.0.segments=18446744073709551615'
hostile -n '-2147483648' segments-2to31 "base.json: objects.0.segments" render base.json --set 'objects.0.segments=2147483648'
bad segments-fraction "objects.0.segments" 'objects.0.segments=3.5'
bad rings-one "objects.0.rings" 'objects.0.rings=1'
bad plane-size-zero "objects.0.size" 'objects.0={"shape": "plane", "size": [0,2]}'
bad plane-tessellation-zero "objects.0.tessellation.0" 'objects.0={"shape": "plane", "tessellation": [0,1]}'
bad plane-tessellation-4096 "objects.0.tessellation.0" 'objects.0={"shape": "plane", "tessellation": [4096,1]}'
bad plane-uv-repeat-zero "objects.0.uv_repeat" 'objects.0={"shape": "plane", "uv_repeat": [0,1]}'
bad plane-uv-repeat-huge "objects.0.uv_repeat" 'objects.0={"shape": "plane", "uv_repeat": [1e5,1]}'
bad torus-minor-over-major "objects.0.minor_radius" 'objects.0={"shape": "torus", "minor_radius": 2}'
bad torus-major-zero "objects.0.major_radius" 'objects.0={"shape": "torus", "major_radius": 0}'
bad torus-sides-two "objects.0.sides" 'objects.0={"shape": "torus", "sides": 2}'
bad cube-size-negative "objects.0.size" 'objects.0={"shape": "cube", "size": -1}'
bad object-name-number "objects.0.name" 'objects.0.name=5'
bad object-cull "objects.0.cull" 'objects.0.cull="front"'
bad object-material-missing "objects.0.material" 'objects.0.material="nosuch"'
bad object-unknown "objects.0.colour" 'objects.0.colour=[1,0,0]'
bad sphere-with-file "objects.0.file" 'objects.0.file="tri.obj"'
bad transform-string "objects.0.transform" 'objects.0.transform="identity"'
bad scale-zero "objects.0.transform.scale" 'objects.0.transform={"scale": 0}'
bad scale-axis-zero "objects.0.transform.scale" 'objects.0.transform={"scale": [1,0,1]}'
bad scale-empty "objects.0.transform.scale" 'objects.0.transform={"scale": []}'
bad scale-huge "objects.0.transform.scale" 'objects.0.transform={"scale": 1e308}'
bad translate-far "objects.0.transform.translate" 'objects.0.transform={"translate": [1e7,0,0]}'
bad rotate-two "objects.0.transform.rotate" 'objects.0.transform={"rotate": [0,0]}'
bad transform-unknown "objects.0.transform.shear" 'objects.0.transform={"shear": [1,0,0]}'
bad second-object-radius "objects.1.radius" 'objects=[{"shape": "sphere"}, {"shape": "sphere", "radius": -2}]'
# A key given twice: the message names its full path.
scene dup-radius.json '[{"shape": "sphere", "radius": 1, "radius": 2}]'
hostile dup-object-radius "dup-radius.json: objects.0.radius" render dup-radius.json
scene dup-second.json '[{"shape": "cube"}, {"shape": "sphere", "radius": 1, "radius": 2}]'
hostile dup-second-object "dup-second.json: objects.1.radius" render dup-second.json
scene dup-scale.json '[{"shape": "sphere", "transform": {"scale": 1, "scale": 2}}]'
hostile dup-transform-scale "dup-scale.json: objects.0.transform.scale" render dup-scale.json
scene dup-fov.json '[{"shape": "sphere"}]'; sed -i 's/"resolution"/"fov_y": 40, "fov_y": 50, "resolution"/' dup-fov.json
hostile dup-camera-fov "dup-fov.json: camera.fov_y" render dup-fov.json
scene dup-ambient.json '[{"shape": "sphere"}]'; sed -i 's/"objects"/"ambient": [0,0,0], "ambient": [1,1,1], "objects"/' dup-ambient.json
hostile dup-top-level "dup-ambient.json: ambient" render dup-ambient.json
scene dup-diffuse.json '[{"shape": "sphere", "material": "m"}]' '{}' '{"m": {"diffuse": [1,0,0], "diffuse": [0,1,0]}}'
hostile dup-material-diffuse "dup-diffuse.json: materials.m.diffuse" render dup-diffuse.json
scene dup-material.json '[{"shape": "sphere", "material": "m"}]' '{}' '{"m": {}, "m": {"diffuse": [1,0,0]}}'
hostile dup-material "dup-material.json: materials.m" render dup-material.json
scene dup-size.json '[{"shape": "sphere"}]' '{"t": {"type": "checker", "size": [16,16], "size": [8,8]}}'
hostile dup-texture-size "dup-size.json: textures.t.size" render dup-size.json
scene dup-dir.json '[{"shape": "sphere"}]'; sed -i 's/"direction": \[0,0,-1\]/&, "direction": [0,-1,0]/' dup-dir.json
hostile dup-light-direction "dup-dir.json: lights.0.direction" render dup-dir.json
scene dup-clock.json '[{"shape": "sphere"}]'; sed -i 's/"objects"/"pipeline": {"clock_mhz": 500, "clock_mhz": 800}, "objects"/' dup-clock.json
hostile dup-pipeline-clock "dup-clock.json: pipeline.clock_mhz" render dup-clock.json
scene dup-mode.json '[{"shape": "sphere"}]'
sed -i 's/"objects"/"pipeline": {"normalize": {"mode": "exact"}, "normalize.mode": "rsqrt1"}, "objects"/' dup-mode.json
hostile dup-setting-two-spellings "dup-mode.json: pipeline.normalize.mode" render dup-mode.json
# Enumerations and strings of a megabyte, and with terminal control bytes: a short, clean message.
mb=$(head -c 1000000 /dev/zero | tr '\0' x)
printf '{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [32,24]},
  "lights": [{"type": "%s", "direction": [0,0,-1]}], "objects": [{"shape": "sphere"}]}' "$mb" >mb-type.json
hostile -s enum-1mb-light-type "mb-type.json: lights.0.type" render mb-type.json
scene mb-shape.json "[{\"shape\": \"$mb\"}]"
hostile -s enum-1mb-shape "mb-shape.json: objects.0.shape" render mb-shape.json
scene mb-path.json '[{"shape": "sphere", "material": "m"}]' '{}' "{\"m\": {\"path\": \"$mb\"}}"
hostile -s enum-1mb-material-path "mb-path.json: materials.m.path" render mb-path.json
scene mb-ref.json "[{\"shape\": \"sphere\", \"material\": \"$mb\"}]"
hostile -s missing-material-1mb-name "mb-ref.json: objects.0.material" render mb-ref.json
printf '{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [32,24], "fov_y": "%s"},
  "objects": [{"shape": "sphere"}]}' "$mb" >mb-fov.json
hostile -s number-given-1mb-string "mb-fov.json: camera.fov_y" render mb-fov.json
scene mb-key.json "[{\"shape\": \"sphere\", \"$mb\": 1}]"
hostile -s unknown-key-1mb "mb-key.json: objects.0" render mb-key.json
scene esc-cull.json '[{"shape": "sphere", "cull": "\u001b]0;owned\u0007\u001b[2J"}]'
hostile -s enum-escapes-json "esc-cull.json: objects.0.cull" render esc-cull.json
hostile -s enum-escapes-set "base.json: materials.m.path" render base.json --set $'materials.m.path=\x1b[31mred\x07'
hostile -s enum-escapes-wrap "base.json: textures.t.wrap" render base.json --set $'textures.t.wrap=\x1b]2;title\x07'
hostile -s unknown-key-escapes "base.json: camera" render base.json --set $'camera.\x1b[2J=1'
# Non-finite and malformed numbers written into the file: named by file and line.
for tok in nan Infinity -Infinity inf 0x10 +1 .5 01; do  # (NaN: hostile_test.sh)
  scene "lit-$tok.json" "[{\"shape\": \"sphere\", \"radius\": $tok}]"
  hostile "number-literal-$tok" "lit-$tok.json: line" render "lit-$tok.json"
done
# A literal beyond double's range is JSON, so the field is known: named.
scene ovf-radius.json '[{"shape": "sphere", "radius": -1e999}]'
hostile number-literal-overflow "ovf-radius.json: objects.0.radius" render ovf-radius.json
scene ovf-ambient.json '[{"shape": "sphere"}]'; sed -i 's/"objects"/"ambient": [0, 1e400, 0], "objects"/' ovf-ambient.json
hostile number-literal-overflow-colour "ovf-ambient.json: ambient" render ovf-ambient.json
# JSON text: BOM, trailing garbage, comments, invalid UTF-8 (in values and in the path).
{ printf '\xef\xbb\xbf'; cat base.json; } >bom.json
either bom 'bom\.json' '[[ -s out.exr ]]' render bom.json
{ cat base.json; printf ' trailing'; } >trail.json;    hostile trailing-garbage "trail.json: line" render trail.json
{ cat base.json; cat base.json; } >twice.json;         hostile two-documents "twice.json: line" render twice.json
{ cat base.json; printf '\0'; } >nul.json;             hostile trailing-nul "nul.json" render nul.json
{ printf '// a comment\n'; cat base.json; } >comment.json; hostile comment "comment.json: line" render comment.json
scene comma.json '[{"shape": "sphere",}]';             hostile trailing-comma "comma.json: line" render comma.json
scene utf8.json $'[{"shape": "sphere", "name": "ball\xff\xfe"}]'
hostile -U invalid-utf8-in-value "utf8.json: line" render utf8.json
hostile -U invalid-utf8-in-enum "base.json: objects.0.shape" render base.json --set $'objects.0.shape=sph\xffere'
hostile -U invalid-utf8-in-key "base.json: camera" render base.json --set $'camera.zo\xffom=1'
hostile -U invalid-utf8-in-file-name "base.json: textures.t.file" render base.json \
  --set 'textures.t={"type": "image", "file": "x.png"}' --set $'textures.t.file=a\xffb.png'
cp base.json $'bad\xff.json'
hostile -U -a bad invalid-utf8-scene-path "camera.fov_y" render $'bad\xff.json' --set camera.fov_y=0
# A good scene under a name that is not UTF-8, with --stats: the statistics (JSON, UTF-8)
# hold the name with the byte replaced, rather than fail after the render.
cp base.json $'good\xff.json'
renders stats-invalid-utf8-scene-path render $'good\xff.json' --stats out-stats.json
# Scene files that are no files.
mkdir -p folder.json
hostile -a folder -n "invalid JSON" scene-is-folder "folder.json" render folder.json
hostile -a folder -n "invalid JSON" reference-scene-is-folder "folder.json" S reference folder.json -o out.exr
hostile -a folder -n "invalid JSON" parallax-bench-scene-is-folder "folder.json" S parallax-bench folder.json --json out.json
hostile scene-is-device "/dev/null" render /dev/null
mkfifo fifo.json
hostile scene-is-fifo "fifo.json" render fifo.json
hostile scene-missing "nosuch.json" render nosuch.json
hostile scene-empty-path "scene" render ''

# ------------------------------------------------------------------------------------------
# 2. Meshes
# ------------------------------------------------------------------------------------------
mesh() {  # mesh NAME FILE [-m KB]: a scene of mesh FILE is refused naming it (-m: under `big`)
  local name=$1 file=$2
  scene "m-$name.json" "[{\"shape\": \"mesh\", \"file\": \"$file\"}]"
  if [[ ${3:-} == -m ]]; then
    hostile -m "$4" -a "m-$name.json: objects.0.file" "mesh-$name" "$file" big render "m-$name.json" -o out.exr
  else
    hostile -a "m-$name.json: objects.0.file" "mesh-$name" "$file" render "m-$name.json"
  fi
}
tri='v 0 0 0\nv 1 0 0\nv 0 1 0\n'
noise() {  # noise N SEED: the same N pseudo-random bytes every run
  "$py" -c 'import random, sys; random.seed(int(sys.argv[2])); sys.stdout.buffer.write(bytes(random.getrandbits(8) for _ in range(int(sys.argv[1]))))' "$@"
}
# Lines assimp's OBJ reader is lenient about, by the format's habit: a vertex short of a
# coordinate (read as 0), lines it does not know (skipped), "nan" as a texture
# coordinate (read as 0). Refused or rendered finite, either is recorded.
mesh_either() {  # mesh_either NAME FILE
  scene "m-$1.json" "[{\"shape\": \"mesh\", \"file\": \"$2\"}]"
  either "mesh-$1" "m-$1\.json: objects\.0\.file" '[[ -s out.exr ]]' render "m-$1.json"
}
printf "${tri}f 1 2 3\nv 0 0 1\nv 1 0 1\nv 0 1\n" >cut.obj;  mesh_either obj-truncated-vertex cut.obj
printf 'v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >inf.obj;  mesh obj-inf inf.obj
printf 'v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >ovf.obj; mesh obj-float32-overflow ovf.obj
printf 'v 2e6 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >far.obj;  mesh obj-beyond-1e6 far.obj
printf "${tri}f 1 2 4294967296\n" >idx32.obj;               mesh obj-index-2to32 idx32.obj
printf "${tri}f 1 2 2147483648\n" >idx31.obj;               mesh obj-index-2to31 idx31.obj
printf "${tri}f 1 2 18446744073709551615\n" >idx64.obj;     mesh obj-index-2to64 idx64.obj
printf "${tri}f -1 -2 -9\n" >negidx.obj;                    mesh obj-negative-index negidx.obj
printf "${tri}f 0 1 2\n" >zeroidx.obj;                      mesh obj-index-zero zeroidx.obj
printf "${tri}f\n" >f0.obj;                                 mesh obj-face-no-vertex f0.obj
printf "${tri}f 1\n" >f1.obj;                               mesh obj-face-one-vertex f1.obj
printf "${tri}f 1 2\n" >f2.obj;                             mesh obj-face-two-vertices f2.obj
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' >flat.obj;    mesh obj-zero-area flat.obj
printf "${tri}f 1 1 1\n" >same.obj;                         mesh obj-repeated-vertex same.obj
printf "${tri}l 1 2 3\np 1\n" >lines.obj;                   mesh obj-lines-and-points lines.obj
printf "$tri" >verts.obj;                                   mesh obj-no-faces verts.obj
{ printf "${tri}f 1 2 3\n"; noise 2000 1; } >tail.obj; mesh_either obj-garbage-after-header tail.obj
printf "${tri}vn nan 0 1\nf 1//1 2//1 3//1\n" >nanvn.obj;  mesh obj-nan-normal nanvn.obj
printf "${tri}vt nan 0\nf 1/1 2/1 3/1\n" >nanvt.obj;       mesh_either obj-nan-uv nanvt.obj
ply() { printf 'ply\nformat %s 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\nelement face %s\nproperty list uchar int vertex_indices\nend_header\n' "$@"; }
{ ply binary_little_endian 3 1; noise 7 2; } >bin.ply;   mesh ply-binary-truncated bin.ply
{ ply binary_little_endian 3 1; noise 400 3; } >rnd.ply; mesh ply-binary-garbage rnd.ply
{ ply binary_little_endian 4000000000 1; head -c 64 /dev/zero; } >huge.ply
# (Not under AddressSanitizer: assimp asks for 48 GB at once, which ASan's allocator
# answers by aborting where the plain one throws; the plain build's run holds the case.)
((asan)) || mesh ply-4e9-vertices huge.ply -m 256000
{ ply ascii 3 1; printf '0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n'; } >oob.ply;      mesh ply-index-out-of-range oob.ply
{ ply ascii 3 1; printf '0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n'; } >neg.ply;     mesh ply-negative-index neg.ply
{ ply ascii 3 1; printf '0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n'; } >nan.ply;    mesh ply-nan nan.ply
{ ply ascii 3 0; printf '0 0 0\n1 0 0\n0 1 0\n'; } >noface.ply;            mesh ply-no-faces noface.ply
{ ply ascii 3 1; printf '0 0 0\n1 0 0\n0 1 0\n2 0 1\n'; } >f2.ply;         mesh ply-face-two-vertices f2.ply
# glTF: a buffer that is not there, an accessor far longer than its buffer; a GLB of noise.
gltf() { printf '{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36, "uri": "%s"}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": %s, "type": "VEC3",
                 "min": [0,0,0], "max": [1,1,0]}]}' "$@"; }
gltf nosuch.bin 3 >nobuf.gltf;                                          mesh gltf-missing-buffer nobuf.gltf
gltf "data:application/octet-stream;base64,$(head -c 36 /dev/zero | base64 -w0)" 1000000000 >count.gltf
mesh gltf-accessor-count count.gltf -m 256000
{ printf 'glTF\x02\x00\x00\x00\x00\x10\x00\x00'; noise 4000 4; } >noise.glb; mesh glb-garbage noise.glb
# STL: ASCII cut short, a binary count past the file, a NaN, zero area.
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n' >cut.stl; mesh stl-ascii-truncated cut.stl
stl() { "$py" -c 'import struct, sys
count, tris = int(sys.argv[1]), [[float(v) for v in t.split(",")] for t in sys.argv[2:]]
sys.stdout.buffer.write(b"\0" * 80 + struct.pack("<I", count) +
  b"".join(struct.pack("<12fH", 0, 0, 1, *t, 0) for t in tris))' "$@"; }
stl 100000000 0,0,0,1,0,0,0,1,0 >count.stl;      mesh stl-binary-count count.stl -m 256000
stl 1 0,0,0,nan,0,0,0,1,0 >nan.stl;              mesh stl-binary-nan nan.stl
stl 1 0,0,0,1,0,0,2,0,0 >flat.stl;               mesh stl-zero-area flat.stl
scene m-dev.json '[{"shape": "mesh", "file": "/dev/zero"}]'; hostile mesh-is-device "m-dev.json: objects.0.file" render m-dev.json
scene m-empty.json '[{"shape": "mesh", "file": ""}]';       hostile mesh-empty-path "m-empty.json: objects.0.file" render m-empty.json
# A mesh without texture coordinates under a path that reads them: refused naming the
# material or object, or rendered with a warning.
uvless() {  # uvless NAME MATERIAL-JSON
  scene "uv-$1.json" '[{"shape": "mesh", "file": "tri.obj", "material": "m"}]' \
    '{"h": {"type": "value-noise", "size": [16,16]}}' "{\"m\": $2}"
  either "mesh-without-uv-$1" 'materials\.m|objects\.0' 'grep -qi warn stderr && [[ -s out.exr ]]' render "uv-$1.json"
}
uvless texture '{"texture": "h"}'
uvless bump-tangent '{"path": "bump-tangent", "height_map": "h"}'
uvless bump-classic '{"path": "bump-classic", "height_map": "h"}'
uvless parallax '{"path": "parallax", "height_map": "h"}'

# ------------------------------------------------------------------------------------------
# 3. Images
# ------------------------------------------------------------------------------------------
tex() {  # tex SCENE FILE [MATERIAL-JSON]: a sphere of that material (default: FILE as its texture)
  local m=${3:-'{"texture": "t"}'}
  scene "$1" '[{"shape": "sphere", "material": "m"}]' "{\"t\": {\"type\": \"image\", \"file\": \"$2\"}}" "{\"m\": $m}"
}
img() {  # img NAME FILE [-m KB]: FILE as a colour texture is refused naming it (-m: under `big`)
  local name=$1 file=$2
  tex "i-$name.json" "$file"
  if [[ ${3:-} == -m ]]; then
    hostile -m "$4" -a "i-$name.json: textures.t.file" "image-$name" "$file" big render "i-$name.json" -o out.exr
  else
    hostile -a "i-$name.json: textures.t.file" "image-$name" "$file" render "i-$name.json"
  fi
}
img png-crc-ihdr crc-ihdr.png
img png-crc-idat crc-idat.png
img png-crc-ancillary crc-text.png
img png-no-iend noiend.png
img png-zero-width zerow.png
img png-palette-overflow badpal.png
img png-bit-depth baddepth.png
img png-interlace badinterlace.png
img png-short-idat shortidat.png
img png-filter-type badfilter.png
img png-16000-claimed claim16k.png -m 256000
img exr-no-colour-channel depth-only.exr
img exr-nan nan.exr
img exr-half-inf inf-half.exr
img exr-window-huge window-huge.exr -m 256000
img jpeg-truncated trunc.jpg
img jpeg-no-header nohead.jpg
cp h16.exr exr-named.png;  img exr-named-png exr-named.png
cp h16.png png-named.exr;  img png-named-exr png-named.exr
cp good.jpg jpg-named.png; img jpeg-named-png jpg-named.png
# A paletted PNG with indices past its palette never gives two different frames.
tex pal.json badpal.png
S render pal.json -o pal1.exr >/dev/null 2>&1; r1=$?
S render pal.json -o pal2.exr >/dev/null 2>&1; r2=$?
if [[ $r1 -eq 2 && $r2 -eq 2 && ! -e pal1.exr ]] || { [[ $r1 -eq 0 && $r2 -eq 0 ]] && cmp -s pal1.exr pal2.exr; }; then
  ((passes++))
else echo "FAIL png-palette-overflow-deterministic: exits $r1, $r2, frames differ or half written"; ((failures++)); fi
# Good but unusual images: a 1x1 PNG works as a texture, a bump and a parallax height map.
tex one-tex.json one.png
renders one-by-one-texture render one-tex.json
tex one-bump.json one.png '{"path": "bump-classic", "height_map": "t"}'
renders one-by-one-bump render one-bump.json
tex one-px.json one.png '{"path": "parallax", "height_map": "t"}'
renders one-by-one-parallax render one-px.json
cp rgb16.png pic.jpg
tex pngjpg.json pic.jpg
either png-named-jpg 'pic\.jpg' '[[ -s out.exr ]]' render pngjpg.json
tex alpha.json alpha.png '{"path": "bump-classic", "height_map": "t"}'
either height-map-alpha 'alpha\.png' '[[ -s out.exr ]]' render alpha.json
either precompute-height-alpha 'alpha\.png' '[[ -s out.exr ]]' S precompute normalmap alpha.png -o out.exr
# Height maps.
tex nanh.json nan-height.exr '{"path": "bump-classic", "height_map": "t"}'
hostile -a "nanh.json: " height-map-nan "nan-height.exr" render nanh.json
tex nanpx.json nan-height.exr '{"path": "parallax", "height_map": "t"}'
hostile -a "nanpx.json: " parallax-height-nan "nan-height.exr" render nanpx.json
for map in normalmap distancemap refinedmap conemap relaxedconemap; do
  hostile "precompute-$map-nan" "nan-height.exr" S precompute $map nan-height.exr -o out.exr
  hostile "precompute-$map-minus-inf" "neg-inf-height.exr" S precompute $map neg-inf-height.exr -o out.exr
done
hostile -m 256000 precompute-normalmap-16000-claimed "claim16k.png" big precompute normalmap claim16k.png -o out.exr
hostile precompute-crc-idat "crc-idat.png" S precompute normalmap crc-idat.png -o out.exr
hostile precompute-palette-overflow "badpal.png" S precompute distancemap badpal.png -o out.exr
hostile precompute-jpeg-truncated "trunc.jpg" S precompute normalmap trunc.jpg -o out.exr
hostile precompute-exr-window-huge "window-huge.exr" S precompute refinedmap window-huge.exr -o out.exr

# ------------------------------------------------------------------------------------------
# 4. Command-line options
# ------------------------------------------------------------------------------------------
# Every numeric option, given what is no number of its range: exit 2 naming the option.
opt() {  # opt OPTION VALUES COMMAND...: each value of VALUES in turn as OPTION's value
  local option=$1 values=$2 v
  shift 2
  for v in $values; do
    [[ $v == "''" ]] && v=
    hostile "option $([[ $2 == precompute ]] && echo "$3" || echo "$2") $option=${v:-(empty)}" "$option" "$@" "$option" "$v"
  done
}
floats="nan NaN inf -inf 1e400 '' ten"
ints="nan 1e400 '' 1.5"
opt --heat-max "$floats" S render pb.json -o out.exr --heat-map heat.png
opt --fail "$floats" S compare a.exr a.exr --diff out.exr
opt --failpercent "$floats" S compare a.exr a.exr --diff out.exr
opt --hardfail "$floats" S compare a.exr a.exr --diff out.exr
opt --azimuth "$floats" S parallax-bench pb.json --rays 2 --elevations 30 --json out.json
opt --elevations "$floats" S parallax-bench pb.json --rays 2 --json out.json
opt --rays "$ints 0" S parallax-bench pb.json --elevations 30 --json out.json
opt --scale "$floats -1" S precompute normalmap h16.png -o out.exr
opt --k "$floats 0" S precompute normalmap h16.png -o out.exr
opt --slices "$ints 0" S precompute distancemap h16.png -o out.exr
opt --slices "$ints" S precompute conemap h16.png -o out.exr
opt --levels "$ints 0" S precompute conemap h16.png -o out.exr
opt --min-elevation "$floats 0" S precompute relaxedconemap h16.png -o out.exr
opt --slices "$ints" S precompute refinedmap h16.png -o out.exr
opt --min-elevation "$floats 0" S precompute refinedmap h16.png -o out.exr
opt --margin "$floats -1" S precompute refinedmap h16.png -o out.exr
opt --azimuths "$ints 0" S precompute refinedmap h16.png -o out.exr
opt --elevations "$ints 0" S precompute refinedmap h16.png -o out.exr
opt --rays-per-texel "$ints 9" S precompute refinedmap h16.png -o out.exr
opt --show "$ints -1" S timing-check t.log
# --set: malformed keys and values.
for s in 'noequals' '=5' '' 'camera..fov_y=3' '.camera=1' 'camera.=1' 'objects.-1.radius=1' 'objects.x.radius=1' \
  'objects.99999999999999999999.radius=1' 'camera.position.0.x=1' 'camera.resolution.1.0=1'; do
  hostile "set '$s'" "--set" render base.json --set "$s"
done
bad set-empty-value "camera.fov_y" 'camera.fov_y='
bad set-empty-setting "pipeline.normalize.mode" 'pipeline.normalize.mode='
bad set-unknown-setting "pipeline.normalize.nosuch" 'pipeline.normalize.nosuch=1'
# Inspection options: malformed, and wholly outside the frame (32x24) or the triangles (342).
for r in '1,2,3,4,5' 'a,b,c,d' '10,10,5,5' '100,100,200,200' '-1,0,4,4' '' 'nan,0,4,4' '0,0,1e400,4' '1,2,3,4,'; do
  hostile -x t.vcd -x t.gtkw "trace-region '$r'" "--trace-region" render base.json --vcd t.vcd --trace-region "$r"
done
for r in '' '1..' '..5' 'a..b' '-1..3' '1...3' 'nan..3' '1..18446744073709551616' '100000..200000'; do
  hostile -x t.vcd -x t.gtkw "trace-triangles '$r'" "--trace-triangles" render base.json --vcd t.vcd --trace-triangles "$r"
done
hostile engine-unknown "--engine" render base.json --engine gpu
hostile engine-empty "--engine" render base.json --engine ''
hostile engine-case "--engine" render base.json --engine SystemC
hostile render-empty-output "--output" S render base.json -o '' --preview out.png
hostile reference-empty-output "--output" S reference base.json -o ''
hostile precompute-empty-output "--output" S precompute normalmap h16.png -o ''
hostile empty-preview "--preview" S render base.json -o out.exr --preview ''
hostile empty-stats "--stats" render base.json --stats ''
hostile empty-heat-map "--heat-map" S render pb.json -o out.exr --heat-map ''
hostile compare-layer "--layer" S compare a.exr b.exr --layer XYZ --diff out.exr
hostile precompute-form "--form" S precompute normalmap h16.png -o out.exr --form bogus
hostile precompute-wrap "--wrap" S precompute normalmap h16.png -o out.exr --wrap mirror
hostile unknown-option "--no-such-option" render base.json --no-such-option
# CLI11's refusals said by the command they are about, as every other message
hostile -s compare-one-frame "shadetlm compare: b is required" S compare a.exr
hostile -s no-command "shadetlm: A subcommand is required" S
# -V as --version (exit 0, the same first line)
ok=0
S -V >stdout 2>stderr && [[ -n $(head -1 stdout) && $(head -1 stdout) == "$(S --version | head -1)" ]] && ok=1
((ok)) || echo "FAIL version-short-flag: -V does not print the version"
verdict $ok
# A mistyped setting: the nearest key, not a list of every one
hostile -s setting-typo "did you mean pipeline.normalize.mode?" S render base.json -o out.exr --set pipeline.normalise.mode=exact
# (CLI11 says a subcommand is required; it does not name the word it did not know)
hostile precompute-unknown-map "unknown command 'bogusmap'" S precompute bogusmap h16.png -o out.exr

# ------------------------------------------------------------------------------------------
# 5. Outputs: equal to an input, to each other, a folder, under a regular file
# ------------------------------------------------------------------------------------------
# (Frames must end in .exr: the frame collides with an EXR input, a texture, never the scene.)
tex exrtex.json h16.exr
ln -sf h16.exr link.exr
hostile -u h16.exr output-is-texture "--output" S render exrtex.json -o h16.exr
hostile -u h16.exr output-is-texture-dot "--output" S render exrtex.json -o ./h16.exr
hostile -u h16.exr output-is-texture-link "--output" S render exrtex.json -o link.exr
hostile -u base.json preview-is-scene "--preview" S render base.json -o out.exr --preview base.json
hostile -u base.json stats-is-scene "--stats" render base.json --stats base.json
hostile -u base.json timing-log-is-scene "--timing-log" render base.json --timing-log base.json
hostile -u base.json timeline-is-scene "--timeline" render base.json --timeline base.json
cp base.json scene.vcd
hostile -u scene.vcd -a "input" vcd-is-scene "--vcd" render scene.vcd --vcd scene.vcd
hostile -u h16.exr reference-output-is-texture "--output" S reference exrtex.json -o h16.exr
tex rgbtex.json rgb16.png
hostile -u rgb16.png preview-is-texture "--preview" S render rgbtex.json -o out.exr --preview rgb16.png
scene tri.json '[{"shape": "mesh", "file": "tri.obj"}]'
hostile -u tri.obj stats-is-mesh "--stats" S render tri.json -o out.exr --preview out.png --stats tri.obj
hostile -u pb.json parallax-bench-json-is-scene "--json" S parallax-bench pb.json --rays 2 --elevations 30 --json pb.json
hostile -u h16.exr normalmap-over-height "--output" S precompute normalmap h16.exr -o h16.exr
hostile -u h16.png distancemap-over-height "--output" S precompute distancemap h16.png -o h16.png
hostile -u h16.exr conemap-over-height "--output" S precompute conemap h16.exr -o ./h16.exr
hostile -u h16.exr refinedmap-over-height "--output" S precompute refinedmap h16.exr -o h16.exr
hostile -u tri.obj normalmap-over-surface "--output" S precompute normalmap h16.png --surface tri.obj -o tri.obj
hostile -u a.exr compare-diff-is-a "--diff" S compare a.exr b.exr --diff a.exr
hostile -u b.exr compare-diff-is-b "--diff" S compare a.exr b.exr --diff b.exr
hostile -u a.exr compare-images-under-file "--images" S compare a.exr b.exr --images a.exr/x
hostile -x x.exr output-equals-timing-log "--timing-log" S render base.json -o x.exr --timing-log x.exr
hostile -x x.exr output-equals-stats "--stats" S render base.json -o x.exr --stats ./x.exr
hostile -x x.png preview-equals-heat-map "--heat-map" S render pb.json -o out.exr --preview x.png --heat-map x.png
hostile -x x.json stats-equals-timeline "--timeline" render base.json --stats x.json --timeline x.json
hostile -x x.png -x x.exr reference-preview-not-png "--preview" S reference base.json -o x.exr --preview x.exr
mkdir -p dir.exr dir.png dir.json dir.log
hostile reference-output-folder "--output" S reference base.json -o dir.exr
hostile preview-folder "--preview" S render base.json -o out.exr --preview dir.png
hostile stats-folder "--stats" render base.json --stats dir.json
hostile heat-map-folder "--heat-map" S render pb.json -o out.exr --heat-map dir.png
hostile timing-log-folder "--timing-log" render base.json --timing-log dir.log
hostile diff-folder "--diff" S compare a.exr b.exr --diff dir.exr
hostile distancemap-output-folder "--output" S precompute distancemap h16.png -o dir.exr
hostile parallax-bench-json-folder "--json" S parallax-bench pb.json --rays 2 --elevations 30 --json dir.json
hostile output-under-file "--output" S render base.json -o base.json/out.exr --preview out.png
hostile output-deep-under-file "--output" S render base.json -o base.json/a/b/out.exr --preview out.png
hostile preview-under-file "--preview" S render base.json -o out.exr --preview base.json/out.png
hostile stats-under-file "--stats" render base.json --stats base.json/s.json
hostile reference-output-under-file "--output" S reference base.json -o h16.png/out.exr
hostile normalmap-output-under-file "--output" S precompute normalmap h16.png -o h16.png/out.exr
hostile diff-under-file "--diff" S compare a.exr b.exr --diff a.exr/d.exr
hostile parallax-bench-json-under-file "--json" S parallax-bench pb.json --rays 2 --elevations 30 --json pb.json/x.json
hostile output-is-device "--output" S render base.json -o /dev/full --preview out.png

# ------------------------------------------------------------------------------------------
# 6. Non-finite values at render time: refused naming the field, or a finite frame
# ------------------------------------------------------------------------------------------
rs() { render base.json --stats out.json "$@"; }
finite light-radiance-overflow 'lights\.0' rs --set 'lights.0.color=[1e30,1e30,1e30]' --set lights.0.intensity=1e12
finite reference-light-radiance-overflow 'lights\.0' S reference base.json -o out.exr \
  --set 'lights.0.color=[1e30,1e30,1e30]' --set lights.0.intensity=1e12
finite diffuse-times-light 'materials\.m|lights\.0' rs --set 'materials.m.diffuse=[3e38,3e38,3e38]' --set lights.0.intensity=1e6
finite ambient-times-ambient 'ambient' rs --set 'ambient=[3e38,3e38,3e38]' --set 'materials.m.ambient=[3e38,3e38,3e38]'
finite reference-ambient-times-ambient 'ambient' S reference base.json -o out.exr \
  --set 'ambient=[3e38,3e38,3e38]' --set 'materials.m.ambient=[3e38,3e38,3e38]'
finite specular-sum 'materials\.m|lights' rs --set 'materials.m.specular=[3e38,3e38,3e38]' --set materials.m.shininess=0 \
  --set 'lights=[{"type": "directional", "direction": [0,0,-1], "intensity": 1e6}, {"type": "point", "position": [0,0,4], "intensity": 1e6}]'
finite texture-times-diffuse 'textures\.t|materials\.m' rs --set 'textures.t.colors=[[3e38,3e38,3e38],[3e38,3e38,3e38]]' \
  --set 'materials.m.diffuse=[3e38,3e38,3e38]' --set materials.m.texture=t
finite background-3e38 'background' rs --set 'background=[3e38,3e38,3e38]'
finite float16-light 'lights\.0|number_format' rs --set pipeline.number_format=float16 --set 'lights.0.color=[1e5,1e5,1e5]'
finite float16-background 'background|number_format' rs --set pipeline.number_format=float16 --set 'background=[1e6,1e6,1e6]'
finite fixed-diffuse 'materials\.m|number_format' rs --set pipeline.number_format=fixed:2.8 --set 'materials.m.diffuse=[1e3,1e3,1e3]'
finite parallax-deep 'materials\.p' render pb.json --stats out.json --set materials.p.parallax.depth=1e6
finite bump-square-steep 'materials\.m' rs --set 'materials.m={"path": "bump-square", "height_map": "t", "height_scale": 1e6, "square_k": 1e-6}'
finite depth-range 'camera' rs --set camera.near=1e-9 --set camera.far=1e12

# ------------------------------------------------------------------------------------------
# 7. The fuzzers' findings (testbenches/fuzz/regressions/<target>/, scripts/fuzz.sh): each
# image replayed as a scene's texture — refused or rendered, never a crash or, under
# AddressSanitizer, a leak. (Their first byte picks the type: 0 PNG, 1 JPEG, 2 EXR.)
for f in "$src"/testbenches/fuzz/regressions/image/*; do
  [[ -e $f ]] || continue
  ext=(png jpg exr)
  e=${ext[$(( $(od -An -tu1 -N1 "$f") % 3 ))]}
  tail -c +2 "$f" >"found.$e"
  scene found.json '[{"shape": "sphere", "material": "m"}]' "{\"t\": {\"type\": \"image\", \"file\": \"found.$e\"}}" '{"m": {"texture": "t"}}'
  either "fuzz-image-$(basename "$f")" 'found' '[[ -s out.exr ]]' render found.json
done

echo "$passes passed, $failures failed"
[[ $failures -eq 0 && $passes -ge 180 ]]
