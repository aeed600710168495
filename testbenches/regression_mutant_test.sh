#!/usr/bin/env bash
# The golden regression catches a one-cycle change: on a copy of each golden scene below
# (its accepted frames and stats as they are), one block's latency is raised by one
# cycle in the scene's pipeline settings, and scripts/regress.py must fail it on cycles
# alone (the frame is the same). The unchanged copy passes first, so a failure is the
# mutant's. Cycles are gated exactly (golden/*/golden.json, cycles.tolerance 0).
# Usage: regression_mutant_test.sh SHADETLM SOURCE_DIR
set -u
bin=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0
failures=0
check() {  # check NAME EXPECTED-EXIT COMMAND...
  local name=$1 want=$2 rc
  shift 2
  "$@" >"$tmp/out" 2>&1
  rc=$?
  if ((rc == want)); then ((passes++)); else echo "FAIL $name: exit $rc, expected $want"; sed 's/^/    /' "$tmp/out" | tail -5; ((failures++)); fi
}
# mutate SCENE BLOCK: the copy's scene.json with BLOCK's latency one above its default.
mutate() {
  python3 - "$tmp/root/golden/$1/scene.json" "$2" "$tmp/default.json" <<'PY'
import json, sys
path, block, stats = sys.argv[1:]
scene = json.load(open(path))
latency = json.load(open(stats))["config"][block + ".latency"]
scene.setdefault("pipeline", {}).setdefault(block, {})["latency"] = latency + 1
json.dump(scene, open(path, "w"), indent=1)
PY
}
for case in "sphere lighting" "bump-plane bump_fetch" "texture-object texel_project" "parallax-steps parallax"; do
  read -r scene block <<<"$case"
  rm -rf "$tmp/root" && mkdir -p "$tmp/root/golden" && cp -r "$src/golden/$scene" "$tmp/root/golden/"
  # (configurations of the scene other than its main one are left out: one row is enough)
  python3 - "$tmp/root/golden/$scene/golden.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["configurations"] = {}
json.dump(spec, open(sys.argv[1], "w"), indent=1)
PY
  check "$scene-unchanged" 0 python3 "$src/scripts/regress.py" "$bin" "$tmp/root" "$tmp/report" --scene "$scene"
  (cd "$tmp/root/golden/$scene" && "$bin" render scene.json -o "$tmp/default.exr" --stats "$tmp/default.json") \
    >/dev/null 2>&1 || { echo "FAIL $scene: the render failed"; ((failures++)); continue; }
  mutate "$scene" "$block"
  check "$scene-$block-latency+1" 1 python3 "$src/scripts/regress.py" "$bin" "$tmp/root" "$tmp/report" --scene "$scene"
  grep -q "cycles" "$tmp/out" || { echo "FAIL $scene-$block-latency+1: not failed on cycles"; ((failures++)); }
done
echo "$passes passed, $failures failed"
((failures == 0))
