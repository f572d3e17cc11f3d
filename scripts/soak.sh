#!/usr/bin/env bash
# The long soak: tyndall-soak for 10,000 frames on lavapipe with validation (synchronization
# included), every assertion of samples/soak/soak.cpp on; prints its summary and the time it took.
# FRAMES and SEED change the run; extra arguments go to tyndall-soak. Build directory: BUILD (build).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build}"
frames="${FRAMES:-10000}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DTYNDALL_WERROR=ON >/dev/null
cmake --build "$build" --target tyndall-soak
export TYNDALL_DEVICE="${TYNDALL_DEVICE:-llvmpipe}"
start=$(date +%s)
"$build/samples/tyndall-soak" --frames "$frames" --seed "${SEED:-1}" "$@"
echo "scripts/soak.sh: $frames frames in $(( $(date +%s) - start )) s"
