#!/usr/bin/env bash
# Device memory a context holds per profile and output size: Stats::deviceMemoryBytes (every
# allocation Tyndall makes, at the size the driver asked for) after one frame of one profile in a
# fresh context, as tyndall-render's --timings reports it. Prints a Markdown table
# (docs/INTEGRATION.md "Device memory").
# Usage: scripts/memory-footprint.sh [build-dir] (default: build)
# Environment: SCENES (default: pillars spot-lamp: a directional and a spot light), SIZES
#   (default: 1280x720 1920x1080 3840x2160), PROFILES (default: reference high balanced performance),
#   SHADOW_MAP (2048).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
render="$build/samples/tyndall-render"
[ -x "$render" ] || { echo "build first: $render not found" >&2; exit 1; }
out=out/memory-footprint
mkdir -p "$out"
map="${SHADOW_MAP:-2048}"
sizes="${SIZES:-1280x720 1920x1080 3840x2160}"
printf '| scene | profile | technique |'
for size in $sizes; do printf ' %s MiB |' "$size"; done
printf '\n|---|---|---|'
for size in $sizes; do printf -- '---|'; done
printf '\n'
for scene in ${SCENES:-pillars spot-lamp}; do
  for profile in ${PROFILES:-reference high balanced performance}; do
    cells=""
    for size in $sizes; do
      w="${size%x*}"; h="${size#*x}"
      run="$out/$scene-$size-$profile.json"
      "$render" "samples/scenes/$scene.json" --profile "$profile" --width "$w" --height "$h" \
        --shadow-map-size "$map" --frames 1 --timings "$run" --output "$out/$scene-$size-$profile.png" >/dev/null
      # The technique is the profile's, the same at every size: the last run's is printed.
      read -r technique mib < <(python3 -c '
import json, sys
t = json.load(open(sys.argv[1]))
print(t["technique"], "%.1f" % (t["deviceMemoryBytes"] / 2**20))' "$run")
      cells="$cells $mib |"
    done
    printf '| %s | %s | %s |%s\n' "$scene" "$profile" "$technique" "$cells"
  done
done
