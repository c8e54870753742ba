#!/usr/bin/env bash
# Formats every C++ file of the tree with clang-format 19 and the project's
# .clang-format, or, with --check, lists the files it would change and fails.
#
#   scripts/format.sh           format in place
#   scripts/format.sh --check   change nothing; exit 1 when a file is unformatted
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/lib/dependencies.sh"
ensure_packages clang-format-19:clang-format-19

cd "$root"
mapfile -t files < <(git ls-files '*.hpp' '*.cpp' '*.h')
if [[ ${1:-} == --check ]]; then
  unformatted=()
  for file in "${files[@]}"; do
    clang-format-19 --dry-run --Werror "$file" 2>/dev/null || unformatted+=("$file")
  done
  if ((${#unformatted[@]})); then
    echo "error: not formatted (run scripts/format.sh): ${unformatted[*]}" >&2
    exit 1
  fi
  echo "-- all ${#files[@]} C++ files formatted"
else
  clang-format-19 -i "${files[@]}"
fi
