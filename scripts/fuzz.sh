#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang with ASan and UBSan) in ./build-fuzz and runs
# each for SECONDS (default 30) from its seed corpus (libFuzzer seed 1), at most 2 GiB of memory
# and 10 s per input, as many targets at once as there are processors.
# New interesting inputs go to a scratch corpus, not into the repository. A crash, a sanitizer
# report, a timeout or an out-of-memory stops with the input saved under build-fuzz/findings/;
# add it to tests/fuzz/corpus/<target>/findings/ with the fix, so the replay tests keep it.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(png tum_list accelerometer fakenect_index pnm calibration pixel_pairs trajectory mcap cdr)

scripts/install_packages.sh clang libclang-rt-14-dev

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DRGBDVO_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

mkdir -p build-fuzz/findings
# fuzz_one TARGET: runs it, leaving its log and its exit status (0: no finding) in build-fuzz/.
fuzz_one() {
  local t=$1 scratch=build-fuzz/corpus/$1 result=0
  mkdir -p "$scratch"
  build-fuzz/tests/fuzz/fuzz_$t "$scratch" tests/fuzz/corpus/$t -max_total_time="$seconds" \
    -seed=1 -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/findings/${t}- >"build-fuzz/fuzz_$t.log" 2>&1 || result=1
  echo $result >"build-fuzz/fuzz_$t.status"
}
# One target per processor at a time (libFuzzer runs on one): each still gets its SECONDS.
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
status=0
for t in "${targets[@]}"; do
  log=build-fuzz/fuzz_$t.log
  if [ "$(cat "build-fuzz/fuzz_$t.status")" = 0 ]; then
    echo "fuzz $t: $(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$') inputs in ${seconds} s, $(grep -o 'cov: [0-9]*' "$log" | tail -1), no finding"
  else
    echo "fuzz $t: FINDING, see $log and build-fuzz/findings/"
    grep -m3 -E 'ERROR|SUMMARY|==[0-9]+==' "$log" || tail -5 "$log"
    status=1
  fi
done
exit $status
