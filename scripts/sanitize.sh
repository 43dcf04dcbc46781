#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UBSan (build-asan/); any report fails the
# run. Part of .ci/run. Built by clang, whose instrumented builds take about half GCC's time
# (docs/decisions/0052-clang-for-the-sanitizer-builds.md), at -O1 with line tables for the
# reports: about half the compile time of -O3, and still far faster to run than -O0.
# Usage: scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
scripts/install_packages.sh clang libclang-rt-14-dev

cmake -S . -B build-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" -DENABLE_ASAN=ON >/dev/null
cmake --build build-asan -j"$jobs" --target rgbdvo rgbdvo_debug rgbdvo_tests
# fakenect's library is preloaded into rgbdvo by the capture tests: ASan's runtime is then not
# first in the library list, which is harmless here. Left out: the fuzz replays (scripts/fuzz.sh
# runs those parsers under ASan and UBSan), the calibration window under Xvfb (timing-bound) and
# the install test (it checks packaging: man page, .deb; it runs in the plain suite).
# Also left out: the tests tagged [long], property tests of the synthetic renderer that take a
# minute each under ASan while shorter tests run the same code (each name becomes an anchored
# pattern, any character but a letter or digit matched by '.').
names=$(build-asan/tests/rgbdvo_tests --list-test-names-only '[long]' || true)  # exit status: the count
long=$(sed -e '/^$/d' -e 's/[^A-Za-z0-9]/./g' -e 's/.*/^&$/' <<<"$names" | paste -sd'|')
[[ -n $long ]] || { echo "sanitize: no test is tagged [long]" >&2; exit 1; }
ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j2 \
    -E "^fuzz_replay_|^calibrate_gui\$|^install_package\$|$long"
echo "sanitize: ASan+UBSan suite passed"
