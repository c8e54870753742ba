#!/usr/bin/env bash
# Checks that every C++ file is formatted (scripts/format.sh), then builds the
# library, tests and examples with g++ (-O2, warnings as errors)
# and runs the CTest suite, then builds them again with clang++ under
# AddressSanitizer and UndefinedBehaviorSanitizer, with the benchmarks
# (uninstrumented) and every public header compiled on its own, and runs the
# suite there, the benchmark smoke run included, the example programs, the
# detectors' Monte-Carlo statistics, the Dey–Bhasin soak runs and the packaging
# test left to the g++ phase; last, under ThreadSanitizer,
# two threads sharing one observer's odeint_system, and the detection evaluation
# on two threads (tests/tsan).
#
# Between the two, the Python package is installed with `pip install .` into a
# virtual environment of its own (build/venv, made on first use) and its pytest
# suite runs from outside the source tree, so that the installed package is
# what is tested; the C++ examples of the g++ build are what it compares with.
#
#   scripts/test.sh                               both builds and the Python suite
#   ADAPTOBS_SKIP_SANITIZERS=1 scripts/test.sh    the g++ Release build and the Python suite
#   ADAPTOBS_SKIP_PYTHON=1 scripts/test.sh        no Python suite
#
# Why two compilers: g++ is the reference compiler for warnings and for the
# optimized code users get; clang instruments at -O0 in about a fifth of the
# time g++ needs at -O1 (benchmarks/compile_time.sh measures such ratios), and
# a second front end checks the warnings again.
#
# Why -O2 and not CMake's Release default of -O3: it is the level Debian and
# most distributions build with, the warnings that need optimization
# (-Wmaybe-uninitialized, -Warray-bounds) run from -O2 on, and it compiles
# about 10% faster.
#
# Why the benchmarks are built in the sanitizer phase only: their optimized
# build (-O3 -march=x86-64-v3, dozens of fixed-size instances) cost a third of
# the g++ phase, while all the suite asks of them is a smoke run that proves
# each one still compiles and executes. They are never instrumented (see
# benchmarks/CMakeLists.txt). Timing runs use an optimized build of their own
# (docs/benchmarks.md).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/lib/dependencies.sh"

sanitize=$([[ ${ADAPTOBS_SKIP_SANITIZERS:-0} == 1 ]] && echo 0 || echo 1)
packages=("${ADAPTOBS_BUILD_PACKAGES[@]}" "${ADAPTOBS_TEST_PACKAGES[@]}")
((sanitize)) && packages+=("${ADAPTOBS_SANITIZER_PACKAGES[@]}")
ensure_packages "${packages[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

echo "== formatting (clang-format 19, .clang-format)"
"$root/scripts/format.sh" --check

# configure DIR CMAKE_ARGUMENT...: a tree left by another generator is configured afresh.
configure() {
  local dir=$1
  shift
  if [[ -f $dir/CMakeCache.txt ]] && ! grep -qx "CMAKE_GENERATOR:INTERNAL=Ninja" "$dir/CMakeCache.txt"; then
    rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
  fi
  cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null
}

echo "== g++ -O2 build, warnings as errors"
# The header check (every public header compiled on its own) runs once, in the
# sanitizer build when there is one: clang parses the headers there at -O0 in
# 45 s of CPU, where g++ at -O2 takes 107.
# The --param flags only tune g++'s own memory: it collects its garbage each time
# its heap grows past a floor of at most 128 MB, and a 4 GB floor skips nearly
# every collection. The objects are byte for byte the same; the largest unit
# compiles with 8 % less CPU and 2.4 GB of memory instead of 2.0.
# Both builds compile each test executable as one translation unit
# (ADAPTOBS_UNITY_TESTS): the files of an executable instantiate much the same
# templates, which are then compiled once. Under g++ -O2 the tests took 645 to
# 702 CPU-seconds against 733 as separate units (two runs), the largest unit
# 3.4 GB of memory.
configure "$root/build/test" -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="--param=ggc-min-heapsize=4194304 --param=ggc-min-expand=400" \
  -DADAPTOBS_WARNINGS_AS_ERRORS=ON -DADAPTOBS_BUILD_BENCHMARKS=OFF -DADAPTOBS_VERIFY_HEADERS=$((sanitize ? 0 : 1)) \
  -DADAPTOBS_UNITY_TESTS=ON
cmake --build "$root/build/test" -j "$jobs"
ctest --test-dir "$root/build/test" --output-on-failure -j "$jobs"
# The reference manual, when doxygen is installed: any Doxygen warning fails the run.
if command -v doxygen > /dev/null; then
  cmake --build "$root/build/test" --target docs
fi
echo "-- g++ build and tests: $((SECONDS - start)) s"

if [[ ${ADAPTOBS_SKIP_PYTHON:-0} != 1 ]]; then
  echo "== Python package: pip install . and pytest"
  python_start=$SECONDS
  venv=$(python_environment "$root/build/venv")
  # PyPI's build isolation: scikit-build-core and nanobind come from the registry,
  # and the CMake build tree (build/python) is kept between runs.
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$root[fleet]" pytest
  (cd "$(mktemp -d)" && ADAPTOBS_EXAMPLES_DIR="$root/build/test/examples" \
    "$venv/bin/python" -m pytest -p no:cacheprovider "$root/python/tests")
  echo "-- Python package and tests: $((SECONDS - python_start)) s"
fi

if ((sanitize)); then
  echo "== clang++ AddressSanitizer + UndefinedBehaviorSanitizer build"
  # -O0 with line tables: the cheapest instrumented build whose reports still
  # name file and line (test_long_runs alone at -O1, see tests/CMakeLists.txt).
  # Eigen's own assertions stay on (no NDEBUG). The example programs run in the
  # g++ phase only: they drive library code the tests run here, and their own
  # compilation was a fifth of this phase's build. lld links the
  # instrumented executables five times faster than ld.bfd (a minute and a half
  # of CPU in all, several seconds of it at the end of the build, where nothing
  # else runs beside it).
  configure "$root/build/sanitize" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O0 -gline-tables-only" -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld \
    -DADAPTOBS_SANITIZE=ON -DADAPTOBS_WARNINGS_AS_ERRORS=ON -DADAPTOBS_BUILD_BENCHMARKS=ON \
    -DADAPTOBS_BUILD_EXAMPLES=OFF -DADAPTOBS_VERIFY_HEADERS=ON -DADAPTOBS_UNITY_TESTS=ON
  cmake --build "$root/build/sanitize" -j "$jobs"
  # The Monte-Carlo statistics of the fault detectors (thousands of seeds of one
  # scenario) and the soak runs of Dey & Bhasin (10⁵ and 10⁶ steps of one
  # observer) are asserted in the g++ phase. Under the sanitizers they would run
  # the same code paths again for a third of this phase's test time; the
  # single-seed tests, the contract suite and the examples cover those paths.
  repeated='^(SatelliteFaultDetection\.(FalseAlarmRatesMatchDesign|DefaultFaultDetectedAndIsolatedByTheCusumAndTheGlr|FiftySecondDriftDetected)|WwtpFaultDetection\.FalseAlarmRatesMatchDesign|DeyBhasinSiso\.CovarianceStaysSymmetricAndInsideKminK0For1e6Steps|DeyBhasin\.Theorem5BoundHoldsWithoutExcitationFor1e5Steps)$'
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build/sanitize" --output-on-failure -j "$jobs" -E "$repeated"

  echo "== clang++ ThreadSanitizer: two threads sharing one observer's odeint_system, and evaluate_detection on two threads"
  # A project of its own (tests/tsan): ThreadSanitizer excludes AddressSanitizer,
  # and its two executables compile in about a minute of CPU.
  cmake -S "$root/tests/tsan" -B "$root/build/tsan" -G Ninja -DCMAKE_CXX_COMPILER=clang++ >/dev/null
  cmake --build "$root/build/tsan"
  TSAN_OPTIONS=halt_on_error=1 "$root/build/tsan/tsan_shared_system"
  TSAN_OPTIONS=halt_on_error=1 "$root/build/tsan/tsan_evaluate_detection"
fi

echo "== all tests passed in $((SECONDS - start)) s"
