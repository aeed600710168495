#!/usr/bin/env bash
# Prints the path of a real terrain height map in out/assets: the USGS elevation model
# of the Jacksboro fault (Tennessee) that matplotlib ships as sample data, taken from
# the Debian package python-matplotlib-data the first time (downloaded and unpacked
# there, not installed; never committed). scripts/dem-to-png.py turns its 344 x 403
# metres into a 16-bit PNG of 512 x 512: a 256 x 256 crop, mirrored so that it tiles as
# the parallax maps do. Prints nothing (and says why) if it cannot be had.
# Usage: scripts/dem-asset.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
assets=$root/out/assets
file=$assets/jacksboro-dem-512.png
if [[ ! -s $file ]]; then
  rm -rf "$assets/mpl"
  mkdir -p "$assets/mpl"
  dem=
  if (cd "$assets/mpl" && apt-get download -q python-matplotlib-data >/dev/null 2>&1); then
    dpkg -x "$assets"/mpl/python-matplotlib-data_*.deb "$assets/mpl/x"
    dem=$(find "$assets/mpl/x" -name jacksboro_fault_dem.npz | head -1)
  fi
  if [[ -z $dem ]] || ! python3 "$root/scripts/dem-to-png.py" "$dem" "$file"; then
    rm -rf "$assets/mpl"
    echo "dem-asset.sh: no elevation model from python-matplotlib-data; the terrain is left out" >&2
    exit 0
  fi
  rm -rf "$assets/mpl"
fi
echo "$file"
