#!/usr/bin/env bash
# The concurrency test (two contexts recording on two threads) built and run under
# ThreadSanitizer. lavapipe and the validation layer are not instrumented: races reported inside
# them alone are suppressed (scripts/tsan.supp); any report with Tyndall's or the host's code on
# it fails. Build directory: BUILD (build-tsan).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build-tsan}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTYNDALL_WERROR=ON -DTYNDALL_SANITIZE_THREAD=ON >/dev/null
cmake --build "$build" --target tyndall_concurrency_tests
export TYNDALL_DEVICE="${TYNDALL_DEVICE:-llvmpipe}"
export TSAN_OPTIONS="suppressions=$PWD/scripts/tsan.supp halt_on_error=1 exitcode=66 ${TSAN_OPTIONS:-}"
"$build/integration-tests/tyndall_concurrency_tests" "$@"
