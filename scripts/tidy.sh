#!/usr/bin/env bash
# clang-tidy with the checks of .clang-tidy (bugprone, performance, concurrency) over our sources:
# src/, apps/, tests/ and the headers of include/ they include. Any finding fails the run.
# Configures build-tidy/ for its compile_commands.json (nothing is built there).
# Usage: scripts/tidy.sh [FILE_REGEX]   (default: every source of src/, apps/ and tests/)
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v run-clang-tidy >/dev/null; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends clang-tidy
fi
cmake -S . -B build-tidy -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
# GCC builds C++17 without a -std flag; clang's default is C++14, so say it.
status=0
run-clang-tidy -j"$(nproc)" -p build-tidy -quiet -extra-arg=-std=c++17 \
  "${1:-$PWD/(src|apps|tests)/}" >build-tidy/tidy.log 2>&1 || status=$?
grep -v -E '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$' build-tidy/tidy.log || true
[ "$status" -eq 0 ] || { echo "tidy: findings above (run-clang-tidy exit $status)"; exit 1; }
echo "tidy: clean"
