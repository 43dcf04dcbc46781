#!/usr/bin/env bash
# Installs the Debian packages rgbdvo needs (only the missing ones), then configures and builds
# it in ./build. Safe to run again. Usage: scripts/setup.sh [extra cmake args]
# RGBDVO_EXTRA_PACKAGES (space-separated) adds packages, e.g. for bench/setup_peers.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libopencv-dev libopencv-contrib-dev libeigen3-dev libfreenect-dev libisal-dev
          libceres-dev
          librosbag-storage-dev libsensor-msgs-dev libroscpp-core-dev
          libzstd-dev liblz4-dev libsqlite3-dev
          libfreenect-bin libcli11-dev catch2 xvfb xdotool gnuplot-nox python3-numpy help2man man-db
          ${RGBDVO_EXTRA_PACKAGES:-})
scripts/install_packages.sh "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
