#!/usr/bin/env bash
# scripts/measure.sh cost end to end at a tiny size: both configurations measured on
# sample scenes and a generated forest, a row each, and the evaluation's spread printed over the
# sample scenes and over the forests; scripts/generate-forest.py reproduces the committed
# forest (its --spacing option must not change the default).
# Usage: check_cost_independence.sh BUILD_DIR WORK_DIR (absolute paths)
set -euo pipefail
build="$1"
work="$2"
repo="$(cd "$(dirname "$0")/.." && pwd)"
fail() { echo "FAIL: $*" >&2; exit 1; }
python3 "$repo/scripts/generate-forest.py" --check || fail "samples/scenes/forest.json is not the generator's"
rm -rf "$work"
COST_OUT="$work" SIZE=32x18 SHADOW_MAP=256 FRAMES=1 SPACINGS="16 8" \
  "$repo/scripts/measure.sh" cost "$build"
for run in defaults one-lookup; do
  for scene in pillars fence forest window-room forest-16 forest-8; do
    grep -q "^| $scene | moments6_64 | [0-9.]*% | " "$work/$run.md" || fail "no $scene row in $work/$run.md"
  done
  grep -q "^moments6_64, the sample scenes: evaluate .* / median [0-9]*% (issue 4 asks < 15%)$" "$work/$run.md" ||
    fail "no spread over the sample scenes in $work/$run.md"
  grep -q "^moments6_64, the forests (forest is spacing 2): evaluate .* / median [0-9]*% (issue 4 asks < 15%)$" "$work/$run.md" ||
    fail "no spread over the forests in $work/$run.md"
done
# The one-lookup run took its settings: the stats' note names no per-ray decision; the defaults' all.
note() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["techniqueNote"])' "$work/$1/pillars-32x18-moments6_64.json"; }
for part in "row depth bounds" "segmented reconstruction" "trimmed segments" "texel walk" "rays within"; do
  note defaults | grep -q "$part" || fail "the defaults' note lacks '$part': $(note defaults)"
  ! note one-lookup | grep -q "$part" || fail "the one-lookup note has '$part': $(note one-lookup)"
done
# The one-lookup run compared against the defaults' Reference renders and rendered none of its own.
! ls "$work/one-lookup/"*-reference.* >/dev/null 2>&1 || fail "the one-lookup run rendered the Reference again"
echo "measure.sh cost: ok"
