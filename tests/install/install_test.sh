#!/usr/bin/env bash
# Installs rgbdvo into a fresh temporary prefix and uses it as a user would, with no path into
# the source tree: the program finds its calibrations by name, examples/ builds against the
# CMake package and the pkg-config file, the man page renders, bash completion completes; then
# the .deb (cpack) unpacked into a temporary root runs, and its Depends name the runtime
# libraries. Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(realpath "$1")
src=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
recording=$tmp/recording
cp -r "$src/data/tum_fr1_xyz_first30" "$recording"  # the sample, away from the source tree
frames=$(grep -vc '^#' "$recording/rgb.txt")

prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
cd "$tmp"

# The installed program: --calib by name resolves to the installed file.
"$prefix/bin/rgbdvo" run "$recording" --calib tum_fr1 --tum "$tmp/run.tum" >"$tmp/run.log" 2>&1 ||
  { cat "$tmp/run.log"; fail "installed rgbdvo run"; }
grep -q "^# calibration: $prefix/share/rgbdvo/calib/tum_fr1.yaml " "$tmp/run.log" ||
  fail "--calib tum_fr1 did not resolve to the installed file: $(grep calibration: "$tmp/run.log")"
[ "$(grep -vc '^#' "$tmp/run.tum")" -eq "$frames" ] || fail "run wrote $(wc -l <"$tmp/run.tum") poses"
"$prefix/bin/rgbdvo" calibrations | grep -q "^tum_fr1	$prefix/share/rgbdvo/calib/tum_fr1.yaml$" ||
  fail "rgbdvo calibrations does not list the installed tum_fr1"
if "$prefix/bin/rgbdvo" run "$recording" --calib no_such_camera --tum "$tmp/x.tum" 2>"$tmp/err.log"; then
  fail "an unknown calibration name was accepted"
fi
grep -q "no_such_camera" "$tmp/err.log" || fail "the error does not name the calibration: $(cat "$tmp/err.log")"

# The library through the CMake package: examples/ built against the prefix only.
cmake -S "$src/examples" -B "$tmp/example" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/example" >/dev/null
"$tmp/example/print_poses" "$recording" "$prefix/share/rgbdvo/calib/tum_fr1.yaml" >"$tmp/example.tum"
[ "$(wc -l <"$tmp/example.tum")" -eq "$frames" ] || fail "the example printed $(wc -l <"$tmp/example.tum") poses"
# The same odometry as the program (same defaults, same seed).
diff <(grep -v '^#' "$tmp/run.tum") "$tmp/example.tum" >/dev/null || fail "example and rgbdvo run disagree"

# Every installed header compiles against the installed tree alone (no private header left out
# from under a public one), and the private ones are not there.
find "$prefix/include/rgbdvo" -name '*.hpp' | sed "s|^$prefix/include/|#include <|; s|\$|>|" >"$tmp/all_headers.cpp"
[ "$(wc -l <"$tmp/all_headers.cpp")" -ge 40 ] || fail "only $(wc -l <"$tmp/all_headers.cpp") headers installed"
# shellcheck disable=SC2046
g++ -std=c++17 -fsyntax-only -I"$prefix/include" $(pkg-config --cflags opencv4 eigen3) "$tmp/all_headers.cpp" ||
  fail "an installed header does not compile against the installed tree"
for private in util/simd.hpp features/sift/sift.hpp features/lucas_kanade.hpp io/png_decoder.hpp \
  util/huge_page_buffer.hpp; do
  [ ! -e "$prefix/include/rgbdvo/$private" ] || fail "the private header $private is installed"
done
# ... and through pkg-config.
PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --exists rgbdvo || fail "pkg-config finds no rgbdvo"
# shellcheck disable=SC2046
g++ -O0 "$src/examples/print_poses.cpp" -o "$tmp/print_poses_pc" \
  $(PKG_CONFIG_PATH=$prefix/lib/pkgconfig pkg-config --cflags --libs --static rgbdvo)
"$tmp/print_poses_pc" "$recording" "$prefix/share/rgbdvo/calib/tum_fr1.yaml" | cmp -s - "$tmp/example.tum" ||
  fail "the pkg-config build disagrees"

# The man page renders and documents every subcommand.
if command -v man >/dev/null; then
  page=$(MANWIDTH=100 man -l "$prefix/share/man/man1/rgbdvo.1" 2>/dev/null)
  for sub in run calibrate eval plot calibrations; do
    grep -q "^   $sub\$" <<<"$page" || fail "man page has no section for $sub"
  done
  grep -q "rgbdvo run \[OPTIONS\]" <<<"$page" || fail "man page shows a build path"
fi

# Bash completion: subcommands, a subcommand's flags, calibration names.
complete_line() {  # prints the completions of the words given (the last one being completed)
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _rgbdvo; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$prefix/share/bash-completion/completions/rgbdvo" "$@"
}
[ "$(complete_line "$prefix/bin/rgbdvo" cal | sort | tr '\n' ' ')" = "calibrate calibrations " ] ||
  fail "completing 'cal': $(complete_line "$prefix/bin/rgbdvo" cal | tr '\n' ' ')"
# (The output is kept and shown on failure: this check once failed under load and passed alone.)
got=$(complete_line "$prefix/bin/rgbdvo" run --depth-t)
grep -qx -- "--depth-term-step" <<<"$got" ||
  fail "no flag completion: got '$got'; 'rgbdvo run --help' lists $("$prefix/bin/rgbdvo" run --help 2>&1 | grep -c -- --depth-term-step) --depth-term-step"
got=$(complete_line "$prefix/bin/rgbdvo" run --calib tum_fr)
grep -qx "tum_fr3" <<<"$got" || fail "no calibration completion: got '$got'"

# The .deb: unpacked into a temporary root, its program runs with its own calibrations.
cpack --config "$build/CPackConfig.cmake" -B "$tmp/package" >/dev/null
deb=$(ls "$tmp"/package/rgbdvo_*.deb)
dpkg-deb -f "$deb" Depends | grep -q "libopencv-core" || fail "Depends lacks OpenCV: $(dpkg-deb -f "$deb" Depends)"
dpkg-deb -f "$deb" Depends | grep -q "libopencv-imgcodecs" ||
  fail "Depends lacks OpenCV's image codecs (loaded when needed): $(dpkg-deb -f "$deb" Depends)"
dpkg-deb -x "$deb" "$tmp/root"
"$tmp/root/usr/bin/rgbdvo" run "$recording" --calib tum_fr1 --tum "$tmp/deb.tum" >"$tmp/deb.log" 2>&1 ||
  { cat "$tmp/deb.log"; fail "the packaged rgbdvo run"; }
grep -q "^# calibration: $tmp/root/usr/share/rgbdvo/calib/tum_fr1.yaml " "$tmp/deb.log" ||
  fail "the packaged program did not use its own calibration"
for f in usr/share/man/man1/rgbdvo.1 usr/share/bash-completion/completions/rgbdvo usr/share/doc/rgbdvo/LICENSE \
  usr/lib/cmake/rgbdvo/rgbdvoConfig.cmake usr/include/rgbdvo/odometry/odometry.hpp; do
  [ -f "$tmp/root/$f" ] || fail "the package lacks /$f"
done
[ ! -e "$tmp/root/usr/include/rgbdvo/util/simd.hpp" ] || fail "a private header was installed"
echo "install: prefix, example (CMake and pkg-config), man page, completion and .deb all work"
