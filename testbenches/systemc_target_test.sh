#!/usr/bin/env bash
# A platform's own SystemC::systemc target is honoured: shadetlm configured with one
# defined before its first line links that target, not pkg-config's, and its installed
# package asks for the same target. Configure-only (a few seconds).
#   systemc_target_test.sh SOURCE_DIR
set -euo pipefail
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The platform's SystemC: here Debian's again, under the target name and with a mark.
cat >"$tmp/platform.cmake" <<'CMAKE'
find_package(PkgConfig REQUIRED)
pkg_check_modules(PLATFORM_SYSTEMC REQUIRED IMPORTED_TARGET systemc)
add_library(SystemC::systemc INTERFACE IMPORTED)
target_link_libraries(SystemC::systemc INTERFACE PkgConfig::PLATFORM_SYSTEMC)
target_compile_definitions(SystemC::systemc INTERFACE PLATFORM_SYSTEMC_MARK=1)
CMAKE
cmake -S "$src" -B "$tmp/build" -DCMAKE_PROJECT_shadetlm_INCLUDE="$tmp/platform.cmake" >"$tmp/log" 2>&1 ||
  { cat "$tmp/log"; exit 1; }
grep -q "PLATFORM_SYSTEMC_MARK=1" "$tmp/build/compile_commands.json" ||
  { echo "FAIL: the blocks are not built with the platform's SystemC::systemc"; exit 1; }
exported=$(cat "$tmp/build/CMakeFiles/Export/"*/shadetlmTargets.cmake)
if ! grep -q "SystemC::systemc" <<<"$exported" || grep -q "PkgConfig::SYSTEMC" <<<"$exported"; then
  echo "FAIL: the package does not name the platform's SystemC::systemc"; exit 1
fi
grep -q 'if("SystemC::systemc" STREQUAL "SystemC::systemc")' "$tmp/build/shadetlmConfig.cmake" ||
  { echo "FAIL: the installed package would not look for SystemC::systemc"; exit 1; }
echo "the platform's SystemC::systemc is linked and exported"
