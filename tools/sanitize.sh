#!/usr/bin/env bash
# Builds vksplat and its tests with ASan + UBSan in build-asan (VKSPLAT_ASAN_BUILD_DIR) and runs the
# test suite there. Extra arguments go to ctest, e.g. `tools/sanitize.sh -E golden` to leave out the
# real-scene golden renders, which take most of the time under the sanitizers.
# Leak checking is off by default: lavapipe leaks a few MB at exit from code that vkDestroyInstance has
# already unloaded, so LeakSanitizer can neither name nor suppress it. Set ASAN_OPTIONS=detect_leaks=1
# to check the tests that use no GPU (e.g. `-L "io|scene|camera|fuzz"`).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${VKSPLAT_ASAN_BUILD_DIR:-$root/build-asan}
jobs=${VKSPLAT_JOBS:-$(nproc)}

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKSPLAT_SANITIZE=ON \
  -DVKSPLAT_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j"$jobs"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 1800 "$@"
