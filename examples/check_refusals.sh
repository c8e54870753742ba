#!/bin/sh
# Runs one example program with bad flag values and asserts, for each, exit
# code 2, nothing on stdout (the values are checked before any work) and exactly
# the expected line on stderr; then that --help gives every flag its range.
#
# Usage: check_refusals.sh DIR EXAMPLE    (DIR: the folder of the built examples)
set -u
dir=$1
example=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cases=0
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# refuses PROGRAM MESSAGE FLAG...: `PROGRAM FLAG...` exits with 2 and the one
# line "PROGRAM: MESSAGE (try --help)" on stderr.
refuses() {
  program=$1
  message=$2
  shift 2
  [ "$program" = "$example" ] || return 0
  cases=$((cases + 1))
  "$dir/$program" --out "$scratch/out" "$@" >"$scratch/stdout" 2>"$scratch/stderr"
  rc=$?
  expected="$program: $message (try --help)"
  if [ "$rc" -ne 2 ] || [ -s "$scratch/stdout" ] || [ "$(wc -l <"$scratch/stderr")" -ne 1 ] ||
    [ "$(cat "$scratch/stderr")" != "$expected" ]; then
    fail "$program $* (exit code $rc)"
    echo "  expected on stderr: $expected"
    echo "  got on stderr:      $(cat "$scratch/stderr")"
    [ -s "$scratch/stdout" ] && echo "  and on stdout:      $(head -c 300 "$scratch/stdout")"
  else
    echo "ok: $program $* -> $message"
  fi
}

# describes PROGRAM FLAG...: `PROGRAM --help` exits with 0 and gives each flag
# a line with its range (a switch: "switch:").
describes() {
  program=$1
  shift
  [ "$program" = "$example" ] || return 0
  cases=$((cases + 1))
  if ! "$dir/$program" --help >"$scratch/help" 2>&1; then
    fail "$program --help did not exit with 0"
    return
  fi
  for flag in out "$@"; do
    grep "^  --$flag " "$scratch/help" >"$scratch/line" || {
      fail "$program --help has no line for --$flag"
      continue
    }
    grep -q -e ': in [[(]' -e ': an integer in \[' -e ': none or T0,T1' -e ' switch: ' -e ': a writable directory' \
      -e ': 0 (the whole sample)' "$scratch/line" || fail "$program --help gives --$flag no range: $(cat "$scratch/line")"
  done
  echo "ok: $program --help describes --out $*"
}

# Bad values that every example refuses in the same way.
common() {
  program=$1
  refuses "$program" "unknown option '--bogus'" --bogus 1
  refuses "$program" "unknown option 'stray'" stray
  refuses "$program" "--out must be a writable directory, got $0/sub: cannot create it: Not a directory" --out "$0/sub"
}

# The continuous-time examples: --seconds, --noise and --seed.
continuous() {
  program=$1
  common "$program"
  refuses "$program" "--noise must be in [0, 1000], got -1" --noise -1
  refuses "$program" "--noise must be in [0, 1000], got nan" --noise nan
  refuses "$program" "--seconds (s) must be in [1, 1e5], got 0" --seconds 0
  refuses "$program" "--seconds (s) must be in [1, 1e5], got 1e9" --seconds 1e9
  refuses "$program" "--seconds (s) must be in [1, 1e5], got 10s" --seconds 10s
  refuses "$program" "--seed must be an integer in [0, 1e15], got 1.5" --seed 1.5
  refuses "$program" "option --seed needs a value" --seed
}

common satellite
refuses satellite "--drop must be in [0, 1), got 2" --drop 2
refuses satellite "--drop must be in [0, 1), got 1" --drop 1
refuses satellite "--noise must be in [0, 1000], got -1" --noise -1
refuses satellite "--seconds (s) must be in [1, 1e6], got 0" --seconds 0
refuses satellite "--seconds (s) must be in [1, 1e6], got abc" --seconds abc
refuses satellite "--seed must be an integer in [0, 1e15], got -1" --seed -1
refuses satellite "--seed must be an integer in [0, 1e15], got 1.5" --seed 1.5
refuses satellite "--outage (s) must be none or T0,T1 with 0 <= T0 <= T1, got 120,100" --outage 120,100
refuses satellite "--outage (s) must be none or T0,T1 with 0 <= T0 <= T1, got 100" --outage 100
refuses satellite "--outage (s) must be none or T0,T1 with 0 <= T0 <= T1, got -5,10" --outage -5,10
refuses satellite "--outage (s) must be none or T0,T1 with 0 <= T0 <= T1 and T0 < 300 (inside the run), got 400,500" \
  --outage 400,500
refuses satellite "option --drop needs a value" --drop
describes satellite seconds seed noise drop outage

common guiro
refuses guiro "--jitter must be in [0, 1), got 2" --jitter 2
refuses guiro "--jitter must be in [0, 1), got -0.1" --jitter -0.1
refuses guiro "--samples must be an integer in [1, 1e5], got 0" --samples 0
refuses guiro "--samples must be an integer in [1, 1e5], got 1.5" --samples 1.5
refuses guiro "--tolerance must be in [0, 1), got -1" --tolerance -1
refuses guiro "--drop must be in [0, 1), got 2" --drop 2
refuses guiro "--outage (sample times, T = 1) must be none or T0,T1 with 0 <= T0 <= T1, got 30,20" --outage 30,20
refuses guiro \
  "--outage (sample times, T = 1) must be none or T0,T1 with 0 <= T0 <= T1 and T0 < 61 (inside the run), got 70,80" \
  --outage 70,80
refuses guiro "--seed must be an integer in [0, 1e15], got x" --seed x
describes guiro samples tolerance jitter seed drop outage

common dey_bhasin_mimo
refuses dey_bhasin_mimo "--channel must be 0 (the whole sample) or an output channel, 1 or 2, got 5" --channel 5
refuses dey_bhasin_mimo "--channel must be 0 (the whole sample) or an output channel, 1 or 2, got -1" --channel -1
refuses dey_bhasin_mimo "--channel must be 0 (the whole sample) or an output channel, 1 or 2, got 1.5" --channel 1.5
refuses dey_bhasin_mimo "--steps must be an integer in [10, 1e7], got 0" --steps 0
refuses dey_bhasin_mimo "--steps must be an integer in [10, 1e7], got -1" --steps -1
refuses dey_bhasin_mimo "--drop must be in [0, 1), got -0.1" --drop -0.1
refuses dey_bhasin_mimo "--outage (samples) must be none or T0,T1 with 0 <= T0 <= T1, got 5,1" --outage 5,1
refuses dey_bhasin_mimo \
  "--outage (samples) must be none or T0,T1 with 0 <= T0 <= T1 and T0 < 1000 (inside the run), got 2000,3000" \
  --outage 2000,3000
describes dey_bhasin_mimo steps channel seed drop outage

common suzuki_siso
refuses suzuki_siso "--lambda must be in (0, 1], got 0" --lambda 0
refuses suzuki_siso "--lambda must be in (0, 1], got 1.5" --lambda 1.5
refuses suzuki_siso "--steps must be an integer in [10, 1e7], got 1.5" --steps 1.5
refuses suzuki_siso "--steps must be an integer in [10, 1e7], got 0" --steps 0
refuses suzuki_siso "--steps must be an integer in [10, 1e7], got 5" --steps 5
describes suzuki_siso steps lambda

common wwtp
refuses wwtp "--theta must be in [-0.225, 0.3], got 0.5" --theta 0.5
refuses wwtp "--theta must be in [-0.225, 0.3], got -1" --theta -1
refuses wwtp "--steps must be an integer in [10, 1e7], got 0" --steps 0
refuses wwtp "--drop must be in [0, 1), got 2" --drop 2
refuses wwtp "--outage (samples) must be none or T0,T1 with 0 <= T0 <= T1 and T0 < 500 (inside the run), got 600,700" \
  --outage 600,700
refuses wwtp "--seed must be an integer in [0, 1e15], got -3" --seed -3
describes wwtp theta steps seed drop outage

continuous bastin_gevers
describes bastin_gevers seconds noise seed
continuous marino_tomei
describes marino_tomei seconds noise seed
continuous besancon
describes besancon seconds noise seed
continuous unified_comparison
describes unified_comparison seconds noise seed
continuous zhang_continuous
refuses zhang_continuous "--gamma must be in (0, 500], got 0" --gamma 0
refuses zhang_continuous "--gamma must be in (0, 500], got 1000" --gamma 1000
describes zhang_continuous seconds gamma noise seed

common dc_motor
refuses dc_motor "--seconds (s) must be in [5, 10000], got 1" --seconds 1
refuses dc_motor "--seed must be an integer in [0, 1e15], got -1" --seed -1
refuses dc_motor "--fault-time (s) must be in [2, 10000], got 1" --fault-time 1
refuses dc_motor "--fault-time (s) must be in [2, 29) (at least 1 s before the end of the run, --seconds), got 40" --fault-time 40
refuses dc_motor "--friction-factor must be in (0, 100], got 0" --friction-factor 0
describes dc_motor seconds seed fault-time friction-factor

common satellite_fault
refuses satellite_fault "--seeds must be an integer in [0, 1e6], got -1" --seeds -1
refuses satellite_fault "--seeds must be an integer in [0, 1e6], got 1.5" --seeds 1.5
refuses satellite_fault "--fault-param must be an integer in [1, 2], got 3" --fault-param 3
refuses satellite_fault "--fault-time (s) must be in [100, 300) (inside the run, --seconds), got 400" --fault-time 400
refuses satellite_fault "--fault-time (s) must be in [100, 1e6], got 50" --fault-time 50
refuses satellite_fault "--fault-size must be in (-1, 10), got -1" --fault-size -1
refuses satellite_fault "--mtbfa (s) must be in [20, 1e6], got 0" --mtbfa 0
refuses satellite_fault "--threads must be an integer in [0, 1024], got -1" --threads -1
refuses satellite_fault "--threads must be an integer in [0, 1024], got 0.5" --threads 0.5
refuses satellite_fault "--seconds (s) must be in [1, 1e6], got -300" --seconds -300
describes satellite_fault fault-param fault-time fault-size drift seconds seed seeds mtbfa threads

common wwtp_fault
refuses wwtp_fault "--seeds must be an integer in [0, 1e6], got -1" --seeds -1
refuses wwtp_fault "--seeds must be an integer in [0, 1e6], got 1.5" --seeds 1.5
refuses wwtp_fault "--fault-time (samples) must be an integer in [300, 800) (inside the run, --steps), got 900" \
  --fault-time 900
refuses wwtp_fault "--fault-time (samples) must be an integer in [300, 1e7], got 100" --fault-time 100
refuses wwtp_fault "--fault-time (samples) must be an integer in [300, 1e7], got 400.5" --fault-time 400.5
refuses wwtp_fault "--fault-size must be in [-0.225, 0.3], got 0.5" --fault-size 0.5
refuses wwtp_fault "--mtbfa (samples) must be in [200, 1e7], got 10" --mtbfa 10
refuses wwtp_fault "--steps (samples) must be an integer in [1, 1e7], got 0" --steps 0
describes wwtp_fault fault-time fault-size drift steps seed seeds mtbfa threads

if [ "$cases" -eq 0 ]; then
  fail "no cases for the example '$example'"
fi
[ "$failures" -eq 0 ] || {
  echo "$failures of $cases cases failed"
  exit 1
}
echo "all $cases cases of $example passed"
