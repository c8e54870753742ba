#!/usr/bin/env bash
# Compile-time cost of adaptobs against the same jobs written with Eigen alone.
#
# Usage: benchmarks/compile_time.sh [-n RUNS] [PAIR...]
#   PAIR: readme guyader_zhang dey_bhasin takagi_sugeno bastin_gevers include (default: all)
#   RUNS (or env RUNS, default 3): compilations of each file, library and hand-written alternately.
#   CXX (default g++) and CXXFLAGS (default -std=c++20 -O2) may be set in the environment.
#
# Each file is compiled alone (-c, -o /dev/null) under /usr/bin/time; the table
# gives medians over the runs of the CPU time (user + sys) and of the peak memory.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir=benchmarks/compile_time
runs="${RUNS:-3}"
while getopts n: option; do
  case "$option" in
    n) runs="$OPTARG" ;;
    *) echo "usage: $0 [-n RUNS] [PAIR...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "$0: RUNS must be a positive integer (got '$runs')" >&2; exit 2; }

if [[ ! -x /usr/bin/time ]]; then
  echo "$0: /usr/bin/time is missing; install the Debian package 'time' (apt-get install time)" >&2
  exit 1
fi

cxx="${CXX:-g++}"
read -r -a flags <<< "${CXXFLAGS:--std=c++20 -O2}"
read -r -a eigen <<< "$(pkg-config --cflags eigen3 2> /dev/null || echo -I/usr/include/eigen3)"
cd "$root"

# Pair name -> "library_file hand_written_file".
declare -A pairs=(
  [readme]="examples/readme_usage.cpp $dir/readme_usage_eigen.cpp"
  [guyader_zhang]="$dir/guyader_zhang_observer.cpp $dir/guyader_zhang_eigen.cpp"
  [dey_bhasin]="$dir/dey_bhasin_observer.cpp $dir/dey_bhasin_eigen.cpp"
  [takagi_sugeno]="$dir/takagi_sugeno_observer.cpp $dir/takagi_sugeno_eigen.cpp"
  [bastin_gevers]="$dir/bastin_gevers_observer.cpp $dir/bastin_gevers_eigen.cpp"
  [include]="$dir/umbrella_include.cpp $dir/eigen_dense_include.cpp"
)
all=(readme guyader_zhang dey_bhasin takagi_sugeno bastin_gevers include)
order=("${@:-${all[@]}}")
for name in "${order[@]}"; do
  [[ -n "${pairs[$name]:-}" ]] || { echo "$0: unknown pair '$name' (known: ${all[*]})" >&2; exit 2; }
done

measurement="$(mktemp)"
trap 'rm -f "$measurement"' EXIT

# Compiles $1 once; prints "cpu_seconds peak_kb".
measure() {
  if ! /usr/bin/time -f '%U %S %M' -o "$measurement" \
      "$cxx" "${flags[@]}" -I include "${eigen[@]}" -c "$1" -o /dev/null; then
    echo "$0: compiling $1 failed" >&2
    exit 1
  fi
  awk '{ printf "%.2f %d\n", $1 + $2, $3 }' "$measurement"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| program | library median CPU s | hand-written median CPU s | CPU ratio | library peak MB | hand-written peak MB | memory ratio |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for name in "${order[@]}"; do
  read -r library hand <<< "${pairs[$name]}"
  lib_cpu=() lib_mem=() hand_cpu=() hand_mem=()
  for ((run = 1; run <= runs; ++run)); do
    echo "$name: run $run of $runs" >&2
    result=$(measure "$library")
    lib_cpu+=("${result% *}") lib_mem+=("${result#* }")
    result=$(measure "$hand")
    hand_cpu+=("${result% *}") hand_mem+=("${result#* }")
  done
  lc=$(printf '%s\n' "${lib_cpu[@]}" | median) hc=$(printf '%s\n' "${hand_cpu[@]}" | median)
  lm=$(printf '%s\n' "${lib_mem[@]}" | median) hm=$(printf '%s\n' "${hand_mem[@]}" | median)
  label="$name"
  [[ "$library" == *_draft.cpp ]] && label+=" (draft)"
  awk -v n="$label" -v lc="$lc" -v hc="$hc" -v lm="$lm" -v hm="$hm" 'BEGIN {
    printf "| %s | %.2f | %.2f | %.2f | %.0f | %.0f | %.2f |\n", n, lc, hc, lc / hc, lm / 1024, hm / 1024, lm / hm }'
done
