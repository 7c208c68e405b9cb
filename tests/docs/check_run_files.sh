#!/bin/bash
# tests/docs/check_run_files.sh ROOT — tools/run_files.sh, which the thread tools use to say that
# two runs gave the same results: two runs' CSVs that differ only in their timings and chosen
# threads compare the same; a result that differs, or a row cut off, does not; a checkpoint's
# processor time is left out of its state.
set -euo pipefail
source "$1/tools/run_files.sh"
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
printf 'step,settlement,solve_s,wall_time,sweeps,solve_threads\n1,0.5,0.01,0.2,30,1\n2,0.6,0.02,0.3,31,1\n' > "$d/a.csv"
printf 'step,settlement,solve_s,wall_time,sweeps,solve_threads\n1,0.5,0.07,0.9,30,2\n2,0.6,0.05,0.8,31,2\n' > "$d/b.csv"
printf 'step,settlement,solve_s,wall_time,sweeps,solve_threads\n1,0.5,0.01,0.2,30,1\n2,0.6,0.02,0.3,32,1\n' > "$d/c.csv"
fail() { echo "check_run_files: $*" >&2; exit 1; }
cmp -s <(untimed_csv "$d/a.csv") <(untimed_csv "$d/b.csv") || fail "timings and threads alone made two runs differ"
[ "$(untimed_csv "$d/a.csv" | head -n 1)" = "step,settlement,sweeps," ] || fail "the columns kept: $(untimed_csv "$d/a.csv" | head -n 1)"
cmp -s <(untimed_csv "$d/a.csv") <(untimed_csv "$d/c.csv") && fail "a different sweep count compared the same"
cmp -s <(untimed_csv "$d/a.csv" 1) <(untimed_csv "$d/c.csv" 1) || fail "the first row alone should compare the same"
[ "$(untimed_csv "$d/a.csv" 1 | wc -l)" -eq 2 ] || fail "ROWS 1 should give the header and one row"
mkdir "$d/r1" "$d/r2"
printf 'x "state.cpu_seconds" 1.5\nx "body.0.x" 0.25\n' > "$d/r1/checkpoint.nscd"
printf 'x "state.cpu_seconds" 9.5\nx "body.0.x" 0.25\n' > "$d/r2/checkpoint.nscd"
cmp -s <(final_state "$d/r1") <(final_state "$d/r2") || fail "the processor time alone made two checkpoints differ"
printf 'x "body.0.x" 0.5\n' > "$d/r2/final_state.nscd"
cmp -s <(final_state "$d/r1") <(final_state "$d/r2") && fail "a different final state compared the same"
echo "check_run_files: passed"
