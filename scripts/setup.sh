#!/usr/bin/env bash
# Installs the Debian packages rgbdvo needs (only the missing ones), then configures and builds
# it in ./build. Safe to run again. Usage: scripts/setup.sh [extra cmake args]
# RGBDVO_EXTRA_PACKAGES (space-separated) adds packages, e.g. for bench/setup_peers.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libopencv-dev libopencv-contrib-dev libeigen3-dev libfreenect-dev libisal-dev
          librosbag-storage-dev libsensor-msgs-dev libroscpp-core-dev
          libfreenect-bin libcli11-dev catch2 xvfb xdotool gnuplot-nox python3-numpy help2man man-db
          ${RGBDVO_EXTRA_PACKAGES:-})
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
