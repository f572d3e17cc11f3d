#!/usr/bin/env bash
# The measurements behind the documents' GPU sections, in one run on a GPU, each part timed:
#   tradeoffs    tyndall-bench's default sweep with a 2048² map, one run per size (1920x1080, then
#                3840x2160), each run's results.json kept as tradeoffs-WxH-results.json as soon as it
#                ends: docs/TRADEOFFS-H200.md comes from the first size's, written again here (with the
#                plots, which need matplotlib) by FROM=$GPU_OUT/keep/tradeoffs-1920x1080-results.json
#                DOC=docs/TRADEOFFS-H200.md scripts/measure.sh tradeoffs (the profile table's data, then:
#                docs/data/profile-table-*.json, plugin/src/profiles.cpp). With TRADEOFFS_BUDGET_S the
#                part stops within that many seconds: every size but the last gets at most 60% of what
#                is left, the last all of it; a run stopped keeps the scenes it finished (the bench
#                rewrites its results after each scene) and the log says how many.
#   epipolar     scripts/measure.sh epipolar with 20 frames (12 for the Reference): docs/measurements/epipolar-<device>-<date>.md
#   prefiltered  scripts/measure.sh prefiltered at 1280x720 and 1920x1080 with 1024² and 2048² maps,
#                every storage variant, 20 frames: docs/measurements/prefiltered-<device>-<date>.md
#   cost         scripts/measure.sh cost at 1920x1080 with a 2048² map, 20 frames: the GPU's
#                figures for docs/measurements/prefiltered-cost-independence-<device>-<date>.md
# The small files to keep are gathered in $GPU_OUT/keep/ (at most 8: results.json, the Markdown
# tables, the epipolar rows, the log). Runs on whatever Vulkan device is present (TYNDALL_DEVICE
# picks one); on lavapipe pick small sizes (below) or it takes hours. A machine without this
# project's packages runs the bundle of scripts/bundle-binaries.sh: LD_LIBRARY_PATH=DEST/lib
# scripts/measure-gpu.sh DEST.
# Usage: scripts/measure-gpu.sh [build-dir] (default: build)
# Environment: PARTS (tradeoffs epipolar prefiltered cost), GPU_OUT (out/gpu), FRAMES (20);
#   TRADEOFF_SIZES (1920x1080 3840x2160), TRADEOFFS_BUDGET_S (none); EPIPOLAR_SIZES (1280x720 1920x1080), EPIPOLAR_MAPS (2048 4096),
#   EPIPOLAR_RESOLUTIONS (full half);
#   PREFILTERED_SIZES (1280x720 1920x1080), PREFILTERED_MAPS (1024 2048); COST_SIZE (1920x1080),
#   COST_MAP (2048), SPACINGS (the cost part's forests); SCENES (names, space-separated) passes
#   through to the parts and the bench (each has its own default); PROFILES, BASES, REFERENCE_FRAMES
#   to the parts that take them (scripts/measure.sh --help).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/measure-common.sh
build="${1:-build}"
for p in tyndall-render tyndall-bench tyndall-compare; do program "$build" "$p" >/dev/null; done
out="${GPU_OUT:-out/gpu}"
frames="${FRAMES:-20}"
mkdir -p "$out/keep"
log="$out/keep/measure-gpu.log"
: >"$log"
say() { echo "$*" | tee -a "$log" >&2; }

for part in ${PARTS:-tradeoffs epipolar prefiltered cost}; do
  start=$SECONDS
  case "$part" in
    tradeoffs)
      sizes_text="${TRADEOFF_SIZES:-1920x1080 3840x2160}"
      read -r -a sizes <<<"${sizes_text//,/ }"
      for i in "${!sizes[@]}"; do
        size="${sizes[$i]}"
        args=(--sizes "$size" --shadow-maps 2048 --frames "$frames" --out "$out/tradeoffs-$size")
        [ -n "${SCENES:-}" ] && args+=(--scenes "${SCENES// /,}")
        limit=()
        if [ -n "${TRADEOFFS_BUDGET_S:-}" ]; then
          left=$((TRADEOFFS_BUDGET_S - (SECONDS - start)))
          [ "$i" -lt $((${#sizes[@]} - 1)) ] && left=$((left * 6 / 10))
          [ "$left" -ge 10 ] || { say "tradeoffs $size: no time left, not run"; continue; }
          limit=(timeout "$left")
        fi
        size_start=$SECONDS
        status=0
        "${limit[@]}" "$build/samples/tyndall-bench" "${args[@]}" 2>>"$log" | tail -n 3 >>"$log" || status=$?
        if [ -f "$out/tradeoffs-$size/results.json" ]; then
          cp "$out/tradeoffs-$size/results.json" "$out/keep/tradeoffs-$size-results.json"
        fi
        scenes_done="$(python3 -c 'import json,sys; print(len({r["scene"] for r in json.load(open(sys.argv[1]))["rows"]}))' \
          "$out/keep/tradeoffs-$size-results.json" 2>/dev/null || echo 0)"
        if [ "$status" -eq 124 ]; then
          say "tradeoffs $size: stopped at its limit after $((SECONDS - size_start)) s, $scenes_done scenes measured"
        elif [ "$status" -ne 0 ]; then
          say "tradeoffs $size: tyndall-bench failed (status $status), $scenes_done scenes measured"
        else
          say "tradeoffs $size: $((SECONDS - size_start)) s, $scenes_done scenes"
        fi
      done
      ;;
    epipolar)
      BENCH_OUT="$out/epipolar" FRAMES="$frames" REFERENCE_FRAMES="${REFERENCE_FRAMES:-12}" \
        SIZES="${EPIPOLAR_SIZES:-1280x720 1920x1080}" SHADOW_MAPS="${EPIPOLAR_MAPS:-2048 4096}" \
        RESOLUTIONS="${EPIPOLAR_RESOLUTIONS:-full half}" \
        scripts/measure.sh epipolar "$build" >"$out/keep/epipolar.md" 2>>"$log"
      cp "$out/epipolar/rows.jsonl" "$out/keep/epipolar-rows.jsonl"
      ;;
    prefiltered)
      : >"$out/keep/prefiltered.md"
      for size in ${PREFILTERED_SIZES:-1280x720 1920x1080}; do
        for map in ${PREFILTERED_MAPS:-1024 2048}; do
          printf '\n### %s, %s² map\n\n' "$size" "$map" >>"$out/keep/prefiltered.md"
          MEASURE_OUT="$out/prefiltered" SIZE="$size" SHADOW_MAP="$map" FRAMES="$frames" \
            SCENES="${SCENES:-pillars fence forest window-room}" \
            scripts/measure.sh prefiltered "$build" >>"$out/keep/prefiltered.md" 2>>"$log"
        done
      done
      ;;
    cost)
      COST_OUT="$out/cost" SIZE="${COST_SIZE:-1920x1080}" SHADOW_MAP="${COST_MAP:-2048}" FRAMES="$frames" \
        scripts/measure.sh cost "$build" >"$out/keep/cost-independence.md" 2>>"$log"
      ;;
    *) echo "unknown part: $part (tradeoffs, epipolar, prefiltered, cost)" >&2; exit 1 ;;
  esac
  say "$part: $((SECONDS - start)) s"
done
# The device, as the bench's results or the renders' timings name it.
device="$(python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
candidates = sorted(glob.glob(f"{out}/keep/tradeoffs-*-results.json")) + sorted(glob.glob(f"{out}/epipolar/*-reference.json")) + \
    sorted(glob.glob(f"{out}/prefiltered/*-reference.json")) + sorted(glob.glob(f"{out}/cost/defaults/*-reference.json"))
for path in candidates:
    if os.path.exists(path):
        print(json.load(open(path))["device"])
        break
else:
    print("unknown")
PY
)"
say "device: $device"
ls -la "$out/keep" >&2
