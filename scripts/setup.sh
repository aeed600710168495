#!/usr/bin/env bash
# Installs the Debian 12 packages shadetlm needs to build, test and run. Quiet and
# quick when everything is already there; uses sudo when not run as root.
set -euo pipefail

packages=(
  g++ cmake make pkg-config git
  libsystemc-dev      # simulation kernel (C++17 build)
  libglm-dev          # vector maths
  libopenexr-dev      # frames
  catch2              # tests (v2)
  libassimp-dev       # meshes
  libstb-dev          # JPEG in
  libpng-dev          # PNG in: the reference decoder (CRCs, palettes checked)
  nlohmann-json3-dev  # scene files
  libcli11-dev        # command line
  valgrind            # scripts/bench.sh: instruction counts
  python3             # report scripts
  verilator           # RTL in the loop (docs/rtl.md): the normalize unit verilated into SystemC
  yosys               # its synthesis to generic cells (scripts/synth.sh, the rtl test)
  opensta             # its timing and power in standard cells (scripts/cells.py)
  qflow-tech-osu018   # the OSU 0.18 um cell library (scripts/cells.py)
)
# Packages a script needs beyond these come as arguments: scripts/plot.sh gnuplot-nox;
# scripts/test.sh and scripts/cluster-bench.sh slurm-wlm's daemons for a single-node
# Slurm (not in every build's list: Debian enables munge's and Slurm's services).
packages+=("$@")

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ $status == "install ok installed" ]] || missing+=("$p")
done
((${#missing[@]} == 0)) && exit 0

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup.sh: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "setup.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
