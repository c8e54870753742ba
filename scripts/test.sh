#!/usr/bin/env bash
# Builds everything with warnings as errors and runs the whole CTest suite,
# then builds and runs the same suite again under AddressSanitizer and
# UndefinedBehaviorSanitizer in a second build tree.
#
#   scripts/test.sh            both builds
#   ADAPTOBS_SKIP_SANITIZERS=1 scripts/test.sh   the Release build only
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/lib/dependencies.sh"

ensure_packages "${ADAPTOBS_BUILD_PACKAGES[@]}" "${ADAPTOBS_TEST_PACKAGES[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

echo "== Release build, warnings as errors"
cmake -S "$root" -B "$root/build/test" -DCMAKE_BUILD_TYPE=Release -DADAPTOBS_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$root/build/test" -j "$jobs"
ctest --test-dir "$root/build/test" --output-on-failure -j "$jobs"

if [[ ${ADAPTOBS_SKIP_SANITIZERS:-0} != 1 ]]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build"
  # -O1 keeps the sanitized suite fast; Eigen's own assertions stay on (no NDEBUG).
  cmake -S "$root" -B "$root/build/sanitize" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
    -DADAPTOBS_SANITIZE=ON -DADAPTOBS_WARNINGS_AS_ERRORS=ON -DADAPTOBS_BUILD_BENCHMARKS=OFF \
    -DADAPTOBS_VERIFY_HEADERS=OFF >/dev/null
  cmake --build "$root/build/sanitize" -j "$jobs"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build/sanitize" --output-on-failure -j "$jobs"
fi

echo "== all tests passed in $((SECONDS - start)) s"
