#!/usr/bin/env bash
# tools/soak_selftest.sh BUILD_DIR — checks tools/soak.sh itself (ctest soak_selftest, ~2 s):
# a 3-cycle soak of the reduced sample passes; the same outputs with a NaN in cycles.csv, with
# an overlap above the limit, with a cycle missing, or with an impossible result in
# summary.txt fail; a bad argument exits 2.
set -u
build=${1:?usage: soak_selftest.sh BUILD_DIR}
here=$(cd "$(dirname "$0")" && pwd)
soak="$here/soak.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bad=0
expect() {  # expect STATUS DESCRIPTION TEXT COMMAND...: exit STATUS, TEXT in the output
  local want=$1 what=$2 text=$3
  shift 3
  "$@" > "$tmp/log" 2>&1
  local got=$?
  if [ "$got" != "$want" ] || ! grep -qF -- "$text" "$tmp/log"; then
    echo "soak_selftest: $what: exit $got, expected $want with '$text' in:"
    cat "$tmp/log"
    bad=1
  else
    echo "soak_selftest: $what: exit $got as expected"
  fi
}

expect 0 "3 cycles of the reduced sample" "soak.sh: PASS" "$soak" -b "$build" -o "$tmp/run" -n 3
expect 1 "asking the check for 4 cycles of a 3-cycle run" "has 3 cycles, 4 wanted" "$soak" -c -o "$tmp/run" -n 4
expect 1 "an overlap limit below the run's largest overlap" "m > 1e-15 m" "$soak" -c -o "$tmp/run" -n 3 -l 1e-15

cp -r "$tmp/run" "$tmp/nan"
awk -F, -v OFS=, 'NR == 3 { $8 = "nan" } { print }' "$tmp/run/cycles.csv" > "$tmp/nan/cycles.csv"
expect 1 "a NaN in cycles.csv" "cycle 2: non-finite nan" "$soak" -c -o "$tmp/nan" -n 3

cp -r "$tmp/run" "$tmp/impossible"
sed -i 's/^result = valid$/result = impossible: cycle 2: a grain below the floor/' "$tmp/impossible/summary.txt"
expect 1 "an impossible result in summary.txt" "result = impossible: cycle 2" "$soak" -c -o "$tmp/impossible" -n 3

expect 2 "-n 0" "-n must be > 0" "$soak" -c -o "$tmp/run" -n 0
expect 2 "-l abc" "-l needs a positive number" "$soak" -c -o "$tmp/run" -n 3 -l abc
exit $bad
