#!/usr/bin/env bash
# Configures (Release by default) and builds shadetlm into build/. BUILD_DIR and
# BUILD_TYPE override the defaults.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" >/dev/null
cmake --build "$build" -j"$(nproc)"
