#!/usr/bin/env bash
# tools/soak.sh — the soak of the extremes suite (issue #9, docs/extremes.md): many loading
# cycles of a reduced ballast sample (box 0.2 m, 14 grains, 10 pads, the paper's load and
# sublayer) with build/examples/ballast/ballast, then a check of its outputs. Not part of ctest.
#
#   tools/soak.sh [-b BUILD_DIR] [-o OUT_DIR] [-n CYCLES] [-l OVERLAP_LIMIT] [-- BALLAST_OPTIONS...]
#
#   -b  build folder holding examples/ballast/ballast (default: build)
#   -o  output folder (default: out/soak); when it already holds a checkpoint.nscd the run is
#       continued with --resume up to CYCLES, so a soak can be run in several sittings
#   -n  loading cycles in all (default: 20000; 250 steps each at the default dt = 2e-4 s)
#   -l  largest end-of-step overlap allowed in any cycle, in m (default: 2e-5, 0.2 % of the
#       smallest grain's diameter: issue #36's target for the soak at the defaults, where the
#       overlap projection keeps the overlaps near its slop of 125 nm)
#   -c  check the outputs of OUT_DIR only, run nothing
#   options after -- go to the ballast driver when the run starts (not when it resumes)
#
# Checks, after the run: the driver exited 0 and its summary.txt says "result = valid" (the
# driver itself refuses impossible states: grains outside the box or below the floor, a
# non-finite position, a settlement larger than the layer); cycles.csv has one row per cycle
# up to CYCLES, every value in it is finite (no NaN or inf), and every cycle's max_overlap is
# at most the limit. Exit status 0 when all hold, 1 when one does not (each failure printed),
# 2 on a bad argument. Run it under nice on a shared machine; a checkpoint is written every
# 500 cycles.
set -u
build=build out=out/soak cycles=20000 limit=2e-5 check_only=0
while getopts "b:o:n:l:ch" opt; do
  case "$opt" in
    b) build=$OPTARG ;;
    o) out=$OPTARG ;;
    n) cycles=$OPTARG ;;
    l) limit=$OPTARG ;;
    c) check_only=1 ;;
    h) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "soak.sh: bad option (see tools/soak.sh -h)" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ "${1:-}" = "--" ] && shift
case "$cycles" in ''|*[!0-9]*) echo "soak.sh: -n needs a positive integer, got '$cycles'" >&2; exit 2 ;; esac
[ "$cycles" -gt 0 ] || { echo "soak.sh: -n must be > 0" >&2; exit 2; }
awk -v l="$limit" 'BEGIN { exit !(l + 0 > 0) }' || { echo "soak.sh: -l needs a positive number, got '$limit'" >&2; exit 2; }

if [ "$check_only" = 0 ]; then
  driver="$build/examples/ballast/ballast"
  [ -x "$driver" ] || { echo "soak.sh: no driver at $driver (build it first, or give -b)" >&2; exit 2; }
  if [ -f "$out/checkpoint.nscd" ]; then
    echo "soak.sh: resuming $out up to $cycles cycles"
    "$driver" --resume "$out" --cycles "$cycles" --progress-every 60
  else
    echo "soak.sh: $cycles cycles of the reduced sample into $out"
    "$driver" --box-width 0.2 --grading-fraction 0.02 --pads 10 --cycles "$cycles" --checkpoint-every 500 \
      --steps-every 2500 --vtk-every 0 --progress-every 60 --output "$out" "$@"
  fi
  rc=$?
  [ "$rc" = 0 ] || echo "soak.sh: FAIL: the driver exited with status $rc"
else
  rc=0
fi

fail=0
[ "$rc" = 0 ] || fail=1
if ! grep -qx "result = valid" "$out/summary.txt" 2>/dev/null; then
  echo "soak.sh: FAIL: $out/summary.txt does not say 'result = valid':"
  grep "^result" "$out/summary.txt" 2>/dev/null || echo "  (no summary.txt)"
  fail=1
fi
# cycles.csv: header, then one row per cycle; columns by name
awk -F, -v limit="$limit" -v want="$cycles" '
  NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; if (!("max_overlap" in col) || !("cycle" in col)) { print "soak.sh: FAIL: cycles.csv has no cycle or max_overlap column"; bad = 1; exit } next }
  {
    for (i = 1; i <= NF; ++i) if (tolower($i) ~ /nan|inf/) { if (nan++ < 5) print "soak.sh: FAIL: cycle " $col["cycle"] ": non-finite " $i " in column " i; }
    o = $col["max_overlap"] + 0; if (o > worst) { worst = o; at = $col["cycle"] }
    if (o > limit) { if (over++ < 5) print "soak.sh: FAIL: cycle " $col["cycle"] ": max overlap " o " m > " limit " m" }
    if ($col["cycle"] + 0 != NR - 1) { if (gap++ < 5) print "soak.sh: FAIL: row " NR " is cycle " $col["cycle"] }
    rows = NR - 1; settlement = $col["settlement_min_load"]
  }
  END {
    if (bad) exit 1
    if (rows != want) { print "soak.sh: FAIL: cycles.csv has " rows " cycles, " want " wanted"; gap++ }
    printf "soak.sh: %d cycles, largest overlap %.3g m (cycle %d, limit %s m), final settlement %s m, %d non-finite values, %d cycles over the limit\n", rows, worst, at, limit, settlement, nan, over
    exit (nan + over + gap > 0)
  }' "$out/cycles.csv" 2>/dev/null || fail=1
[ -f "$out/cycles.csv" ] || { echo "soak.sh: FAIL: no $out/cycles.csv"; fail=1; }
if [ "$fail" = 0 ]; then echo "soak.sh: PASS"; else echo "soak.sh: FAIL"; fi
exit "$fail"
