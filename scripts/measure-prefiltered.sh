#!/usr/bin/env bash
# Measures the prefiltered technique against the Reference: per storage variant and scene, the
# relative RMSE of L_in (tyndall-compare against the Reference's AOV from the same build and
# device), the GPU time of each prefiltered pass (timestamps, median over the frames) and Tyndall's
# total, next to the Reference's (and the ratio of the two: the speedup of the scattering passes,
# the composite left out of both). Writes out/measure-prefiltered/* (MEASURE_OUT) and prints one
# table row per run, then, for each variant measured on several scenes, the spread of its
# evaluation pass over them ((max − min) / median; issue 4 asks < 15%).
# Each render compiles only the pipelines its technique runs (--pipelines on-first-use, in its first
# frame, on the CPU): a faster start, the same GPU timings.
# Usage: scripts/measure-prefiltered.sh [build-dir] (default: build)
# Environment: SCENES (default: the directional scenes; a name from samples/scenes/ or a path to a
#   scene file), BASES (default: all six), SIZE (640x360),
#   SHADOW_MAP (1024), FRAMES (3), PREFILTERED (extra --prefiltered keys, e.g. "rows=512,columns=512"),
#   REFERENCE_FROM (the MEASURE_OUT of an earlier run with the same SIZE, SHADOW_MAP and FRAMES:
#   its Reference renders are compared against and timed instead of rendering them again).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
render="$build/samples/tyndall-render"
compare="$build/samples/tyndall-compare"
[ -x "$render" ] || { echo "build first: $render not found" >&2; exit 1; }
out="${MEASURE_OUT:-out/measure-prefiltered}"
mkdir -p "$out"
size="${SIZE:-640x360}"
w="${size%x*}"; h="${size#*x}"
map="${SHADOW_MAP:-1024}"
frames="${FRAMES:-3}"
extra="${PREFILTERED:-}"
printf '| scene | variant | relative RMSE | moment map | rectify | prefix sums | evaluate | epipole block | prefiltered total ms | Reference ms | speedup |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|\n'
evaluations="$out/evaluations-$size.tsv"  # variant, scene, evaluate ms: the spread below
: >"$evaluations"
for entry in ${SCENES:-pillars fence forest window-room analytic-spheres analytic-boxes analytic-mixed}; do
  case "$entry" in
    *.json) file="$entry"; scene="$(basename "$entry" .json)" ;;
    *) file="samples/scenes/$entry.json"; scene="$entry" ;;
  esac
  if [ -n "${REFERENCE_FROM:-}" ]; then
    ref="$REFERENCE_FROM/$scene-$size-reference"
    [ -f "$ref.exr" ] && [ -f "$ref.json" ] || { echo "no Reference render $ref.{exr,json}" >&2; exit 1; }
  else
    ref="$out/$scene-$size-reference"
    "$render" --pipelines on-first-use "$file" --technique reference --width "$w" --height "$h" \
      --shadow-map-size "$map" --frames "$frames" --timings "$ref.json" --aov-scattering "$ref.exr" >/dev/null
  fi
  for basis in ${BASES:-moments4_64 moments4_128 moments6_64 moments6_96 moments6_192 fourier32}; do
    run="$out/$scene-$size-$basis"
    "$render" --pipelines on-first-use "$file" --technique prefiltered --prefiltered "basis=$basis${extra:+,$extra}" \
      --width "$w" --height "$h" --shadow-map-size "$map" --frames "$frames" --timings "$run.json" \
      --aov-scattering "$run.exr" >/dev/null
    "$compare" "$run.exr" "$ref.exr" >"$run-error.json"
    python3 - "$run.json" "$run-error.json" "$ref.json" "$scene" "$basis" "$evaluations" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
e = json.load(open(sys.argv[2]))
r = json.load(open(sys.argv[3]))
p = t["passMilliseconds"]
block = p.get("prefiltered_epipole_fixup_args", 0) + p.get("prefiltered_epipole_fixup", 0)
total = sum(v for k, v in p.items() if k.startswith("prefiltered_"))
ref = r["passMilliseconds"].get("reference_scattering", 0)
def ms(v):  # three significant digits down to 0.001 ms: a GPU's passes take well under 0.1 ms
    return f"{v:.1f}" if v >= 10 else f"{v:.2f}" if v >= 1 else f"{v:.3f}"
print(f"| {sys.argv[4]} | {sys.argv[5]} | {e['relativeRmse'] * 100:.2f}% | "
      f"{ms(p.get('prefiltered_moment_shadow_map', 0))} | {ms(p.get('prefiltered_rectify', 0))} | "
      f"{ms(p.get('prefiltered_prefix_sums', 0))} | {ms(p.get('prefiltered_evaluate', 0))} | {ms(block)} | "
      f"{ms(total)} | {ms(ref)} | {ref / total:.1f}x |")
with open(sys.argv[6], "a") as f:
    f.write(f"{sys.argv[5]}\t{sys.argv[4]}\t{p.get('prefiltered_evaluate', 0)}\n")
PY
  done
done
echo
python3 scripts/evaluation-spread.py "$evaluations"
