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
# The host stub on lavapipe grows by about 0.85 MiB a frame with or without Tyndall (tyndall-render
# on pillars at 64x36: 426 MiB more RSS at 600 frames than at 100, with --no-effect too), so the
# long run's bound on RSS growth is the host's growth over 10,000 frames, not Tyndall's.
"$build/samples/tyndall-soak" --frames "$frames" --seed "${SEED:-1}" --rss-bound-mib "${RSS_BOUND_MIB:-12288}" "$@"
echo "scripts/soak.sh: $frames frames in $(( $(date +%s) - start )) s"
