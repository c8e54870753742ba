# Installs what is missing from Debian packages, or says what to install.
# Sourced by scripts/demo.sh and scripts/test.sh.
#
# ensure_packages PACKAGE...   each PACKAGE is "name" or "name:command" (a
# command whose presence is enough, e.g. any gnuplot variant for gnuplot-nox).

package_present() {
  local package=${1%%:*} command=""
  [[ $1 == *:* ]] && command=${1#*:}
  if [[ -n $command ]] && command -v "$command" >/dev/null 2>&1; then
    return 0
  fi
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"
}

ensure_packages() {
  local missing=() spec
  for spec in "$@"; do
    package_present "$spec" || missing+=("${spec%%:*}")
  done
  [[ ${#missing[@]} -eq 0 ]] && return 0

  if ! command -v apt-get >/dev/null 2>&1; then
    echo "error: missing packages: ${missing[*]} (and no apt-get on this machine); install them and retry." >&2
    exit 1
  fi
  if [[ $(id -u) -ne 0 ]]; then
    echo "error: missing Debian packages: ${missing[*]}" >&2
    echo "run:   sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "-- installing missing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; }; then
    echo "error: apt-get could not install: ${missing[*]}" >&2
    exit 1
  fi
}

# Packages every build needs.
ADAPTOBS_BUILD_PACKAGES=(cmake:cmake g++:g++ make:make libeigen3-dev)
# Packages of the test suite, examples and benchmarks.
ADAPTOBS_TEST_PACKAGES=(ninja-build:ninja libgtest-dev libbenchmark-dev gnuplot-nox:gnuplot libdsdp-dev)
# Boost.Odeint: the independent integrator of the continuous-time observers' RK4 test.
ADAPTOBS_TEST_PACKAGES+=(libboost-dev)
# The formatter whose output the tree is checked against (scripts/format.sh): one
# version, since each release formats some constructs differently.
ADAPTOBS_TEST_PACKAGES+=(clang-format-19:clang-format-19)
# MathJax 2, copied into the reference manual (when doxygen is installed) so that its
# formulas render offline (CMakeLists.txt, "The reference manual").
ADAPTOBS_TEST_PACKAGES+=(libjs-mathjax)
# The sanitizer build of scripts/test.sh: clang, its sanitizer runtimes, and LLVM's
# linker (an instrumented test executable links in about 1 s with it, 6 s with ld.bfd).
ADAPTOBS_SANITIZER_PACKAGES=(clang:clang++ libclang-rt-dev lld:ld.lld)

# python_environment DIR: makes the virtual environment DIR unless it exists
# (with Debian's python3-venv when the python3 on the PATH lacks venv) and
# prints its path.
python_environment() {
  local dir=$1
  # The extension module compiles against the interpreter's headers.
  if ! python3 -c 'import os, sysconfig; raise SystemExit(not os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")))'; then
    ensure_packages python3-dev >&2
  fi
  if [[ ! -x $dir/bin/python ]]; then
    if ! python3 -m venv "$dir" >/dev/null 2>&1; then
      rm -rf "$dir"
      ensure_packages python3-venv python3-pip >&2
      python3 -m venv "$dir" >&2
    fi
  fi
  echo "$dir"
}
