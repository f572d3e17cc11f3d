#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds with warnings as errors, runs ctest
# (unit, integration on lavapipe with validation layers, consumer). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-tests -DCMAKE_BUILD_TYPE=Release -DTYNDALL_WERROR=ON
cmake --build build-tests -j"$(nproc)"
# Integration tests run on the CPU driver so that CI and every developer see the same device.
export TYNDALL_DEVICE="${TYNDALL_DEVICE:-llvmpipe}"
ctest --test-dir build-tests --output-on-failure -j2 "$@"
