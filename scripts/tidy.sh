#!/usr/bin/env bash
# clang-tidy 22 with the checks of .clang-tidy (bugprone, performance, concurrency) over our sources:
# src/, apps/, tests/ and the headers of include/ they include. Any finding fails the run.
# Configures build-tidy/ for its compile_commands.json (nothing is built there). A file found
# clean is not checked again while what clang-tidy reads of it is unchanged (scripts/tidy_run.py;
# the record is kept in ~/.cache/rgbdvo-tidy, or $RGBDVO_TIDY_CACHE).
# Usage: scripts/tidy.sh [FILE_REGEX]   (default: every source of src/, apps/ and tests/)
set -euo pipefail
cd "$(dirname "$0")/.."
# Version 22 (Debian's clang-tidy-22) does not match its checks against the system headers' code,
# which takes version 14 about four times as long (docs/decisions/0053-clang-tidy-22.md).
export CLANG_TIDY=clang-tidy-22
need=()
command -v clang-tidy-22 >/dev/null || need+=(clang-tidy-22)
command -v clang++ >/dev/null || need+=(clang)  # its preprocessor tells whether a file changed
[ ${#need[@]} -eq 0 ] || scripts/install_packages.sh "${need[@]}"
cmake -S . -B build-tidy -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
# GCC builds C++17 without a -std flag; say it to clang. libstdc++ 12 calls its own deprecated
# get_temporary_buffer, which clang 22 reports from the system header; GCC's -Wall build still
# reports any deprecated call of ours.
if python3 scripts/tidy_run.py build-tidy "${1:-$PWD/(src|apps|tests)/}" \
    "${RGBDVO_TIDY_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/rgbdvo-tidy}" -extra-arg=-std=c++17 \
    -extra-arg=-Wno-deprecated-declarations; then
  echo "tidy: clean"
else
  echo "tidy: findings above"
  exit 1
fi
