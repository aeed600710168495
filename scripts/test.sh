#!/usr/bin/env bash
# Set-up command 2: installs what is missing, builds, and runs every test through
# ctest. Extra arguments go to ctest (e.g. -L golden, -R coverage).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
cd "${BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)" "$@"
