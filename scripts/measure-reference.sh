#!/usr/bin/env bash
# Measures the Reference technique: GPU time per pass (timestamps, median over the frames after
# the first) and wall-clock time per frame, on the default device, for the given scenes and
# sizes. Writes out/measure/<scene>-<W>x<H>.json and prints one table row per run.
# Each render compiles only the pipelines its technique runs (--pipelines on-first-use, in its first
# frame, on the CPU): a faster start, the same GPU timings.
# Usage: scripts/measure-reference.sh [build-dir] (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
render="$build/samples/tyndall-render"
[ -x "$render" ] || { echo "build first: $render not found" >&2; exit 1; }
mkdir -p out/measure
frames="${FRAMES:-4}"
printf '| scene | size | shadow map | reference_scattering ms | composite ms | Tyndall total ms | frame wall ms |\n'
printf '|---|---|---|---|---|---|---|\n'
for scene in ${SCENES:-pillars}; do
  for size in ${SIZES:-640x360 1280x720}; do
    w="${size%x*}"; h="${size#*x}"
    json="out/measure/$scene-$size.json"
    "$render" --pipelines on-first-use "samples/scenes/$scene.json" --profile reference --width "$w" --height "$h" \
      --shadow-map-size 2048 --frames "$frames" --timings "$json" >/dev/null
    python3 - "$json" "$scene" "$size" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
p = t["passMilliseconds"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | 2048 | {p.get('reference_scattering', 0):.1f} | "
      f"{p.get('composite', 0):.2f} | {t['totalMilliseconds']:.1f} | {t['wallMillisecondsPerFrame']:.1f} |")
PY
  done
done
