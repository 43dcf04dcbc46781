#!/usr/bin/env bash
# The threaded parts under ThreadSanitizer (build-tsan/): the bounded queue, the feature workers
# and the pipeline, SIFT from several threads, the fakenect recorder, and `rgbdvo capture` and
# `rgbdvo run` end to end (the Kinect thread, the recording thread, the workers). Any report
# fails the run. Part of .ci/run; built by clang at -O1 with line tables, as scripts/sanitize.sh.
# tests/tsan.supp suppresses what OpenCV's uninstrumented reference counting hides from it.
# Usage: scripts/tsan.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_packages.sh clang libclang-rt-14-dev

# Only the 6 test files (of about 100) that hold these tests are built;
# --warn NoTests fails the run when a name below matches no test of them.
cmake -S . -B build-tsan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" -DENABLE_TSAN=ON \
  -DRGBDVO_TESTS_MATCHING='/(util/bounded_queue|pipeline/run|features/features|capture/fakenect_recorder|apps/cli_capture|apps/cli_run)_test\.cpp$' \
  >/dev/null
cmake --build build-tsan -j"$(nproc)" --target rgbdvo rgbdvo_debug rgbdvo_tests
# exitcode 66 on any report: the test binary, and each rgbdvo the command-line tests start.
export TSAN_OPTIONS="halt_on_error=0 exitcode=66 suppressions=$PWD/tests/tsan.supp"
build-tsan/tests/rgbdvo_tests --warn NoTests \
  "BoundedQueue*,Feature workers*,*pipeline*,Workers*,SiftExtractor gives the same features from several threads at once,FakenectRecorder*,rgbdvo capture*,rgbdvo run on the real fr1/xyz*,rgbdvo run stops on SIGTERM*"
echo "tsan: the threaded tests passed under ThreadSanitizer"
