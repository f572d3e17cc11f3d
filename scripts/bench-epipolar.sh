#!/usr/bin/env bash
# Benchmarks the epipolar technique against the Reference in the same run (the epipolar issue's
# "Measure"): per scene, output size and shadow-map size, the Reference's GPU time, then each
# profile's per-pass GPU times (timestamps, median over the frames after the first), total,
# speedup over the Reference, relative RMSE of L_in against the Reference's AOV, and the ray-marched
# samples. Writes out/bench-epipolar/* and prints a Markdown table (per-pass times in a second
# table). Runs on whatever Vulkan device is present (TYNDALL_DEVICE picks one).
# Each render compiles only the pipelines its technique runs (--pipelines on-first-use, in its first
# frame, on the CPU): a faster start, the same GPU timings.
# Usage: scripts/bench-epipolar.sh [build-dir] (default: build)
# Environment: SCENES (pillars forest window-room spot-lamp), SIZES (1280x720 1920x1080),
#   SHADOW_MAPS (2048 4096), PROFILES (high balanced performance), FRAMES (12), REFERENCE_FRAMES (4).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
render="${RENDER:-$build/samples/tyndall-render}"
compare="${COMPARE:-$build/samples/tyndall-compare}"
[ -x "$render" ] || { echo "build first: $render not found" >&2; exit 1; }
out="${BENCH_OUT:-out/bench-epipolar}"
mkdir -p "$out"
frames="${FRAMES:-12}"
reference_frames="${REFERENCE_FRAMES:-4}"
rows="$out/rows.jsonl"
: >"$rows"
# Warm-up, discarded: a GPU's clocks ramp up over its first busy moments, so the first timed run was
# slow (an H100 run of 2026-11-23: pillars' Reference at 1280x720 took 15.3 ms there against
# 9.8 ms at 1920x1080).
first_scene="$(set -- ${SCENES:-pillars}; echo "$1")"
first_size="$(set -- ${SIZES:-1280x720}; echo "$1")"
"$render" --pipelines on-first-use "samples/scenes/$first_scene.json" --technique reference --width "${first_size%x*}" \
  --height "${first_size#*x}" --frames 2 >/dev/null
for scene in ${SCENES:-pillars forest window-room spot-lamp}; do
  for size in ${SIZES:-1280x720 1920x1080}; do
    w="${size%x*}"; h="${size#*x}"
    for map in ${SHADOW_MAPS:-2048 4096}; do
      ref="$out/$scene-$size-$map-reference"
      "$render" --pipelines on-first-use "samples/scenes/$scene.json" --technique reference --width "$w" --height "$h" \
        --shadow-map-size "$map" --frames "$reference_frames" --timings "$ref.json" --aov-scattering "$ref.exr" >/dev/null
      for profile in ${PROFILES:-high balanced performance}; do
        run="$out/$scene-$size-$map-$profile"
        "$render" --pipelines on-first-use "samples/scenes/$scene.json" --profile "$profile" --width "$w" --height "$h" \
          --shadow-map-size "$map" --frames "$frames" --timings "$run.json" --aov-scattering "$run.exr" >/dev/null
        "$compare" "$run.exr" "$ref.exr" >"$run-error.json"
        python3 - "$run.json" "$run-error.json" "$ref.json" "$scene" "$size" "$map" "$profile" >>"$rows" <<'PY'
import json, sys
t, e, r = (json.load(open(p)) for p in sys.argv[1:4])
print(json.dumps({"scene": sys.argv[4], "size": sys.argv[5], "map": int(sys.argv[6]), "profile": sys.argv[7],
                  "device": t["device"], "passes": t["passMilliseconds"], "total": t["totalMilliseconds"],
                  "reference": r["totalMilliseconds"], "rmse": e["relativeRmse"], "nonFinite": e["nonFinite"],
                  "marched": t.get("marchedSamples", 0), "fixedUp": t.get("fixedUpPixelFraction", 0.0)}))
PY
      done
    done
  done
done
python3 - "$rows" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
# The sample counts of a frame are read back when its slot comes round again: with too few frames
# for that (fixedUpPixelFraction < 0) they are unknown, not zero.
def counts(r):
    return "n/a | n/a" if r["fixedUp"] < 0 else f"{r['marched']} | {100 * r['fixedUp']:.2f}%"
print(f"Device: {rows[0]['device']}\n")
print("| scene | size | shadow map | profile | Reference ms | epipolar ms | speedup | relative RMSE | NaN/Inf | marched samples | fixed up |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['scene']} | {r['size']} | {r['map']}² | {r['profile']} | {r['reference']:.2f} | {r['total']:.2f} | "
          f"{r['reference'] / r['total']:.1f}× | {100 * r['rmse']:.2f}% | {r['nonFinite']} | {counts(r)} |")
names = []
for r in rows:
    for name in r["passes"]:
        if name.startswith("epipolar_") and name not in names:
            names.append(name)
print("\nPer-pass GPU milliseconds (median over the frames):\n")
print("| scene | size | map | profile | " + " | ".join(n.removeprefix("epipolar_") for n in names) + " |")
print("|---|---|---|---|" + "---|" * len(names))
for r in rows:
    print(f"| {r['scene']} | {r['size']} | {r['map']} | {r['profile']} | " +
          " | ".join(f"{r['passes'].get(n, 0.0):.3f}" for n in names) + " |")
PY
