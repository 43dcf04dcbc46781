#!/usr/bin/env bash
# The converter's command line: the bundled excerpt written as MCAP (lz4 chunks, 16UC1 depth)
# and as .db3, each listed by `rgbdvo info` with its 30 images a topic; a bad option refused.
# Usage: tum_to_ros2_test.sh CONVERTER RGBDVO SOURCE_DIR
set -euo pipefail
converter=$1 rgbdvo=$2 source=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
excerpt=$source/data/tum_fr1_xyz_first30
"$converter" "$excerpt" "$dir/x.mcap" --compression lz4 --depth 16UC1 | grep -q "30 frames"
"$converter" "$excerpt" "$dir/x.db3" | grep -q "30 frames"
for bag in "$dir/x.mcap" "$dir/x.db3"; do
  info=$("$rgbdvo" info "$bag")
  grep -q "ROS 2 bag" <<<"$info"
  grep -E -q "^/camera/depth/image +sensor_msgs/msg/Image +cdr +30 " <<<"$info"
  grep -E -q "^/camera/rgb/image_color +sensor_msgs/msg/Image +cdr +30 " <<<"$info"
done
if "$converter" "$excerpt" "$dir/y.mcap" --depth 8UC1 2>/dev/null; then exit 1; fi
echo "tum_to_ros2: MCAP and .db3 written and listed"
