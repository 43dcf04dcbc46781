#!/bin/bash
# Fails when a library file includes a header of a layer it may not use (docs/architecture.md).
# Each folder of include/rgbdvo/ and src/ is a layer; a file may include headers of its own
# folder and of the folders listed for it below. Tests and apps may include any layer.
set -euo pipefail
cd "$(dirname "$0")/.."

declare -A may_use=(
  [util]=""
  [geometry]=""
  [sensor]="geometry util"
  [io]="geometry util"
  [features/sift]="util"
  [features]="util features/sift"
  [estimation]="geometry sensor"
  [sources]="geometry sensor io util"
  [capture]="geometry sensor io util sources"
  [odometry]="geometry sensor io util features features/sift estimation sources"
  [pipeline]="geometry sensor io util features features/sift estimation sources odometry"
  [evaluation]="geometry io util"
  [calibrate]="geometry sensor io util sources"
  [synthetic]="geometry sensor io util sources capture"
)

status=0
while IFS= read -r file; do
  layer=$(dirname "${file#include/rgbdvo/}")
  layer=${layer#src/}
  [[ $file == src/* ]] && layer=$(dirname "${file#src/}")
  if [[ -z ${may_use[$layer]+set} ]]; then
    echo "$file: folder '$layer' is not a known layer (add it to scripts/check_layers.sh and docs/architecture.md)"
    status=1
    continue
  fi
  while IFS= read -r used; do
    [[ $used == "$layer" ]] && continue
    if [[ " ${may_use[$layer]} " != *" $used "* ]]; then
      echo "$file: layer '$layer' may not include rgbdvo/$used/ (allowed: ${may_use[$layer]:-none})"
      status=1
    fi
  done < <(sed -n 's|^#include "rgbdvo/\(.*\)/[a-z_0-9]*\.hpp".*|\1|p' "$file" | sort -u)
  if grep -q '^#include "rgbdvo/[a-z_0-9]*\.hpp"' "$file"; then
    echo "$file: includes a header outside the layer folders: $(grep -o '"rgbdvo/[a-z_0-9]*\.hpp"' "$file" | head -1)"
    status=1
  fi
done < <(find include/rgbdvo src -name '*.hpp' -o -name '*.cpp' | sort)

if [[ $status -eq 0 ]]; then echo "layers: every include follows docs/architecture.md"; fi
exit $status
