#!/usr/bin/env bash
# Generates docs/TRADEOFFS.md: runs tyndall-bench's default sweep (every sample scene except the
# analytic ones, the default parameter grid of the epipolar and prefiltered techniques, against the
# Reference and the full-screen floor pass) and copies its document and plots into docs/.
# Runs on whatever Vulkan device is present (TYNDALL_DEVICE picks one). On Mesa lavapipe with 2
# cores the default (640x360, 2048² maps) took 33 minutes on 2026-11-26 (the floor pass, the
# Reference and 23 configurations on each of 6 scenes, the prefiltered ones on the 4 directional
# ones; a third of it stained-glass's; the grid has one prefiltered configuration more since), 22
# minutes on 2026-11-27 (its rows are docs/data/tradeoffs-lavapipe-results.json); on a GPU pass
# SIZES=1920x1080 SHADOW_MAPS=2048 for the issue's goals.
# Usage: scripts/tradeoffs.sh [build-dir] (default: build)
# Environment: SIZES (640x360), SHADOW_MAPS (2048), FRAMES (20), SCENES (the bench's default);
#   FROM=out/tradeoffs/results.json writes the document again from an earlier run without measuring
#   (FROM=docs/data/tradeoffs-lavapipe-results.json: the run docs/TRADEOFFS.md shows);
#   DOC (docs/TRADEOFFS.md, whose choice is the code's profile table; another path keeps another
#   device's run beside it, e.g. DOC=docs/TRADEOFFS-H200.md for the GPU run it names).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
bench="$build/samples/tyndall-bench"
[ -x "$bench" ] || { echo "build first: $bench not found" >&2; exit 1; }
out="${BENCH_OUT:-out/tradeoffs}"
# Plots of an earlier run in the same folder (another size) would otherwise be copied to docs/.
rm -f "$out"/pareto-*.svg "$out"/pareto-*.png
if [ -n "${FROM:-}" ]; then
  "$bench" --from "$FROM" --out "$out"
else
  args=(--sizes "${SIZES:-640x360}" --shadow-maps "${SHADOW_MAPS:-2048}" --frames "${FRAMES:-20}" --out "$out")
  [ -n "${SCENES:-}" ] && args+=(--scenes "$SCENES")
  "$bench" "${args[@]}"
fi
doc="${DOC:-docs/TRADEOFFS.md}"
if [ "$doc" = docs/TRADEOFFS.md ]; then
  cp "$out/tradeoffs.md" "$doc"
else
  # Another device's or size's run: its choice is a measurement, not the code's profile table.
  { head -n 1 "$out/tradeoffs.md"
    printf '\n> A run on another device or size than docs/TRADEOFFS.md, kept for its measurements: its "choice" is what this run would pick, not `plugin/src/profiles.cpp`'"'"'s table (docs/TRADEOFFS.md is). Written by `DOC=%s scripts/tradeoffs.sh` (with `FROM=results.json` of a run on that device, or run there with SIZES and SHADOW_MAPS).\n' "$doc"
    tail -n +2 "$out/tradeoffs.md"; } >"$doc"
fi
cp "$out"/pareto-*.svg "$out"/pareto-*.png docs/
echo "wrote $doc and docs/pareto-*.svg/.png from $out"
