#!/usr/bin/env bash
# scripts/bundle-binaries.sh and scripts/measure-gpu.sh end to end at a tiny size: the bundle loads
# every library but the C runtime from itself (bundle-binaries.sh fails otherwise), its programs
# run from it, and measure-gpu.sh gathers a table row per run (the cost part's two runs too) and
# names the device, its tradeoffs part keeps to TRADEOFFS_BUDGET_S; scripts/measure.sh's reference,
# translucent and memory parts print a row per run, and an unknown part is refused with the usage text.
# Usage: check_measure_scripts.sh BUILD_DIR WORK_DIR (absolute paths)
set -euo pipefail
build="$1"
work="$2"
repo="$(cd "$(dirname "$0")/.." && pwd)"
rm -rf "$work"
"$repo/scripts/bundle-binaries.sh" "$build" "$work/bundle"
LD_LIBRARY_PATH="$work/bundle/lib" GPU_OUT="$work/gpu" PARTS="epipolar prefiltered cost" FRAMES=2 REFERENCE_FRAMES=2 \
  EPIPOLAR_SIZES=32x18 EPIPOLAR_MAPS=256 PREFILTERED_SIZES=32x18 PREFILTERED_MAPS=256 SCENES=pillars \
  COST_SIZE=32x18 COST_MAP=256 SPACINGS=16 \
  PROFILES=performance BASES=moments4_64 "$repo/scripts/measure-gpu.sh" "$work/bundle"
keep="$work/gpu/keep"
fail() { echo "FAIL: $*" >&2; exit 1; }
grep -q '^| pillars | 32x18 | 256² | performance | ' "$keep/epipolar.md" || fail "no epipolar row in $keep/epipolar.md"
# EPIPOLAR_RESOLUTIONS' default (full half): the profile again at half resolution.
grep -q '^| pillars | 32x18 | 256² | performance half | ' "$keep/epipolar.md" ||
  fail "no half-resolution epipolar row in $keep/epipolar.md"
[ "$(wc -l <"$keep/epipolar-rows.jsonl")" -eq 2 ] || fail "expected two rows in $keep/epipolar-rows.jsonl"
grep -q '^| pillars | moments4_64 | [0-9.]*% | ' "$keep/prefiltered.md" || fail "no prefiltered row in $keep/prefiltered.md"
grep -q '^### 32x18, 256² map' "$keep/prefiltered.md" || fail "no size heading in $keep/prefiltered.md"
grep -q '^epipolar: [0-9]* s$' "$keep/measure-gpu.log" || fail "no epipolar timing in the log"
grep -q '^prefiltered: [0-9]* s$' "$keep/measure-gpu.log" || fail "no prefiltered timing in the log"
for run in defaults one-lookup; do
  grep -q "^## $run" "$keep/cost-independence.md" || fail "no $run run in $keep/cost-independence.md"
done
[ "$(grep -c '^| forest-16 | [a-z0-9_]* | [0-9.]*% | ' "$keep/cost-independence.md")" -eq 2 ] ||
  fail "expected a forest-16 row per run in $keep/cost-independence.md"
grep -q '^cost: [0-9]* s$' "$keep/measure-gpu.log" || fail "no cost timing in the log"
grep -q '^device: ' "$keep/measure-gpu.log" && ! grep -q '^device: unknown' "$keep/measure-gpu.log" ||
  fail "the log does not name the device"
# The tradeoffs part within TRADEOFFS_BUDGET_S: each size a bench run of its own, the first given
# 60% of the budget, the last the rest, each stopped at its limit and said so in the log.
start=$SECONDS
LD_LIBRARY_PATH="$work/bundle/lib" GPU_OUT="$work/gpu-tradeoffs" PARTS=tradeoffs TRADEOFF_SIZES="32x18 48x27" \
  TRADEOFFS_BUDGET_S=30 SCENES=pillars FRAMES=1 "$repo/scripts/measure-gpu.sh" "$work/bundle"
[ $((SECONDS - start)) -lt 60 ] || fail "the tradeoffs part took $((SECONDS - start)) s with a 30 s budget"
tradeoffs_log="$work/gpu-tradeoffs/keep/measure-gpu.log"
for size in 32x18 48x27; do
  grep -E -q "^tradeoffs $size: (stopped at its limit after [0-9]+ s, [0-9]+ scenes measured|[0-9]+ s, 1 scenes)\$" \
    "$tradeoffs_log" || fail "no line for $size in $tradeoffs_log"
done
table="$(LD_LIBRARY_PATH="$work/bundle/lib" REFERENCE_OUT="$work/reference" SCENES=pillars SIZES=32x18 FRAMES=2 \
  "$repo/scripts/measure.sh" reference "$work/bundle")"
grep -q '^| pillars | 32x18 | 2048 | [0-9.]* | ' <<<"$table" || fail "no reference row: $table"
table="$(LD_LIBRARY_PATH="$work/bundle/lib" MEMORY_OUT="$work/memory" SCENES=pillars SIZES=32x18 \
  PROFILES=performance SHADOW_MAP=256 \
  "$repo/scripts/measure.sh" memory "$work/bundle")"
grep -q '^| pillars | performance | epipolar | [0-9.]* |$' <<<"$table" || fail "no memory row: $table"
table="$(LD_LIBRARY_PATH="$work/bundle/lib" TRANSLUCENT_OUT="$work/translucent" SIZE=32x18 SHADOW_MAP=256 LAYERS=1 \
  FRAMES=2 "$repo/scripts/measure.sh" translucent "$work/bundle")"
grep -q '^| analytic-glass | 32x18 | 256 | 0 (opaque) | [0-9.]* | 1.00x |$' <<<"$table" || fail "no opaque row: $table"
grep -q '^| analytic-glass | 32x18 | 256 | 1 | [0-9.]* | [0-9.]*x |$' <<<"$table" || fail "no translucent row: $table"
status=0
"$repo/scripts/measure.sh" no-such-part >/dev/null 2>"$work/usage.txt" || status=$?
[ "$status" -eq 2 ] && grep -q '^usage: scripts/measure.sh PART' "$work/usage.txt" &&
  grep -q 'unknown part: no-such-part' "$work/usage.txt" || fail "an unknown part was not refused (status $status)"
echo "bundle, measure-gpu.sh and measure.sh: ok"
