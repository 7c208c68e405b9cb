#!/bin/bash
# tools/ab_threads.sh — two builds side by side at 1 and 2 threads (issue #37): the LMGC90 case
# (its own sample, 3,000 steps), the paper's sample (4 ballast cycles) and, if asked, a
# 7,000-grain deposit (900 steps), `--order colored`,
# each run of a round taken in turn (A then B, 2 threads then 1), the cores' round trip before
# each. Where the builds' numbers differ, so do their trajectories (sweeps a step): the table
# gives the time a sweep, B against A, and each build's speed-up of 2 threads over 1.
#
# Usage: tools/ab_threads.sh BUILD_A BUILD_B [WORK_DIR]       (docs/record/benchmarks-history.md §11.4)
#   REPEATS=6   rounds        CASES="lmgc90 paper"   the cases (and "deposit")
#   SAMPLE=FILE the paper sample (ballast's sample.nscd; else prepared as tools/threads_table.sh does)
# Each build needs examples/ballast/ballast, examples/deposit/lmgc90_deposit_case and
# examples/deposit/deposit (a folder with only those, copied from an older commit's build, will do).
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,14p "$0" >&2; exit 2; }
A=$1 B=$2 WORK=${3:-out/ab_threads}
REPEATS=${REPEATS:-6}
CASES=${CASES:-lmgc90 paper}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
for b in "$A" "$B"; do
  for p in examples/ballast/ballast examples/deposit/lmgc90_deposit_case examples/deposit/deposit; do
    [ -x "$b/$p" ] || { echo "ab_threads: no $b/$p" >&2; exit 2; }
  done
done
mkdir -p "$WORK"
g++ -O2 -pthread "$ROOT/tools/core_latency.cpp" -o "$WORK/core_latency"
SAMPLE=${SAMPLE:-}
if [[ " $CASES " == *" paper "* && -z "$SAMPLE" ]]; then
  SAMPLE=$WORK/sample/sample.nscd
  [ -f "$SAMPLE" ] || "$A/examples/ballast/ballast" --prepare-only --output "$WORK/sample" --overwrite \
    --progress-every 1000 --prep-max-time 0.4 --settle-time 0.1 > "$WORK/sample.log" 2>&1
fi

# one run: case $1, build $2, threads $3, folder $4; prints "wall sweeps_a_step"
run() {
  case $1 in
    lmgc90) "$2/examples/deposit/lmgc90_deposit_case" --sample-file "$ROOT/tests/data/lmgc90/deposit_700.txt" --no-vtk \
      --order colored --threads "$3" --steps 3000 --output "$4" --overwrite --progress-every 100000 > "$4.log" 2>&1 ;;
    paper) "$2/examples/ballast/ballast" --sample "$SAMPLE" --cycles 4 --order colored --threads "$3" --vtk-every 0 \
      --checkpoint-every 0 --output "$4" --overwrite --progress-every 100000 > "$4.log" 2>&1 ;;
    deposit) "$2/examples/deposit/deposit" --grains 7000 --steps 900 --order colored --threads "$3" --no-vtk \
      --output "$4" --overwrite --progress-every 100000 > "$4.log" 2>&1 ;;
  esac
  awk -F' = ' '$1 == "wall_time" {w = $2} $1 == "mean_sweeps" {s = $2} END {print w, s}' "$4/summary.txt"
}

echo "ab_threads: A = $A, B = $B on $(nproc) cores; load before: $(uptime)"
status=0
LOG=$WORK/runs.txt
: > "$LOG"
for r in $(seq 1 "$REPEATS"); do
  for c in $CASES; do
    for t in 2 1; do
      for v in A B; do
        dir=$A
        [ $v = B ] && dir=$B
        lat=$("$WORK/core_latency" 3)
        echo "$r $c $v $t $(run "$c" "$dir" "$t" "$WORK/$c.$v.t$t.r$r") $lat" | tee -a "$LOG"
      done
    done
  done
done
echo "load after: $(uptime)"
# the same bits at 1 and 2 threads: each build's final state of each case and round
source "$ROOT/tools/run_files.sh"
for c in $CASES; do
  for v in A B; do
    for r in $(seq 1 "$REPEATS"); do
      cmp -s <(final_state "$WORK/$c.$v.t1.r$r") <(final_state "$WORK/$c.$v.t2.r$r") ||
        { echo "ab_threads: $c, build $v, round $r: 1 and 2 threads end in different states" >&2; status=1; }
    done
  done
done
# medians over the rounds of: B/A a sweep at 1 and 2 threads; each build's 2-thread speed-up
python3 - "$LOG" <<'EOF'
import collections, statistics, sys
run = {}
lat = []
for line in open(sys.argv[1]):
    r, c, v, t, wall, sweeps, ns = line.split()
    run[r, c, v, t] = (float(wall), float(wall) / float(sweeps))
    lat.append(int(ns))
rounds = sorted({k[0] for k in run})
print(f"\nround trip before the runs: median {statistics.median(lat):.0f} ns, {min(lat)} to {max(lat)} ns\n")
print("| case | B/A a sweep, 2 threads | B/A a sweep, 1 thread | A: 2 threads against 1 | B: 2 threads against 1 |")
print("|---|---|---|---|---|")
for c in dict.fromkeys(k[1] for k in run):
    med = lambda f: statistics.median(f(r) for r in rounds)
    ratio = lambda t: med(lambda r: run[r, c, "B", t][1] / run[r, c, "A", t][1])
    speed = lambda v: med(lambda r: run[r, c, v, "1"][0] / run[r, c, v, "2"][0])
    print(f"| {c} | {ratio('2'):.3f} | {ratio('1'):.3f} | {speed('A'):.2f}x | {speed('B'):.2f}x |")
EOF
exit $status
