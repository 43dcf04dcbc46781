#!/usr/bin/env bash
# Makes docs/calibrate_window.png: the `rgbdvo calibrate` window on the bundled TUM excerpt with
# six hand-picked pairs (one deliberately wrong), robust fit on, under a private Xvfb.
# Needs xvfb, xdotool and imagemagick (import, convert). Usage: scripts/calibrate_screenshot.sh
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
Xvfb -displayfd 3 -screen 0 1600x900x24 -nolisten tcp 3>"$work/display" 2>/dev/null &
xvfb_pid=$!
trap 'kill $app_pid $xvfb_pid 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
export DISPLAY=":$(head -1 "$work/display")" XDG_RUNTIME_DIR="$work"
build/rgbdvo calibrate data/tum_fr1_xyz_first30 --out "$work/c.yaml" --calib calib/tum_fr1.yaml \
  >/dev/null 2>&1 &
app_pid=$!
wid=$(timeout 30 xdotool search --sync --onlyvisible --name '^rgbdvo calibrate$' | head -1)
sleep 1
eval "$(xdotool getwindowgeometry --shell "$wid")"
xdotool windowfocus --sync "$wid"
pair() {  # u_vis v_vis u_ir v_ir
  xdotool mousemove --sync $((X + $1)) $((Y + $2)) click 1
  xdotool mousemove --sync $((X + 640 + $3)) $((Y + $4)) click 1
}
pair 291 63 286 67    # back monitor, top left
pair 509 53 504 59    # back monitor, top right
pair 600 111 601 116  # right monitor, corner
pair 175 318 176 319  # milk carton, top left
pair 301 297 301 301  # pen holder
pair 150 420 168 405  # a wrong click
xdotool mousemove --sync $((X + 40)) $((Y + 36)) click 1  # chair corner, twin not yet clicked
xdotool key r
xdotool mousemove --sync $((X + 640 + 286)) $((Y + 67))   # magnifier on pair 1's IR point
sleep 1
import -window "$wid" "$work/shot.png"
convert "$work/shot.png" -colors 256 PNG8:docs/calibrate_window.png
ls -l docs/calibrate_window.png
