#!/usr/bin/env bash
# Installs the benchmark-only peer libraries (OpenCV's contrib rgbd module and Open3D), then
# configures and builds rgbdvo with the peer runners in ./build. Not needed for rgbdvo itself.
# Usage: bench/setup_peers.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
RGBDVO_EXTRA_PACKAGES="libopen3d-dev" scripts/setup.sh -DBUILD_BENCH_PEERS=ON "$@"
