#!/usr/bin/env bash
# Generates docs/TRADEOFFS.md: runs tyndall-bench's default sweep (every sample scene except the
# analytic ones, the default parameter grid of the epipolar and prefiltered techniques, against the
# Reference and the full-screen floor pass) and copies its document and plots into docs/.
# Runs on whatever Vulkan device is present (TYNDALL_DEVICE picks one). On Mesa lavapipe with 2
# cores the default (640x360, 2048² maps) takes about 40 minutes; on a GPU pass
# SIZES=1920x1080 SHADOW_MAPS=2048 for the issue's goals.
# Usage: scripts/tradeoffs.sh [build-dir] (default: build)
# Environment: SIZES (640x360), SHADOW_MAPS (2048), FRAMES (20), SCENES (the bench's default);
#   FROM=out/tradeoffs/results.json writes the document again from an earlier run without measuring.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
bench="$build/samples/tyndall-bench"
[ -x "$bench" ] || { echo "build first: $bench not found" >&2; exit 1; }
out="${BENCH_OUT:-out/tradeoffs}"
if [ -n "${FROM:-}" ]; then
  "$bench" --from "$FROM" --out "$out"
else
  args=(--sizes "${SIZES:-640x360}" --shadow-maps "${SHADOW_MAPS:-2048}" --frames "${FRAMES:-20}" --out "$out")
  [ -n "${SCENES:-}" ] && args+=(--scenes "$SCENES")
  "$bench" "${args[@]}"
fi
cp "$out/tradeoffs.md" docs/TRADEOFFS.md
cp "$out"/pareto-*.svg "$out"/pareto-*.png docs/
echo "wrote docs/TRADEOFFS.md and docs/pareto-*.svg/.png from $out"
