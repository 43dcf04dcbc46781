#!/usr/bin/env bash
# Installs the benchmark-only peer libraries (OpenCV's contrib rgbd module and Open3D), then
# configures and builds rgbdvo with the peer runners in ./build. Not needed for rgbdvo itself.
# Usage: bench/setup_peers.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(libopencv-contrib-dev libopen3d-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup_peers: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

scripts/setup.sh -DBUILD_BENCH_PEERS=ON "$@"
