#!/usr/bin/env bash
# Writes the man page of rgbdvo from its own --help (help2man), with one section per
# subcommand from `rgbdvo SUBCOMMAND --help`. Usage: scripts/make_manpage.sh RGBDVO_EXE OUT.1
set -euo pipefail
exe=$1
out=$2
include=$(mktemp)
trap 'rm -f "$include"' EXIT

# roff: a leading '.' or "'" would be a request, a backslash an escape.
roff_text() { sed -e 's/\\/\\e/g' -e 's/^\([.'"'"']\)/\\\&\1/' -e "s|$exe|rgbdvo|g"; }

{
  echo "[DESCRIPTION]"
  echo "rgbdvo estimates the 6-DOF trajectory of a Kinect-style RGB-D camera from its colour and"
  echo "depth images: SIFT features matched between frames, lifted to 3D through the depth image,"
  echo "RANSAC over 4-match hypotheses and a robust refinement (Fiala & Ufkes, CRV 2011)."
  echo "Each subcommand's flags are listed below and by \\fBrgbdvo\\fR \\fISUBCOMMAND\\fR \\fB--help\\fR."
  echo "[SUBCOMMANDS]"
  for sub in $("$exe" --help | awk '/^Subcommands:/ {f = 1; next} f && NF {print $1}'); do
    echo ".SS $sub"
    echo ".nf"
    "$exe" "$sub" --help | roff_text
    echo ".fi"
  done
  echo "[FILES]"
  echo ".TP"
  echo ".I /usr/share/rgbdvo/calib/*.yaml"
  echo "Calibrations that \\fB--calib\\fR finds by name (\\fBrgbdvo calibrations\\fR lists them)."
  echo "[ENVIRONMENT]"
  echo ".TP"
  echo ".B RGBDVO_CALIB_PATH"
  echo "Colon-separated folders searched first for a calibration given by name."
  echo "[SEE ALSO]"
  echo "The documentation in /usr/share/doc/rgbdvo (README.md, docs/)."
} > "$include"

help2man --no-info --section 1 --name "visual odometry for Kinect-style RGB-D cameras" \
  --include "$include" --output "$out" "$exe"
# help2man names the program by the path it was given.
sed -i "s|$exe|rgbdvo|g" "$out"
