#!/usr/bin/env bash
# Fault injection against the output contract (src/shadetlm/core/output.hpp): a full disk, signals,
# SIGKILL, an allocation limit, special files as inputs and outputs that collide. Every
# output appears whole or not at all, never beside a temporary "<path>.tmp.<host>.<pid>", and the
# outputs of one run appear together.
# Usage: fault_test.sh SHADETLM SOURCE_DIR
set -u
bin=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d)
background=""  # the pid of a render running in the background, if any
trap '[[ -n $background ]] && kill -KILL "$background" 2>/dev/null; rm -rf "$tmp"' EXIT
cd "$tmp"
passes=0
failures=0

# begin NAME ... problem TEXT ... end: one case, failed by any problem.
begin() { case_name=$1; ok=1; : >"$tmp/stderr"; }
problem() { echo "FAIL $case_name: $*"; ok=0; }
end() {
  if ((ok)); then ((passes++)); else sed 's/^/    /' "$tmp/stderr" | head -4; ((failures++)); fi
}
fresh() { rm -rf "$1"; mkdir -p "$1"; }  # fresh DIR: an empty folder
temporaries() { find "$1" -name '*.tmp.*' -printf '%f ' 2>/dev/null; }  # temporaries under DIR
contents() { find "$1" -mindepth 1 -printf '%P ' 2>/dev/null; }       # everything under DIR
names_one_of() {  # names_one_of "TEXT...": stderr contains one of them
  local t
  for t in $1; do grep -qF -- "$t" "$tmp/stderr" && return 0; done
  return 1
}
snapshot() {  # snapshot DIR: its entries and the checksums of its files
  (cd "$1" && find . -mindepth 1 | sort && find . -type f -exec sha256sum {} + | sort)
}
scene() {  # scene FILE JSON-of-the-objects-array [JSON-of-the-textures]: a scene around them
  printf '{"camera": {"position": [0,0,4], "target": [0,0,0], "resolution": [32,24]},
           "lights": [{"type": "directional", "direction": [0,0,-1]}],
           "textures": %s, "objects": %s}' "${3:-{\}}" "$2" >"$1"
}
tex() {  # tex SCENE FILE: a scene whose sphere wears image FILE
  scene "$1" '[{"shape": "sphere", "material": "m"}]' "{\"t\": {\"type\": \"image\", \"file\": \"$2\"}}"
  sed -i 's/"objects"/"materials": {"m": {"texture": "t"}}, "objects"/' "$1"
}

# Inputs shared by the cases: frames of the demo to compare, a 32x32 height map.
fresh in
(cd in && "$bin" render --set 'camera.resolution=[32,32]' -o r.exr >/dev/null &&
  "$bin" reference --set 'camera.resolution=[32,32]' -o g.exr --preview h.png >/dev/null) ||
  { echo "setup failed"; exit 1; }
parallax=$src/scenes/parallax/steps.json
asan=0  # a build under AddressSanitizer (scripts/test.sh --sanitize): libasan linked in
ldd "$bin" | grep -q libasan && asan=1
small=(--set 'camera.resolution=[64,48]')
tiny=(--set 'camera.resolution=[4,4]')

# --- 1, 2. A full disk (a file size limit): exit 1, the message names the output and not
# its temporary, and no output of the run exists afterwards, nor any temporary. The
# outputs of a run appear together: when one fails, those that fit do not appear either.

# limit_between "FITTING..." "FAILING..." COMMAND...: a file size limit that the FITTING
# outputs of COMMAND fit and the FAILING ones exceed, from the sizes of an unlimited run;
# 0 if there is none.
limit_between() {
  local fitting=$1 failing=$2 f size max=0 min=
  shift 2
  fresh m
  (cd m && "$@") >/dev/null 2>&1 || { echo 0; return; }
  for f in $fitting; do size=$(stat -c %s "m/$f") || { echo 0; return; }; ((size > max)) && max=$size; done
  for f in $failing; do
    size=$(stat -c %s "m/$f") || { echo 0; return; }
    [[ -z $min ]] || ((size < min)) && min=$size
  done
  ((max < min)) && echo $(((max + min) / 2)) || echo 0
}
# full_disk NAME LIMIT "NAMED..." COMMAND...: COMMAND run in an empty folder with writes
# past LIMIT bytes failing; its message names one of NAMED. (Output goes through pipes,
# which the limit does not reach.)
full_disk() {
  # Under AddressSanitizer (scripts/test.sh --sanitize) a write that fails after a
  # SystemC simulation is not tried: unwinding the exception past SystemC's coroutine
  # stacks makes ASan report a false stack-buffer-overflow (its sigaltstack interceptor,
  # google/sanitizers#189). The plain build's run holds these cases.
  if ((asan)) && [[ " $* " == *" render "* && " $* " != *" --engine loop "* ]]; then
    echo "note: $1 skipped under AddressSanitizer"
    return
  fi
  begin "$1"
  local limit=$2 named=$3 rc
  shift 3
  if ((limit <= 0)); then problem "setup: no file size limit separates the outputs"; end; return; fi
  fresh c  # (as long a name as m: the .gtkw holds its folder's path)
  (cd c && prlimit --fsize="$limit" "$@" 2>&1 >/dev/null) | cat >"$tmp/stderr"
  rc=${PIPESTATUS[0]}
  # A failed write exits 1; compare's 1 means "the frames differ", so its trouble is 2.
  local want=1
  [[ " $* " == *" compare "* ]] && want=2
  ((rc == want)) || problem "exit $rc, expected $want (limit $limit bytes)"
  names_one_of "$named" || problem "message names none of: $named"
  ! grep -qF .tmp. "$tmp/stderr" || problem "message names a temporary"
  local left; left=$(contents c)
  [[ -z $left ]] || problem "left behind: $left"
  end
}
all=(-o out.exr --preview out.png --stats out.json --vcd out.vcd --timeline out.tl.json --timing-log out.log)
full_disk disk-render-exr 2000 out.exr "$bin" render "${small[@]}" -o out.exr
full_disk disk-render-preview 2000 "out.exr out.png" "$bin" render "${small[@]}" -o out.exr --preview out.png
full_disk disk-render-heat-map 1000 "out.exr heat.png" "$bin" render "$parallax" "${small[@]}" -o out.exr --heat-map heat.png
cmd=("$bin" render "${tiny[@]}" -o out.exr --stats out.json)
full_disk disk-render-stats "$(limit_between out.exr out.json "${cmd[@]}")" out.json "${cmd[@]}"
cmd=("$bin" render "${small[@]}" -o out.exr --vcd out.vcd)
full_disk disk-render-vcd "$(limit_between "out.exr out.gtkw" out.vcd "${cmd[@]}")" out.vcd "${cmd[@]}"
cmd=("$bin" render "${small[@]}" -o out.exr --timeline out.tl.json)
full_disk disk-render-timeline "$(limit_between out.exr out.tl.json "${cmd[@]}")" out.tl.json "${cmd[@]}"
cmd=("$bin" render "${small[@]}" -o out.exr --timing-log out.log)
full_disk disk-render-timing-log "$(limit_between out.exr out.log "${cmd[@]}")" out.log "${cmd[@]}"
full_disk disk-render-everything 2000 "out.exr out.png out.json out.vcd out.gtkw out.tl.json out.log" \
  "$bin" render "${small[@]}" "${all[@]}"
cmd=("$bin" render "${small[@]}" -o out.exr --preview out.png --stats out.json)
full_disk together-render-frame-fails "$(limit_between "out.png out.json" out.exr "${cmd[@]}")" out.exr "${cmd[@]}"
cmd=("$bin" render "${small[@]}" -o out.exr --preview out.png --vcd out.vcd --trace-region 0,0,1,1)
full_disk together-render-frame-fails-after-vcd "$(limit_between "out.png out.vcd out.gtkw" out.exr "${cmd[@]}")" \
  out.exr "${cmd[@]}"
cmd=("$bin" render "${tiny[@]}" -o out.exr --timing-log out.log)
full_disk together-render-frame-fails-after-timing-log "$(limit_between out.log out.exr "${cmd[@]}")" out.exr "${cmd[@]}"
full_disk disk-reference-exr 2000 ref.exr "$bin" reference "${small[@]}" -o ref.exr
full_disk disk-reference-preview 2000 "ref.exr ref.png" "$bin" reference "${small[@]}" -o ref.exr --preview ref.png
cmd=("$bin" reference "${small[@]}" -o ref.exr --preview ref.png)
full_disk together-reference "$(limit_between ref.png ref.exr "${cmd[@]}")" ref.exr "${cmd[@]}"
images="im-new.png im-reference.png im-diff.png im-heat.png"
compare=("$bin" compare "$tmp/in/r.exr" "$tmp/in/g.exr" --failpercent 100)  # a passing comparison
full_disk disk-compare-diff 2000 d.exr "${compare[@]}" --diff d.exr
full_disk disk-compare-images 50 "$images" "${compare[@]}" --images im
cmd=("${compare[@]}" --diff d.exr --images im)
full_disk together-compare "$(limit_between "$images" d.exr "${cmd[@]}")" d.exr "${cmd[@]}"
for map in normalmap distancemap conemap refinedmap; do
  full_disk "disk-precompute-$map" 1000 map.exr "$bin" precompute "$map" "$tmp/in/h.png" -o map.exr
done
full_disk disk-parallax-bench-json 1000 pb.json \
  "$bin" parallax-bench "$parallax" --rays 2 --elevations 60 --json pb.json

# --- 3. Signals at known points of a run. SHADETLM_PAUSE_AT (src/shadetlm/core/output.hpp) makes the
# run stop itself (SIGSTOP) on reaching a point; the test waits for that stop, sends its
# signal and lets the run go on. No delay is guessed, so a faster, slower or busier
# machine changes nothing. The run's folder holds an older run's outputs first: a run
# ended by SIGINT or SIGTERM leaves them exactly as they were (its outputs are one
# group, committed together or not at all), and no temporary.
long=(render --set 'camera.resolution=[160,120]' -o out.exr --preview out.png --stats out.json
  --vcd out.vcd --timeline out.tl.html --trace-region 40,30,80,60 --compare-reference)
points=("loading the scene" "pipeline" "pipeline half" "golden model" "writing" "commit")
# The older run's outputs (another resolution, so every file differs from this run's).
fresh old
(cd old && "$bin" "${long[@]}" --set 'camera.resolution=[96,72]') >/dev/null 2>&1 ||
  { echo "setup failed: the older run"; exit 1; }
outputs_of() { (cd "$1" && find . -mindepth 1 -not -name '*.tmp.*' | sort && find . -type f -not -name '*.tmp.*' -exec sha256sum {} + | sort); }

# start_paused POINT: the run in the background in folder k (a copy of old), SIGINT and
# SIGTERM at their defaults (a script's background jobs ignore SIGINT), stopping itself
# at POINT; false if it ends instead or has not stopped within five minutes.
start_paused() {
  rm -rf k && cp -a old k
  (cd k && exec env --default-signal=INT,TERM,HUP SHADETLM_PAUSE_AT="$1" "$bin" "${long[@]}") >/dev/null 2>"$tmp/stderr" &
  background=$!
  local i state
  for ((i = 0; i < 15000; i++)); do
    read -r _ _ state _ 2>/dev/null <"/proc/$background/stat" || return 1
    [[ $state == T || $state == t ]] && return 0
    [[ $state == Z ]] && return 1
    sleep 0.02
  done
  return 1
}
finish() { wait "$background" 2>/dev/null; local rc=$?; background=""; return $rc; }  # its exit status
signal_case() {  # signal_case SIGNAL POINT: SIGNAL sent to the run stopped at POINT
  begin "sig$1-at-${2// /-}"
  local signal=$1 rc left
  start_paused "$2" || problem "the run never stopped at '$2'"
  kill -s "$signal" "$background" 2>/dev/null
  kill -CONT "$background" 2>/dev/null
  finish; rc=$?
  ((rc == 128 + $(kill -l "$signal"))) || problem "exit $rc, expected $((128 + $(kill -l "$signal"))) (SIG$signal)"
  left=$(temporaries k)
  [[ -z $left ]] || problem "temporaries left: $left"
  [[ $(outputs_of k) == "$(outputs_of old)" ]] || problem "the older run's outputs changed: some of this run's appeared"
  end
}
for signal in INT TERM HUP; do
  for point in "${points[@]}"; do signal_case "$signal" "$point"; done
done
# The pause itself is checked: a run let go on at a point it stopped at finishes whole.
begin paused-run-finishes
start_paused commit || problem "the run never stopped at 'commit'"
kill -CONT "$background" 2>/dev/null
finish || problem "exit $?, expected 0"
for f in out.exr out.png out.json out.vcd out.gtkw out.tl.html; do
  cmp -s "k/$f" "old/$f" && problem "$f is still the older run's"
done
end

# --- 4. SIGKILL leaves its temporaries, and the older outputs as they were; the next
# run writing the same outputs removes them, says so ("left by a run that was killed"),
# succeeds and leaves no temporary.
killed_case() {  # killed_case POINT [leaves]: the run killed outright at POINT (leaving temporaries), then a short one
  begin "sigKILL-at-${1// /-}"
  local rc left
  start_paused "$1" || problem "the run never stopped at '$1'"
  kill -KILL "$background" 2>/dev/null
  finish
  [[ $(outputs_of k) == "$(outputs_of old)" ]] || problem "the older run's outputs changed"
  left=$(temporaries k)
  [[ ${2:-} != leaves || -n $left ]] || problem "no temporaries left at '$1', where every output has one"
  (cd k && "$bin" render "${small[@]}" -o out.exr --preview out.png --stats out.json --vcd out.vcd --timeline out.tl.html) \
    >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  ((rc == 0)) || problem "the next run: exit $rc, expected 0"
  if [[ -n $left ]] && ! grep -q "left by a run that was killed" "$tmp/stdout" "$tmp/stderr"; then
    problem "the next run does not mention the temporaries left ($left)"
  fi
  left=$(temporaries k)
  [[ -z $left ]] || problem "temporaries left after the next run: $left"
  end
}
killed_case "pipeline half"
killed_case "golden model" leaves
killed_case commit leaves

# A temporary is "<output>.tmp.<host>.<pid>": a dead process's on this host is removed,
# another host's is left alone (on a folder a cluster shares, its writer may still run).
begin other-hosts-temporaries-kept
mkdir -p h
host=$(hostname | tr -c 'A-Za-z0-9\n-' '-')
: >h/out.exr.tmp.$host.999999999
: >h/out.exr.tmp.another-node.1
(cd h && "$bin" render "${small[@]}" -o out.exr) >"$tmp/stdout" 2>"$tmp/stderr" || problem "render failed"
[[ ! -e h/out.exr.tmp.$host.999999999 ]] || problem "this host's dead temporary was not removed"
[[ -e h/out.exr.tmp.another-node.1 ]] || problem "another host's temporary was removed"
end

# --- 5. An allocation limit (ulimit -v) that a 1920x1080 render cannot live with: exit 1
# or 2 with a message, no crash, no output, no temporary. The limits are found here:
# from the least a 64x48 render needs up to just under what the 1920x1080 one needs.
# (Not under AddressSanitizer, scripts/test.sh --sanitize: it reserves terabytes of
# address space for its shadow memory, so that no ulimit -v leaves it room to start.)
big=(render --set 'camera.resolution=[1920,1080]' -o out.exr --preview out.png)
if ((asan)); then
  echo "note: the allocation limits are skipped under AddressSanitizer"
else
  runs_within() {  # runs_within KB COMMAND...: COMMAND succeeds in an empty folder within KB of memory
    local kb=$1
    shift
    fresh a
    # (600 s: a guard against a hang, not a judge of speed; a loaded machine takes minutes)
    { (cd a && ulimit -v "$kb" && timeout 600 "$bin" "$@") >/dev/null 2>&1; } 2>/dev/null
  }
  least=20000
  while ((least < 2000000)) && ! runs_within $least render "${small[@]}" -o out.exr --preview out.png; do
    ((least += 5000))
  done
  enough=200000
  while ((enough < 8000000)) && ! runs_within $enough "${big[@]}"; do ((enough *= 2)); done
  low=$least
  while ((enough - low > 250)); do  # the least the big render needs, within 250 KB
    mid=$(((low + enough) / 2))
    if runs_within $mid "${big[@]}"; then enough=$mid; else low=$mid; fi
  done
  echo "note: a 64x48 render runs within $least KB, the 1920x1080 one within $enough KB"
  for kb in $least $(((least + enough) / 2)) $((enough - 4000)) $((enough - 1000)) $((enough - 500)); do
    ((kb >= least)) || continue
    begin "alloc-limit-${kb}k"
    fresh a
    { (cd a && ulimit -v "$kb" && exec timeout 600 "$bin" "${big[@]}") >/dev/null 2>"$tmp/stderr"; } 2>/dev/null
    rc=$?
    if ((rc == 0)); then echo "note: alloc-limit-${kb}k: the render fitted after all; not counted"; continue; fi
    ((rc == 1 || rc == 2)) || problem "exit $rc, expected 1 or 2"
    grep -q "shadetlm:" "$tmp/stderr" || problem "no 'shadetlm:' message"
    left=$(contents a)
    [[ -z $left ]] || problem "left behind: $left"
    end
  done
fi

# --- 6. Special files as inputs (a FIFO, /dev/zero, a folder, a symlink loop, a missing
# file) as the scene, a mesh, an image texture and a frame to compare: exit 2 at once,
# the message names the file, no output.
fresh s
cd s
mkfifo fifo.json fifo.obj fifo.png fifo.exr
mkdir dir.json dir.obj dir.png dir.exr
ln -s /dev/zero zero.obj
ln -s /dev/zero zero.png
for e in json obj png exr; do ln -s "loop-b.$e" "loop-a.$e"; ln -s "loop-a.$e" "loop-b.$e"; done
cd "$tmp"
special() {  # special NAME PATH COMMAND...: run in s; killed if blocked (120 s: a refusal takes milliseconds, a loaded machine more)
  begin "$1"
  local path=$2 rc
  shift 2
  rm -f s/out.exr
  (cd s && timeout 120 "$@") >/dev/null 2>"$tmp/stderr"
  rc=$?
  if ((rc == 124)); then problem "blocked (killed after 120 s)"; else ((rc == 2)) || problem "exit $rc, expected 2"; fi
  grep -qF -- "$path" "$tmp/stderr" || problem "message does not name $path"
  [[ ! -e s/out.exr ]] || problem "output written"
  end
}
for kind in fifo zero dir loop missing; do
  case $kind in
    fifo) name=fifo ;; zero) name=zero ;; dir) name=dir ;; loop) name=loop-a ;; missing) name=missing ;;
  esac
  scenefile=$name.json
  [[ $kind == zero ]] && scenefile=/dev/zero
  special "scene-$kind" "$scenefile" "$bin" render "$scenefile" -o out.exr
  scene "s/mesh-$kind.json" "[{\"shape\": \"mesh\", \"file\": \"$name.obj\"}]"
  special "mesh-$kind" "$name.obj" "$bin" render "mesh-$kind.json" -o out.exr
  tex "s/texture-$kind.json" "$name.png"
  special "texture-$kind" "$name.png" "$bin" render "texture-$kind.json" -o out.exr
  frame=$name.exr
  [[ $kind == zero ]] && frame=/dev/zero
  special "compare-$kind" "$frame" "$bin" compare "$frame" "$tmp/in/g.exr" --diff out.exr
done
special compare-reference-fifo fifo.exr "$bin" compare "$tmp/in/g.exr" fifo.exr --diff out.exr

# --- 7. Outputs that collide with an input, another output, a folder or nothing: exit 2
# naming the option, before anything is written: the folder's files untouched, no new
# file or folder.
fresh x
scene x/s.json '[{"shape": "sphere"}]'
cp in/g.exr x/a.exr
cp in/r.exr x/b.exr
cp in/g.exr x/x.exr
cp in/g.exr x/h.exr
cp in/h.png x/t.png
tex x/t.json h.exr
python3 - x/t.json <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["textures"]["p"] = {"type": "image", "file": "t.png"}
s["materials"]["n"] = {"texture": "p"}
s["objects"].append({"shape": "sphere", "material": "n", "radius": 0.5})
json.dump(s, open(sys.argv[1], "w"))
PY
mkdir x/folder.exr
echo text >x/plain
collision() {  # collision NAME "OPTIONS..." COMMAND...: run in x, rejected naming one of OPTIONS
  begin "$1"
  local options=$2 rc before
  shift 2
  before=$(snapshot x)
  (cd x && "$@") >/dev/null 2>"$tmp/stderr"
  rc=$?
  ((rc == 2)) || problem "exit $rc, expected 2"
  names_one_of "$options" || problem "message names none of: $options"
  [[ $(snapshot x) == "$before" ]] || problem "the folder changed: now $(contents x)"
  end
}
# (The frame's path ends in .exr and the preview's in .png, so those two cannot collide;
# an input can: an EXR texture, a PNG texture.)
collision output-is-a-texture --output "$bin" render t.json -o h.exr
collision preview-is-a-texture --preview "$bin" render t.json -o out.exr --preview t.png
collision stats-is-the-output "--stats --output" "$bin" render s.json -o x.exr --stats x.exr
collision heat-map-is-the-preview "--heat-map --preview" \
  "$bin" render "$parallax" "${small[@]}" -o out.exr --preview x.png --heat-map x.png
collision stats-is-the-gtkw "--stats --vcd" "$bin" render s.json -o out.exr --vcd x.vcd --stats x.gtkw
collision precompute-output-is-the-height "--output" "$bin" precompute normalmap h.exr -o h.exr
collision diff-is-the-frame --diff "$bin" compare a.exr b.exr --diff a.exr
collision diff-is-an-image "--diff --images" "$bin" compare a.exr b.exr --images p --diff p-diff.png
collision output-is-a-folder --output "$bin" render s.json -o folder.exr
collision stats-is-a-folder --stats "$bin" render s.json -o out.exr --stats folder.exr
collision output-folder-is-a-file --output "$bin" render s.json -o plain/x.exr
collision output-empty --output "$bin" render s.json -o ''
collision rejected-scene-makes-no-folder camera.fov_y "$bin" render s.json --set camera.fov_y=500 -o newdir/x.exr
collision rejected-collision-makes-no-folder "--stats --output" \
  "$bin" render s.json -o newdir/x.exr --stats newdir/x.exr
collision missing-scene-makes-no-folder missing.json "$bin" render missing.json -o newdir/x.exr

echo "$passes passed, $failures failed"
[[ $failures -eq 0 ]]
