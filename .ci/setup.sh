#!/usr/bin/env bash
# Installs the Debian 12 packages valve builds against (as root, or through sudo), then
# configures and builds a Release tree in build/. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
PACKAGES=(build-essential cmake ccache pkg-config libinsighttoolkit5-dev libvtk9-dev libcgal-dev
          libeigen3-dev libsuitesparse-dev libopenblas0-pthread nlohmann-json3-dev catch2 libssl-dev
          gnuplot-nox xvfb xauth libgl1-mesa-dri calculix-ccx snakemake libnanoflann-dev)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
