#!/usr/bin/env bash
# Prints the path of one of skimage's sample images (e.g. moon.png, astronaut.png) in
# out/assets, taking it from the Debian package python3-skimage the first time
# (downloaded and unpacked there, not installed). Prints nothing if the package cannot be
# downloaded. Used by the report scripts for their real-world inputs.
# Usage: scripts/skimage-asset.sh NAME
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
assets=$root/out/assets
file=$assets/$1
if [[ ! -s $file ]]; then
  mkdir -p "$assets/pkg"
  if (cd "$assets/pkg" && apt-get download -q python3-skimage >/dev/null 2>&1); then
    dpkg -x "$assets"/pkg/python3-skimage_*.deb "$assets/pkg/x"
    cp "$(find "$assets/pkg/x" -name "$1" | head -1)" "$file"
    rm -rf "$assets/pkg"
  else
    echo "skimage-asset.sh: python3-skimage could not be downloaded; no $1" >&2
    exit 0
  fi
fi
echo "$file"
