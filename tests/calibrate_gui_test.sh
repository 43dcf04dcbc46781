#!/usr/bin/env bash
# The `rgbdvo calibrate` window tested for real: a private Xvfb display, the window found by its
# name, clicks and keys sent with xdotool at known image coordinates, then the saved pairs and
# the fitted calibration checked. Exit 77 (ctest: skipped) where Xvfb or xdotool is missing.
# Usage: calibrate_gui_test.sh RGBDVO_EXE SOURCE_DIR
set -euo pipefail
exe=$1
src=$2
for tool in Xvfb xdotool; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIPPED: '$tool' is not installed (Debian packages xvfb and xdotool; scripts/setup.sh installs them)"
    exit 77
  fi
done

work=$(mktemp -d /tmp/rgbdvo_gui_test.XXXXXX)
xvfb_pid=""
app_pid=""
cleanup() {
  [ -n "$app_pid" ] && kill "$app_pid" 2>/dev/null || true
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAILED: $*"
  echo "--- rgbdvo output:"
  cat "$work/app.log" 2>/dev/null || true
  exit 1
}
# Polls a shell condition every 0.1 s for up to $1 seconds.
wait_for() {
  local timeout=$1
  shift
  local deadline=$((SECONDS + timeout))
  until eval "$@"; do
    [ $SECONDS -ge $deadline ] && return 1
    sleep 0.1
  done
}

# A free display number chosen by Xvfb itself (-displayfd), so parallel tests do not collide.
Xvfb -displayfd 3 -screen 0 1600x900x24 -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
wait_for 20 '[ -s "$work/display" ]' || fail "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=":$(head -1 "$work/display")"
export XDG_RUNTIME_DIR="$work"
echo "display $DISPLAY"

# In an ENABLE_ASAN build, LeakSanitizer reports a leak inside libdbus (loaded by Qt), not ours.
echo "leak:libdbus-1.so" >"$work/lsan.supp"
LSAN_OPTIONS="suppressions=$work/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}" \
"$exe" calibrate "$src/data/tum_fr1_xyz_first30" --out "$work/c.yaml" \
  --calib "$src/calib/tum_fr1.yaml" >"$work/app.log" 2>&1 &
app_pid=$!

wid=""
wait_for 30 'wid=$(xdotool search --onlyvisible --name "^rgbdvo calibrate$" 2>/dev/null | head -1); [ -n "$wid" ]' ||
  fail "no visible window named 'rgbdvo calibrate' within 30 s"
# The canvas is 1280x600 (two 640x480 images and a 120 px panel) shown without scaling, so the
# window must be exactly that size; then window pixel (x, y) is canvas pixel (x, y).
wait_for 20 'eval "$(xdotool getwindowgeometry --shell "$wid")"; [ "${WIDTH}x${HEIGHT}" = 1280x600 ]' ||
  fail "window $wid is ${WIDTH}x${HEIGHT}, expected the canvas size 1280x600"
echo "window $wid at $X,$Y size ${WIDTH}x${HEIGHT}"
xdotool windowfocus --sync "$wid"

# Clicks at canvas pixel (x, y); the depth image starts at x = 640.
click() { xdotool mousemove --sync $((X + $1)) $((Y + $2)) click 1; }
vis() { click "$1" "$2"; }
ir() { click $((640 + $1)) "$2"; }
# A key is acted on after cv::waitKey returns, which may be after later clicks were already
# dispatched; so after each key wait for the line rgbdvo prints for it before going on.
key() {
  local pattern=$2
  xdotool key --clearmodifiers "$1"
  wait_for 20 'grep -q -- "$pattern" "$work/app.log"' || fail "no '$pattern' printed after the $1 key"
}

# Pairs of the mapping u_ir = 0.9 u_vis + 20, v_ir = 0.9 v_vis + 30.
vis 100 100; vis 110 120; ir 119 138        # pair 1; the second colour click moves the first
ir 290 210; vis 300 200                     # pair 2, IR image first
vis 400 300; ir 500 100                     # a wrong pair (3) ...
key u "^undo: pair 3 removed"               # ... undone
vis 50 50                                   # a pending point ...
key u "^undo: pending point dropped"        # ... cancelled
vis 500 400; ir 470 390                     # pair 3
key n "^frame 10$"                          # next frame
vis 200 350; click 100 550; ir 200 345      # pair 4; the click on the panel is ignored
key s "wrote .*c.yaml"
xdotool key --clearmodifiers q
wait_for 20 '! kill -0 $app_pid 2>/dev/null' || fail "rgbdvo still running 20 s after the q key"
wait "$app_pid" || fail "rgbdvo calibrate exited with status $?"
app_pid=""
cat "$work/app.log"

# Each pair keeps the depth under its IR click (a fifth column, z_ir_m, metres).
expected="u_vis,v_vis,u_ir,v_ir
110,120,119,138
300,200,290,210
500,400,470,390
200,350,200,345"
[ "$(cut -d, -f1-4 "$work/c.pairs.csv")" = "$expected" ] ||
  fail "saved pairs differ; got:
$(cat "$work/c.pairs.csv")
expected:
$expected"
[ "$(head -n 1 "$work/c.pairs.csv")" = "u_vis,v_vis,u_ir,v_ir,z_ir_m" ] ||
  fail "saved pairs have no depth column"
awk -F, 'NR > 1 && !($5 > 0.4 && $5 < 8) { bad = 1 } END { exit bad }' "$work/c.pairs.csv" ||
  fail "a saved pair's depth is not a depth of the recording"
# The fit recovers the mapping exactly (the clicks are exact pixels) and keeps K_ir of the base.
check() {
  local got
  got=$(awk -v k="$1:" '$1 == k {print $2}' "$work/c.yaml")
  awk -v g="$got" -v w="$2" 'BEGIN { d = g - w; exit !(g != "" && d < 1e-6 && d > -1e-6) }' ||
    fail "$1 = '$got' in c.yaml, expected $2"
}
check A 0.9
check B 20
check C 0.9
check D 30
grep -q "5.1729999999999995e+02" "$work/c.yaml" || fail "K_ir fx of calib/tum_fr1.yaml (517.3) not kept"
grep -q "from 4 of 4 pairs" "$work/app.log" || fail "the printed fit does not use 4 pairs"
echo "PASSED: 4 pairs clicked (undo, pending cancel, IR-first, next frame), A-D recovered"
