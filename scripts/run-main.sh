#!/usr/bin/env bash
# The main job: installs what is missing, builds, and renders the default scene with the default
# profile on whatever Vulkan device is present (lavapipe on a machine without a GPU). Writes
# out/pillars.png, out/pillars.exr, out/pillars-scattering.exr and out/pillars-timings.json, and
# prints the per-pass timings.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --target tyndall-render -j"$(nproc)"
mkdir -p out
build/samples/tyndall-render samples/scenes/pillars.json \
  --output out/pillars.png --output-hdr out/pillars.exr \
  --aov-scattering out/pillars-scattering.exr --timings out/pillars-timings.json \
  --frames 5 "$@"
