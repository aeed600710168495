#!/usr/bin/env bash
# The scripts as a user meets them with bad arguments and bad files (issue 38): each stops
# with exit 2 and one line on stderr, "<script>: <what>", naming the option or the file,
# never a traceback, never a hang (60 s and it counts as one), and leaves the folder it
# ran in as it was: no partial output, temporary or progress file. Fake programs stand in
# for shadetlm where a render has to fail or to come back wrong; SHADETLM renders a
# one-run sweep at 16 x 12 (that the good paths still work). No case depends on speed.
# Usage: scripts_test.sh SHADETLM SOURCE_DIR
set -u
bin=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
work=$tmp/work  # where the scripts run, and their files: compared before and after each case
mkdir -p "$work/tmp" "$tmp/fakes"
export TMPDIR=$work/tmp  # the reports' temporaries land in the compared folder too
unset SHADETLM_MAP_CACHE SHADETLM REGEN_GOLDEN
export PYTHONDONTWRITEBYTECODE=1  # no scripts/__pycache__ in the source tree
passes=0
failures=0
scripts=$src/scripts
# The interpreter itself, not a version manager's shim, and without site (-S): the scripts
# need only the standard library, and those two were most of the time of a case.
python=$(python3 -c 'import sys; print(sys.executable)')

snapshot() {  # every entry under the work folder; files with their size and time
  find "$work" -mindepth 1 \( -type d -printf '%y %P\n' \) -o -printf '%y %P %s %T@\n' | sort
}

# run SCRIPT.py ARGS...: the script, in the work folder, stdin $stdin (else nothing), killed
# after 300 s (a guard against a hang: the cases take well under a second unloaded); its
# stdout and stderr into $tmp.
run() {
  (cd "$work" && timeout 300 "$python" -S "$scripts/$1" "${@:2}" <"${stdin:-/dev/null}" >"$tmp/stdout" 2>"$tmp/stderr")
}

# refused NAME STATUS WHAT SCRIPT.py ARGS...: the script exits STATUS (not killed by run's guard) with one
# line on stderr that starts with its name and contains WHAT, no traceback, and the work
# folder as it was.
refused() {
  local name=$1 want=$2 what=$3
  shift 3
  local script=${1%.py} before after rc lines problems=()
  before=$(snapshot)
  run "$@"
  rc=$?
  after=$(snapshot)
  mapfile -t lines <"$tmp/stderr"
  if ((rc == 124)); then problems+=("hung: killed after 300 s"); elif ((rc != want)); then
    problems+=("exit $rc, expected $want"); fi
  [[ ${lines[*]} == *Traceback* ]] && problems+=("a traceback")
  ((${#lines[@]} == 1)) || problems+=("${#lines[@]} lines on stderr, expected 1")
  [[ ${lines[0]:-} == "$script: "* || ${lines[0]:-} == "$script.py: "* ]] || problems+=("stderr does not start with '$script: '")
  [[ ${lines[*]} == *"$what"* ]] || problems+=("stderr does not name '$what'")
  [[ $before == "$after" ]] || problems+=("the folder changed: $(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -3 | tr '\n' ' ')")
  if ((${#problems[@]})); then
    echo "FAIL $name: $(IFS=';'; echo "${problems[*]}")"; sed 's/^/    /' "$tmp/stderr" | head -5; ((failures++))
  else
    ((passes++))
  fi
}
bad() { refused "$1" 2 "$2" "${@:3}"; }  # bad NAME WHAT SCRIPT.py ARGS...: refused with exit 2
ok() {  # ok NAME SCRIPT.py ARGS...: the script exits 0 within 60 s, no traceback
  local name=$1
  shift
  run "$@"
  local rc=$?
  if ((rc != 0)) || grep -q Traceback "$tmp/stderr"; then
    echo "FAIL $name: exit $rc"; sed 's/^/    /' "$tmp/stderr" | head -5; ((failures++))
  else
    ((passes++))
  fi
}
expect() {  # expect NAME CONDITION...: the condition holds
  if "${@:2}"; then ((passes++)); else echo "FAIL $1: not ${*:2}"; ((failures++)); fi
}

# Fake programs: input refused (exit 2), a crash (exit 1, and by a signal), no stats, broken stats.
fake() { printf '#!/bin/sh\n%s\n' "$2" >"$tmp/fakes/$1" && chmod +x "$tmp/fakes/$1"; }
fake refuses 'echo "shadetlm: camera.resolution: not W,H" >&2; exit 2'
fake crashes 'echo "a warning" >&2; echo "shadetlm: internal error: boom" >&2; echo "more" >&2; exit 1'
fake killed 'kill -KILL $$'  # (no core file)
fake no-stats 'exit 0'
fake broken-stats 'while [ $# -gt 0 ]; do [ "$1" = --stats ] && printf "{" >"$2"; shift; done; exit 0'
printf 'not a program\n' >"$tmp/fakes/text" && chmod +x "$tmp/fakes/text"
f=$tmp/fakes

# Fixtures (in the work folder: no case may change them).
header=run,family,scene,configuration,wall_s,frame_cycles,pixels,add,mul,div,sqrt,rsqrt,lut,fetch,line,err_max,err_rmse,err_psnr,wall_q1_s,wall_q3_s,wall_min_s,wall_max_s,wall_runs
config='normal_interp.mode=perspective;normalize.mode=exact;number_format=float32'
row() {  # row RUN WALL_S ERR_RMSE [CONFIG]: a sweep row of the sphere
  echo "$1,normal,golden/sphere/scene.json,${4:-$config},$2,1000,100,1,2,3,4,5,6,0,0,1e-06,$3,140,$2,$2,$2,$2,1"
}
csv() { { echo "$header"; for r in "${@:2}"; do echo "$r"; done; } >"$work/$1"; }
csv good.csv "$(row 0 0.01 1e-07)"
csv run-abc.csv "$(row abc 0.01 1e-07)"
csv run-far.csv "$(row 99999 0.01 1e-07)"
csv run-neg.csv "$(row -1 0.01 1e-07)"
csv run-twice.csv "$(row 0 0.01 1e-07)" "$(row 0 0.01 1e-07)"
csv wrong-scene.csv "$(row 0 0.01 1e-07 | sed 's/sphere/torus/')"
csv short.csv "0,normal,golden/sphere/scene.json"
csv wall-abc.csv "$(row 0 abc 1e-07)"
csv rmse-inf.csv "$(row 0 0.01 inf)"
csv config-bad.csv "$(row 0 0.01 1e-07 'what=ever')"
csv header-only.csv
prow() {  # prow RUN CONFIG: a sweep row of the parallax scene
  echo "$1,parallax,golden/parallax-steps/scene.json,$2,0.01,1000,100,1,2,3,4,5,6,0,0,1e-06,1e-05,100,0.01,0.01,0.01,0.01,1"
}
cone='materials.carved.method=cone;materials.carved.max_iterations=64'
csv cones.csv "$(prow 0 "$cone;pipeline.number_format=float32")" \
  "$(prow 1 "$cone;materials.carved.cones=relaxed;pipeline.number_format=float32")" \
  "$(prow 2 "$cone;materials.carved.cones=relaxed;pipeline.number_format=float16")"
csv same-label.csv "$(prow 0 "$cone")" "$(prow 1 'materials.carved.max_iterations=64;materials.carved.method=cone')"
printf 'run,family\n0,normal\n' >"$work/columns.csv"
printf '%s\n0,normal\0,x\n' "$header" >"$work/nul.csv"
sweep() {  # sweep FOLDER SHARDS ARGS: a results folder with its manifest, ARGS its run options
  mkdir -p "$work/$1/shards"
  printf '{"kind": "sweep", "shards": %s, "args": %s}\n' "$2" "$3" >"$work/$1/manifest.json"
}
sweep merge-nul 1 '[]' && cp "$work/nul.csv" "$work/merge-nul/shards/sweep-0-of-1.csv"
sweep merge-abc 1 '[]' && cp "$work/run-abc.csv" "$work/merge-abc/shards/sweep-0-of-1.csv"
sweep merge-columns 1 '[]' && cp "$work/columns.csv" "$work/merge-columns/shards/sweep-0-of-1.csv"
sweep merge-twice 2 '[]' && cp "$work/good.csv" "$work/merge-twice/shards/sweep-0-of-2.csv" &&
  cp "$work/good.csv" "$work/merge-twice/shards/sweep-1-of-2.csv"
sweep merge-missing 2 '[]' && cp "$work/good.csv" "$work/merge-missing/shards/sweep-0-of-2.csv"
sweep merge-args-string 1 '"--match x"' && cp "$work/good.csv" "$work/merge-args-string/shards/sweep-0-of-1.csv"
sweep merge-args-bad 1 '["--resolution", "0,0"]' && cp "$work/good.csv" "$work/merge-args-bad/shards/sweep-0-of-1.csv"
sweep merge-huge 1000000000 '[]'
mkdir -p "$work/merge-garbage" && printf '{"kind": "sweep", "shards": ' >"$work/merge-garbage/manifest.json"
mkdir -p "$work/merge-regress" && printf '{"kind": "regress", "shards": 1}\n' >"$work/merge-regress/manifest.json"
# Slurm submissions (scripts/slurm.py's manifest), each with one field wrong.
slurm_manifest() {  # slurm_manifest FOLDER PYTHON_EDIT: the manifest of a 2-shard sweep, edited
  mkdir -p "$work/$1"
  "$python" -c "import json, sys
m = {'kind': 'sweep', 'shards': 2, 'runs': 5, 'args': [], 'program': '/bin/true', 'root': '/', 'repeats': 0,
     'max_parallel': None, 'sbatch': [], 'jobs': []}
$2
json.dump(m, open(sys.argv[1], 'w'))" "$work/$1/manifest.json"
}
slurm_manifest slurm-huge "m['shards'] = 10 ** 9"
slurm_manifest slurm-args-string "m['args'] = '--match x'"
slurm_manifest slurm-jobs "m['jobs'] = [3]"
slurm_manifest slurm-repeats "m['repeats'] = 'x'"
slurm_manifest slurm-runs "m['runs'] = None"
slurm_manifest slurm-shards-float "m['shards'] = 2.0"
slurm_manifest slurm-sweep-sh "del m['program']"
# Golden scenes that are not (regress.py), and a regression shard that is not.
mkdir -p "$work/root-bad/golden/sphere" "$work/root-lacking/golden/sphere" "$work/regress-shard/shards"
printf '{"accuracy": ' >"$work/root-bad/golden/sphere/golden.json"
"$python" -c "import json, sys
s = json.load(open(sys.argv[1])); del s['regression']; json.dump(s, open(sys.argv[2], 'w'))" \
  "$src/golden/sphere/golden.json" "$work/root-lacking/golden/sphere/golden.json"
printf '{"kind": "regress", "shards": 1}\n' >"$work/regress-shard/manifest.json"
printf '[{"scene": "sphere"' >"$work/regress-shard/shards/regress-0-of-1.json"
printf 'not a zip\n' >"$work/not.npz"
printf '# doc\n' >"$work/doc.md"
printf '$enddefinitions $end\n' >"$work/trace.vcd"
printf '$timescale 1 ps $end\n$enddefinitions $end\n#2000\n' >"$work/old.vcd"  # a render's VCD of before: ps
printf '{"clock_mhz": 500, "elaborated": ["a"], "blocks": {"a": {"latency": 1}}}\n' >"$work/stats-a.json"

# --- sweep.py: options.
one='^normal golden/sphere/scene.json .*perspective;.*mode=exact;'  # one run
bad sweep-resolution-0 "--resolution" sweep.py "$bin" "$src" --shard 0/1 --results r --resolution 0,0
bad sweep-resolution-huge "--resolution" sweep.py "$bin" "$src" --list --resolution 20000,10
bad sweep-resolution-text "--resolution" sweep.py "$bin" "$src" --list --resolution big
bad sweep-match "--match" sweep.py "$bin" "$src" --list --match '('
bad sweep-shard "--shard" sweep.py "$bin" "$src" --shard 2/2 --results r
bad sweep-shard-huge "--shard" sweep.py "$bin" "$src" --shard 0/1000000000 --results r
bad sweep-shard-results "--results" sweep.py "$bin" "$src" --shard 0/1
bad sweep-shards-0 "--shards" sweep.py "$bin" "$src" --plan p --shards 0
bad sweep-shards-huge "--shards" sweep.py "$bin" "$src" --plan p --shards 1000000000
bad sweep-repeats "--repeats" sweep.py "$bin" "$src" --merge merge-abc --repeats -1
bad sweep-time-text "--time" sweep.py "$bin" "$src" --time x
bad sweep-time-0 "--time" sweep.py "$bin" "$src" --time 0
bad sweep-no-mode "--list" sweep.py "$bin" "$src"
bad sweep-no-program "nobin" sweep.py ./nobin "$src" --shard 0/1 --results r --match "$one"
bad sweep-no-checkout "nowhere" sweep.py "$bin" nowhere --shard 0/1 --results r --match "$one"
bad sweep-results-file "doc.md/shards" sweep.py "$bin" "$src" --shard 0/1 --results doc.md --match "$one"
bad sweep-plan-file "doc.md/x" sweep.py "$bin" "$src" --plan doc.md/x
# --time: the rows on stdin.
stdin=$work/run-abc.csv bad sweep-time-run-abc "stdin: row 1: run 'abc'" sweep.py "$bin" "$src" --time 1
stdin=$work/run-far.csv bad sweep-time-run-far "row 1: run '99999'" sweep.py "$bin" "$src" --time 1
stdin=$work/run-neg.csv bad sweep-time-run-negative "row 1: run '-1'" sweep.py "$bin" "$src" --time 1
stdin=$work/run-twice.csv bad sweep-time-twice "row 2: run 0 is there twice" sweep.py "$bin" "$src" --time 1
stdin=$work/wrong-scene.csv bad sweep-time-scene "golden/torus" sweep.py "$bin" "$src" --time 1
stdin=$work/short.csv bad sweep-time-short "row 1 has fewer fields" sweep.py "$bin" "$src" --time 1
stdin=$work/columns.csv bad sweep-time-columns "no column scene" sweep.py "$bin" "$src" --time 1
stdin=$work/nul.csv bad sweep-time-nul "stdin" sweep.py "$bin" "$src" --time 1
bad sweep-time-empty "stdin" sweep.py "$bin" "$src" --time 1
# --merge: shards and manifests that are not a sweep's.
bad sweep-merge-nul "merge-nul/shards/sweep-0-of-1.csv" sweep.py "$bin" "$src" --merge merge-nul
bad sweep-merge-run "merge-abc/shards/sweep-0-of-1.csv: row 1" sweep.py "$bin" "$src" --merge merge-abc
bad sweep-merge-columns "merge-columns/shards/sweep-0-of-1.csv" sweep.py "$bin" "$src" --merge merge-columns
bad sweep-merge-twice "sweep-1-of-2.csv: row 1: run 0 is there twice" sweep.py "$bin" "$src" --merge merge-twice
bad sweep-merge-missing "1 of 2 shards missing (1)" sweep.py "$bin" "$src" --merge merge-missing
bad sweep-merge-args-string "merge-args-string/manifest.json" sweep.py "$bin" "$src" --merge merge-args-string
bad sweep-merge-args-bad "merge-args-bad/manifest.json: args: --resolution" sweep.py "$bin" "$src" --merge merge-args-bad
bad sweep-merge-huge "merge-huge/manifest.json" sweep.py "$bin" "$src" --merge merge-huge
bad sweep-merge-garbage "merge-garbage/manifest.json" sweep.py "$bin" "$src" --merge merge-garbage
bad sweep-merge-regress "merge-regress holds a regress" sweep.py "$bin" "$src" --merge merge-regress
bad sweep-merge-none "nowhere/manifest.json" sweep.py "$bin" "$src" --merge nowhere
# --shard: the program fails, or comes back without its stats; no .progress, no folder left.
bad sweep-render-refused "shadetlm: camera.resolution: not W,H" sweep.py "$f/refuses" "$src" --shard 0/1 --results r --match "$one"
refused sweep-render-crash 1 "shadetlm: internal error: boom" sweep.py "$f/crashes" "$src" --shard 0/1 --results r --match "$one"
refused sweep-render-signal 1 "signal 9" sweep.py "$f/killed" "$src" --shard 0/1 --results r/deeper --match "$one"
bad sweep-no-stats "no readable stats" sweep.py "$f/no-stats" "$src" --shard 0/1 --results r --match "$one"
bad sweep-broken-stats "no readable stats" sweep.py "$f/broken-stats" "$src" --shard 0/1 --results r --match "$one"
bad sweep-not-a-program "cannot run it" sweep.py "$f/text" "$src" --shard 0/1 --results r --match "$one"
# SIGTERM (scancel, timeout) in the middle of a shard: the render killed, nothing left.
# The fake render says it started through a FIFO, then blocks on another that nobody
# writes, until the shard's end kills it: the test waits for that event, no delay guessed.
mkfifo "$f/started" "$f/hold"
fake waits "echo \$\$ >$f/waits.pid; echo \$\$ >$f/started; exec cat $f/hold"
before=$(snapshot)
(cd "$work" && exec "$python" -S "$scripts/sweep.py" "$f/waits" "$src" --shard 0/1 --results r --match "$one" \
   </dev/null >"$tmp/stdout" 2>"$tmp/stderr") &
shard=$!
read -r -t 300 _ <>"$f/started"  # (read-write: opening it never blocks; the read waits for the render)
expect sweep-sigterm-render-started [ -s "$f/waits.pid" ]
expect sweep-sigterm-progress-kept [ -e "$work/r/shards/sweep-0-of-1.progress" ]
kill -TERM $shard
wait $shard
rc=$?
expect sweep-sigterm-status [ $rc == 143 ]
render_gone() { [[ -s $f/waits.pid ]] && ! kill -0 "$(<"$f/waits.pid")" 2>/dev/null; }
expect sweep-sigterm-render-killed render_gone
expect sweep-sigterm-nothing-left [ "$(snapshot)" == "$before" ]
expect sweep-sigterm-quiet [ ! -s "$tmp/stderr" ]

# The good path, with the real program: plan, one shard, merge, time again.
ok sweep-plan sweep.py "$bin" "$src" --plan sweep-ok --match "$one" --resolution 16,12 --no-map-cache
expect sweep-plan-one [ "$(cat "$tmp/stdout")" == 1 ]
ok sweep-shard sweep.py "$bin" "$src" --shard 0/1 --results sweep-ok --match "$one" --resolution 16,12 --no-map-cache
ok sweep-merge sweep.py "$bin" "$src" --merge sweep-ok --repeats 0
expect sweep-merged [ "$(wc -l <"$work/sweep-ok/sweep.csv")" == 2 ]
# The run's silicon: an area and an energy a pixel, both positive.
expect sweep-silicon python3 -c 'import csv, sys; r = next(csv.DictReader(open(sys.argv[1])))
assert float(r["area_mm2"]) > 0 and float(r["energy_nj_per_pixel"]) > 0, r' "$work/sweep-ok/sweep.csv"
expect sweep-no-progress [ -z "$(find "$work/sweep-ok" -name '*.progress' -o -name '*.tmp.*')" ]
stdin=$work/sweep-ok/sweep.csv ok sweep-time sweep.py "$bin" "$src" --time 1 --resolution 16,12 --no-map-cache
expect sweep-timed grep -q ',normal,golden/sphere/scene.json,' "$tmp/stdout"

# --- regress.py
bad regress-no-program "nobin" regress.py ./nobin "$src" out
bad regress-not-a-program "cannot run it" regress.py "$f/text" "$src" out --scene sphere
bad regress-no-checkout "nowhere" regress.py "$bin" nowhere out
bad regress-scene "nosuch" regress.py "$bin" "$src" out --scene nosuch
bad regress-shard "--shard" regress.py "$bin" "$src" out --shard 1/1
bad regress-shard-merge "--merge" regress.py "$bin" "$src" out --shard 0/1 --merge
bad regress-golden-json "root-bad/golden/sphere/golden.json" regress.py "$bin" root-bad out
bad regress-golden-lacking "root-lacking/golden/sphere/golden.json" regress.py "$bin" root-lacking out
bad regress-out-file "doc.md" regress.py "$bin" "$src" doc.md --scene sphere
bad regress-merge-shard "regress-shard/shards/regress-0-of-1.json" regress.py "$bin" "$src" regress-shard --merge
bad regress-merge-sweep "merge-missing holds a sweep" regress.py "$bin" "$src" merge-missing --merge
bad regress-merge-none "nowhere/manifest.json" regress.py "$bin" "$src" nowhere --merge
bad regress-unknown-option "--frobnicate" regress.py "$bin" "$src" out --frobnicate

# --- slurm.py (no case reaches Slurm)
bad slurm-status-huge "slurm-huge/manifest.json" slurm.py status slurm-huge
bad slurm-merge-args-string "slurm-args-string/manifest.json" slurm.py merge slurm-args-string
bad slurm-status-jobs "jobs" slurm.py status slurm-jobs
bad slurm-merge-repeats "repeats" slurm.py merge slurm-repeats
bad slurm-status-runs "runs" slurm.py status slurm-runs
bad slurm-status-shards-float "slurm-shards-float/manifest.json" slurm.py status slurm-shards-float
bad slurm-status-sweep-sh "not submitted by scripts/slurm.py" slurm.py status slurm-sweep-sh
bad slurm-status-garbage "merge-garbage/manifest.json" slurm.py status merge-garbage
bad slurm-status-none "nowhere/manifest.json" slurm.py status nowhere
bad slurm-submit-shards "--shards" slurm.py submit sweep new --shards 0
bad slurm-submit-shards-text "--shards" slurm.py submit sweep new --shards many
bad slurm-submit-scene "--scene" slurm.py submit sweep new --scene sphere
bad slurm-command "frobnicate" slurm.py frobnicate new
bad slurm-no-results "results" slurm.py status

# --- plot.py: nothing drawn, no folder made.
bad plot-usage "usage" plot.py good.csv
bad plot-no-csv "nowhere.csv" plot.py nowhere.csv plots
bad plot-wall "row 1: wall_s is 'abc'" plot.py wall-abc.csv plots
bad plot-rmse "row 1: err_rmse is 'inf'" plot.py rmse-inf.csv plots
bad plot-config "row 1: 'what=ever'" plot.py config-bad.csv plots
bad plot-columns "no column scene" plot.py columns.csv plots
bad plot-empty "header-only.csv: no runs" plot.py header-only.csv plots
bad plot-nul "nul.csv" plot.py nul.csv plots
bad plot-same-label "would share the label 'cone 64'" plot.py same-label.csv plots
# Every point's label its own: classic and relaxed cones, the number format where not float32.
labels() {  # labels CSV: plot.py's label of each row, one a line
  (cd "$work" && "$python" -S -c 'import sys; sys.path.insert(0, sys.argv[1]); import plot
for r in plot.load(sys.argv[2]): print(r["label"])' "$scripts" "$1")
}
expect plot-labels-unique [ "$(labels cones.csv)" == $'cone 64\nrelaxed cone 64\nrelaxed cone 64 float16' ]

# --- sweep-findings.py: the prose's figures, from the rows (here: exact's operations
# 50 % above forward difference's on the sphere; the spans of the two runs).
frow() {  # frow RUN MODE ADDS CYCLES: a sphere run of that normalize mode and those additions
  echo "$1,normal,golden/sphere/scene.json,normal_interp.mode=perspective;normalize.mode=$2;number_format=float32,0.01,$4,100,$3,0,0,0,0,0,0,0,1e-06,1e-07,140,0.01,0.01,0.01,0.01,1"
}
csv findings.csv "$(frow 0 forward-difference 100 2000)" "$(frow 1 exact 150 1000)"
ok findings sweep-findings.py findings.csv
expect findings-ops grep -qF '| sphere | exact | 1000 | +50 % |' "$tmp/stdout"
expect findings-span grep -qF '| normal | sphere | 2 | 10.0 | 1000–2000 | 100–150 |' "$tmp/stdout"
bad findings-usage "usage" sweep-findings.py
bad calibrate-usage "usage" calibrate.py --x
bad operators-ops "--ops" operators.py --ops nothing
bad findings-wall "row 1: wall_s is 'abc'" sweep-findings.py wall-abc.csv

# --- The reports and helpers: their arguments.
bad scaling-usage "usage" scaling.py "$bin"
bad radicand-no-program "nobin" radicand-report.py ./nobin "$src"
bad format-no-program "nobin" format-report.py ./nobin "$src"
bad format-option "usage" format-report.py "$bin" "$src" --bumpy
bad skipping-option "usage" skipping-report.py "$bin" "$src" --dox
bad stability-no-checkout "nowhere" stability-report.py "$bin" nowhere out
bad golden-accuracy-workdir "nowork" golden-accuracy.py "$bin" "$src" nowork
bad parallax-real "nofile.png" parallax-report.py "$bin" "$src" "moon=nofile.png"
bad texture-photo "nophoto.png" texture-report.py "$bin" nophoto.png
bad bump-images "--images" bump-report.py "$bin" --images doc.md
bad doc-tables-usage "usage" doc-tables.py report.txt doc.md name x
bad doc-tables-no-doc "nodoc.md" doc-tables.py --run nodoc.md name 1 -- true
bad doc-tables-no-command "nocommand" doc-tables.py --run doc.md name 1 -- ./nocommand
bad bench-table-file "nofile.txt" bench-table.py nofile.txt doc.md
bad bench-table-counts "doc.md: no instruction counts" bench-table.py doc.md doc.md
bad dem-to-png-zip "not.npz" dem-to-png.py not.npz out.png
bad vcd-causality-stats "nostats.json" vcd-causality.py trace.vcd nostats.json
bad merge-vcd-timescale 'trace.vcd: its $timescale' merge-vcd.py trace.vcd trace.vcd out.vcd
bad merge-vcd-old "old.vcd: not a render's VCD of one time unit a cycle" merge-vcd.py old.vcd old.vcd out.vcd
bad vcd-causality-old 'old.vcd: not a VCD it can read: its $timescale is not 1 ns' vcd-causality.py old.vcd stats-a.json
bad silicon-report-usage "usage" silicon-report.py
bad silicon-report-root "doc.md: no golden" silicon-report.py "$bin" doc.md
bad golden-cycles-usage "usage" golden-cycles.py
bad block-share-args "stdin" block-share.py extra
bad make-stress-scenes-out "doc.md" make-stress-scenes.py doc.md

echo "$passes passed, $failures failed"
[[ $failures -eq 0 ]]
