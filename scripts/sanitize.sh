#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UBSan (build-asan/); any report fails the
# run. Not in .ci/run yet: the ASan build takes about 20 minutes on a 2-core machine.
# Usage: scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DENABLE_ASAN=ON >/dev/null
cmake --build build-asan -j"$jobs" --target rgbdvo rgbdvo_tests
# fakenect's library is preloaded into rgbdvo by the capture tests: ASan's runtime is then not
# first in the library list, which is harmless here. Left out: the fuzz replays (scripts/fuzz.sh
# runs those parsers under ASan and UBSan) and the calibration window under Xvfb (timing-bound).
ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j2 -E '^fuzz_replay_|^calibrate_gui$'
echo "sanitize: ASan+UBSan suite passed"
