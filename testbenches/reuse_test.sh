#!/usr/bin/env bash
# Installs shadetlm into a staging prefix and builds and runs the out-of-tree example
# of docs/reuse.md against it: find_package(shadetlm) and one block in a testbench of
# one's own. Usage: reuse_test.sh BUILD_DIR SOURCE_DIR [CXX_FLAGS [LINKER_FLAGS]]
set -euo pipefail
build=$1
src=$2
cxx_flags=${3:-}
link_flags=${4:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/stage" >/dev/null
find "$tmp/stage" -name shadetlmConfig.cmake | grep -q . # lib/, lib64/ or lib/<arch>/
test -f "$tmp/stage/include/shadetlm/modules/normalize/normalize_kernel.hpp"
# COMPONENTS modules must not look for the file-format packages (they are hidden here),
# and the link keeps every library it is given (--no-as-needed: Debian's gcc drops
# unused ones otherwise), so the readelf check below sees any that come along.
cmake -S "$src/examples/reuse" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/stage" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=ON -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON \
  -DCMAKE_CXX_FLAGS="$cxx_flags" -DCMAKE_EXE_LINKER_FLAGS="$link_flags -Wl,--no-as-needed" >/dev/null
cmake --build "$tmp/build" -j2 >/dev/null
SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 "$tmp/build/normalize_testbench"
# The blocks alone (COMPONENTS modules) bring no file formats along: the testbench
# needs none of assimp, OpenEXR or stb.
if readelf -d "$tmp/build/normalize_testbench" | grep -iE "NEEDED.*(assimp|openexr|OpenEXR|Imf|Iex|stb)"; then
  echo "FAIL: linking shadetlm::modules pulled in the io component's libraries"; exit 1
fi
