#!/usr/bin/env bash
# Issue 4's cost independence: the prefiltered evaluation pass's time over the four scenes with
# shafts and over forests of 56 to 10,094 trunks (scripts/generate-forest.py --spacing), with the
# defaults and with the published one-lookup evaluation (one reconstruction per pixel: no depth
# bounds, segments, trimming, short rays or texel walk), each a measure-prefiltered.sh table (the
# errors against the Reference beside the times) followed by the evaluation's spread over the scenes.
# Writes out/cost-independence/{forest-S.json,defaults.md,one-lookup.md} (COST_OUT).
# Usage: scripts/measure-cost-independence.sh [build-dir] (default: build)
# Environment: SIZE (640x360), SHADOW_MAP (2048), FRAMES (3), BASES (moments6_64),
#   SCENES (the sample scenes, "pillars fence forest window-room": the issue's four),
#   SPACINGS (the forests' grid spacings; "16 8 4 1.4 1": the sample forest is spacing 2).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${COST_OUT:-out/cost-independence}"
mkdir -p "$out"
scenes="${SCENES:-pillars fence forest window-room}"
for spacing in ${SPACINGS:-16 8 4 1.4 1}; do
  python3 scripts/generate-forest.py --spacing "$spacing" --out "$out/forest-$spacing.json" >/dev/null
  scenes+=" $out/forest-$spacing.json"
done
export SIZE="${SIZE:-640x360}" SHADOW_MAP="${SHADOW_MAP:-2048}" FRAMES="${FRAMES:-3}" BASES="${BASES:-moments6_64}"
export SCENES="$scenes"
# PrefilteredSettings with every per-ray decision off: klehm2014 and peters2017's evaluation.
one_lookup="taps=1,segments=0,depth-bounds=0,trim=0,texel-walk=0,short-rays=0"
# The second run compares against, and is timed beside, the first run's Reference renders.
for run in defaults one-lookup; do
  extra=""; reference_from=""
  [ "$run" = one-lookup ] && extra="$one_lookup" && reference_from="$out/defaults"
  echo "## $run${extra:+ ($extra)}"
  MEASURE_OUT="$out/$run" PREFILTERED="$extra" REFERENCE_FROM="$reference_from" \
    scripts/measure-prefiltered.sh "$build" | tee "$out/$run.md"
  # The issue's check is over its four scenes (the default SCENES); the forests show how the time
  # follows the trunks.
  evaluations="$out/$run/evaluations-$SIZE.tsv"
  python3 scripts/evaluation-spread.py "$evaluations" --exclude-prefix forest- --title "the sample scenes" |
    tee -a "$out/$run.md"
  python3 scripts/evaluation-spread.py "$evaluations" --prefix forest --title "the forests (forest is spacing 2)" |
    tee -a "$out/$run.md"
  echo
done
