#!/usr/bin/env bash
# Fuzzes the scene loader (JSON; glTF with binary buffers) and frame validation with libFuzzer under
# AddressSanitizer and UndefinedBehaviorSanitizer (clang, from scripts/install-deps.sh), each target
# for FUZZ_SECONDS (600) on a copy of its committed corpus, niced. Prints each run's last libFuzzer
# status line (executions, coverage); a crash leaves its input in out/fuzz/TARGET/ (copy it into
# integration-tests/fuzz/corpus/TARGET/, where ctest replays it). TARGETS picks some.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build-fuzz}"
seconds="${FUZZ_SECONDS:-600}"
targets="${TARGETS:-scene gltf frame}"
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTYNDALL_FUZZ=ON \
  -DTYNDALL_SANITIZE=ON >/dev/null
for target in $targets; do cmake --build "$build" --target "tyndall_fuzz_$target"; done
for target in $targets; do
  out="out/fuzz/$target"
  mkdir -p "$out/corpus"
  cp -n integration-tests/fuzz/corpus/"$target"/* "$out/corpus/" 2>/dev/null || true
  [ "$target" = scene ] && cp -n samples/scenes/*.json "$out/corpus/"
  # The scene target resolves glTF paths against samples/scenes; the others read only their input.
  (cd "$out" && nice -n 10 "$OLDPWD/$build/integration-tests/tyndall_fuzz_$target" corpus \
     -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix=./ >log.txt 2>&1; echo "exit $?" >>log.txt) &
done
wait
for target in $targets; do
  echo "== $target: $(grep -E '^#[0-9]+[[:space:]]+DONE' "out/fuzz/$target/log.txt" | tail -1)"
  grep -E '^stat::number_of_executed_units|^exit|SUMMARY' "out/fuzz/$target/log.txt" || true
done
