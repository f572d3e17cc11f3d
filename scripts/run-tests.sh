#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds with warnings as errors, runs the unit
# tests under AddressSanitizer + UndefinedBehaviorSanitizer, then ctest (unit, integration on
# lavapipe with validation layers, consumer). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

# Sanitizers on the CPU code (the integration tests run inside lavapipe, whose LLVM JIT is not
# instrumented, so they run in the plain build below).
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTYNDALL_WERROR=ON -DTYNDALL_SANITIZE=ON
cmake --build build-sanitize --target tyndall_unit_tests -j"$jobs"
build-sanitize/integration-tests/tyndall_unit_tests --gtest_brief=1

cmake -S . -B build-tests -DCMAKE_BUILD_TYPE=Release -DTYNDALL_WERROR=ON
cmake --build build-tests -j"$jobs"
# Integration tests run on the CPU driver so that CI and every developer see the same device.
export TYNDALL_DEVICE="${TYNDALL_DEVICE:-llvmpipe}"
ctest --test-dir build-tests --output-on-failure -j2 "$@"
