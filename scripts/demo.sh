#!/usr/bin/env bash
# Builds the library's examples (Release) and runs the satellite example of
# Guyader & Zhang (2003): writes satellite.csv and satellite.png into the folder it prints.
#
#   scripts/demo.sh [OUTPUT_DIR]      (default: build/demo/output)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/lib/dependencies.sh"

ensure_packages "${ADAPTOBS_BUILD_PACKAGES[@]}" gnuplot-nox:gnuplot

build="$root/build/demo"
out=${1:-$build/output}
jobs=$(nproc 2>/dev/null || echo 2)

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DADAPTOBS_BUILD_TESTS=OFF -DADAPTOBS_BUILD_BENCHMARKS=OFF -DADAPTOBS_VERIFY_HEADERS=OFF \
  -DADAPTOBS_BUILD_EXAMPLES=ON >/dev/null
cmake --build "$build" --target satellite -j "$jobs"

mkdir -p "$out"
out=$(cd "$out" && pwd)
"$build/examples/satellite" --out "$out"
echo
echo "satellite example written to: $out"
ls -1 "$out"/satellite.*
