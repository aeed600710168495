#!/usr/bin/env bash
# The command line as a user meets it: exit codes (0 ok, 2 bad input or failed
# comparison), messages that name the file and the field, and no output file when
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
check demo 0 "$bin" reference -o "$tmp/demo.exr" --preview "$tmp/demo.png"
[[ -s $tmp/demo.exr && -s $tmp/demo.png ]] && ((passes++)) || { echo "FAIL demo: no frame"; ((failures++)); }
check same 0 "$bin" compare "$tmp/demo.exr" "$tmp/demo.exr"
expect_output same PASS

# A different frame of the same scene: brighter light.
check brighter 0 "$bin" reference -o "$tmp/bright.exr" --set lights.0.intensity=2
check differs 2 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --diff "$tmp/diff.exr"
expect_output differs FAIL
[[ -s $tmp/diff.exr ]] && ((passes++)) || { echo "FAIL differs: no diff frame"; ((failures++)); }
check tolerated 0 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --layer Z --layer N
check tolerant 0 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --failpercent 100
check json 2 "$bin" compare "$tmp/bright.exr" "$tmp/demo.exr" --json
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
check no-command 2 "$bin"

# A mesh through assimp, from the scenes folder.
check mesh 0 "$bin" reference "$src/scenes/knot.json" -o "$tmp/knot.exr" --set camera.resolution=[96,64]

echo "$passes passed, $failures failed"
[[ $failures -eq 0 ]]
