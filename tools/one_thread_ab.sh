#!/bin/bash
# tools/one_thread_ab.sh — two builds' one-thread solve, like for like (issue #37's target: one
# thread no more than 3 % slower than at 78e8530): the LMGC90 case (its own sample, 3,000 steps)
# and the paper's sample (2 ballast cycles), `--order colored --relaxation 1.3 --anderson 3
# --threads 1`, the builds taken in turn in each round. Where the builds' numbers differ, so do
# their trajectories: the solve is compared a contact and sweep, Σ solve_s / Σ (sweeps ×
# contacts) over steps.csv; and, as a user sees it, the whole run's solve (Σ solve_s, each build
# with its own sweeps). Prints each round and a Markdown table of the medians, B against A.
#
# Usage: tools/one_thread_ab.sh BUILD_A BUILD_B [WORK_DIR]  (docs/record/benchmarks-history.md §11.29)
#   REPEATS=6       rounds         LMGC_STEPS=3000, PAPER_CYCLES=2   the runs' lengths
#   ARGS_A, ARGS_B  options for one build only (a build with the overlap projection against
#                   78e8530, which had none: ARGS_B="--projection false")
#   SAMPLE=FILE     the paper sample (else prepared as tools/threads_table.sh does)
#   CALLGRIND=1     also the instructions of MoreauJean::solve a contact and sweep (valgrind's
#                   callgrind: one round, minutes; repeatable where the times are not)
# Each build needs examples/ballast/ballast and examples/deposit/lmgc90_deposit_case.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,18p "$0" >&2; exit 2; }
A=$1 B=$2 WORK=${3:-out/one_thread_ab}
REPEATS=${REPEATS:-6}
LMGC_STEPS=${LMGC_STEPS:-3000}
PAPER_CYCLES=${PAPER_CYCLES:-2}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
for b in "$A" "$B"; do
  for p in examples/ballast/ballast examples/deposit/lmgc90_deposit_case; do
    [ -x "$b/$p" ] || { echo "one_thread_ab: no $b/$p" >&2; exit 2; }
  done
done
mkdir -p "$WORK"
SAMPLE=${SAMPLE:-$WORK/sample/sample.nscd}
[ -f "$SAMPLE" ] || "$A/examples/ballast/ballast" --prepare-only --output "$WORK/sample" --overwrite \
  --progress-every 1000 --prep-max-time 0.4 --settle-time 0.1 > "$WORK/sample.log" 2>&1
COMMON=(--order colored --relaxation 1.3 --anderson 3 --threads 1)

# one run: case $1, build $2 (A or B), folder $3, then any prefix (valgrind) after
run() {
  local case=$1 which=$2 out=$3
  shift 3
  local build=$A extra=${ARGS_A:-}
  [ "$which" = B ] && build=$B extra=${ARGS_B:-}
  # shellcheck disable=SC2086  # (extra: options split on purpose)
  case $case in
    lmgc90) "$@" "$build/examples/deposit/lmgc90_deposit_case" --sample-file "$ROOT/tests/data/lmgc90/deposit_700.txt" \
      --no-vtk --steps "$LMGC_STEPS" "${COMMON[@]}" --output "$out" --overwrite $extra > "$out.log" 2>&1 ;;
    paper) "$@" "$build/examples/ballast/ballast" --sample "$SAMPLE" --cycles "$PAPER_CYCLES" --vtk-every 0 --steps-every 1 \
      --checkpoint-every 0 "${COMMON[@]}" --output "$out" --overwrite $extra > "$out.log" 2>&1 ;;
  esac
}

# ns a contact and sweep of run folder $1 and its solve's seconds in all (given a callgrind
# file $2: instructions a contact and sweep)
per_contact_sweep() {
  python3 - "$@" <<'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/steps.csv")))
cs = sum(int(r["sweeps"]) * int(r["contacts"]) for r in rows)
if cs == 0:
    sys.exit(f"one_thread_ab: {sys.argv[1]} swept no contact: give it more steps or cycles")
if len(sys.argv) > 2:
    import subprocess
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", sys.argv[2]], capture_output=True, text=True).stdout
    line = next(l for l in text.splitlines() if "MoreauJean::solve()" in l)
    print(f"{int(re.sub(r'[^0-9]', '', line.split()[0])) / cs:.2f}")
else:
    solve = sum(float(r['solve_s']) for r in rows)
    print(f"{1e9 * solve / cs:.3f} {solve:.4f}")
PY
}

: > "$WORK/rounds.txt"
for r in $(seq "$REPEATS"); do
  for which in A B; do
    for case in lmgc90 paper; do
      run "$case" "$which" "$WORK/$case-$which"
      v=$(per_contact_sweep "$WORK/$case-$which")
      echo "$r $which $case $v" | tee -a "$WORK/rounds.txt"
    done
  done
done
if [ "${CALLGRIND:-0}" = 1 ]; then
  for which in A B; do
    for case in lmgc90 paper; do
      run "$case" "$which" "$WORK/cg-$case-$which" valgrind --tool=callgrind --callgrind-out-file="$WORK/cg-$case-$which.out"
      v=$(per_contact_sweep "$WORK/cg-$case-$which" "$WORK/cg-$case-$which.out")
      echo "instructions $which $case $v" | tee -a "$WORK/rounds.txt"
    done
  done
fi
python3 - "$WORK/rounds.txt" "$A" "$B" <<'PY'
import statistics as st, sys
ns, solve, ir = {}, {}, {}
for line in open(sys.argv[1]):
    f = line.split()
    if f[0] == "instructions":
        ir[(f[1], f[2])] = float(f[3])
    else:
        ns.setdefault((f[1], f[2]), []).append(float(f[3]))
        solve.setdefault((f[1], f[2]), []).append(float(f[4]))
print(f"\nA = {sys.argv[2]}, B = {sys.argv[3]}; one thread, a contact and sweep of the solve, and the "
      "whole run's solve (each build on its own trajectory: its own sweeps)")
print("| case | A ns | B ns | B / A (medians) | B / A round by round | A instructions | B instructions "
      "| A solve s | B solve s | B / A |")
print("|---|---|---|---|---|---|---|---|---|---|")
for case in ("lmgc90", "paper"):
    a, b = ns[("A", case)], ns[("B", case)]
    pairs = sorted(y / x for x, y in zip(a, b))
    ia, ib = ir.get(("A", case)), ir.get(("B", case))
    sa, sb = st.median(solve[("A", case)]), st.median(solve[("B", case)])
    print(f"| {case} | {st.median(a):.3f} | {st.median(b):.3f} | {st.median(b) / st.median(a):.3f} | "
          f"{pairs[0]:.3f}–{pairs[-1]:.3f} | {f'{ia:.2f}' if ia else '—'} | {f'{ib:.2f}' if ib else '—'} "
          f"| {sa:.3f} | {sb:.3f} | {sb / sa:.3f} |")
PY
