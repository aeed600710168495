#!/usr/bin/env bash
# libFuzzer on the scene parser and the image and mesh loaders, each for SECONDS
# (default 60), under AddressSanitizer and UBSan, in a clang build of its own
# (build-fuzz/). Seeds: the project's scenes, meshes and images. Crashes go to
# out/fuzz/crashes/; a crash found is fixed and its input kept in
# testbenches/fuzz/regressions/<target>/, which hostile_more_test.sh replays (images).
# Usage: scripts/fuzz.sh [SECONDS] [scene|image|mesh ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" clang libclang-rt-14-dev
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(scene image mesh)
build=$root/build-fuzz
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADETLM_FUZZ=ON \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}") >/dev/null
out=$root/out/fuzz
mkdir -p "$out/crashes"
for t in "${targets[@]}"; do
  corpus=$out/corpus-$t
  mkdir -p "$corpus"
  # Seeds (the loaders' fuzzers take a first byte that picks the file type).
  case $t in
    scene) find "$root/scenes" "$root/golden" -name '*.json' -exec cp {} "$corpus/" \; ;;
    image) for f in "$root"/docs/images/*.png; do { printf '\x00'; cat "$f"; } >"$corpus/$(basename "$f")"; done ;;
    mesh) for f in "$root"/scenes/assets/*.obj "$root"/scenes/stress/assets/*.obj; do
            { printf '\x00'; cat "$f"; } >"$corpus/$(basename "$f")"; done ;;
  esac
  if [[ -d $root/testbenches/fuzz/regressions/$t ]]; then cp "$root/testbenches/fuzz/regressions/$t"/* "$corpus/" 2>/dev/null || true; fi
  echo "fuzz_$t: $seconds s"
  ASAN_OPTIONS=detect_leaks=1 "$build/testbenches/fuzz/fuzz_$t" "$corpus" -max_total_time="$seconds" \
    -artifact_prefix="$out/crashes/$t-" -print_final_stats=1 2>&1 | grep -E "^stat::number_of_executed_runs|ERROR|SUMMARY|crash-|Done" || true
done
# Out-of-memory reports are listed apart: stb_image's inflater grows its buffer with the
# compressed stream, so a PNG that inflates far past its declared size allocates that much
# before failing (a known limit of stb, docs/development.md) — resource use, not a crash.
if ls "$out/crashes/"oom-* "$out/crashes/"*-oom-* >/dev/null 2>&1; then
  echo "fuzz.sh: out-of-memory inputs (not crashes): $(ls "$out/crashes/" | grep -c oom)" >&2
fi
if ls "$out/crashes/" 2>/dev/null | grep -qv oom; then
  echo "fuzz.sh: crashes in $out/crashes" >&2
  exit 1
fi
echo "fuzz.sh: no crash"
