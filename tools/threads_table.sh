#!/bin/bash
# tools/threads_table.sh — one run on one thread against two (issue #37): the paper's sample
# (4 ballast cycles), the LMGC90 case (its own sample, 3,000 steps) and a 7,000-grain deposit
# (900 steps), each `--order colored` (ORDER), at 1 and 2 threads taken in turn (1, 2, 1, 2, …) for
# REPEATS rounds. Prints each run's phases (the summary's detect_seconds, prepare_seconds, …),
# a Markdown table of the wall-time medians and the speed-ups (and the solve's: the issue gives the
# LMGC90 case's in solve seconds), and checks
# that every run of a case ends in the same final state, byte for byte, and writes the same
# steps.csv but for its timing columns (the results do not depend on the threads).
#
# Usage: tools/threads_table.sh [BUILD_DIR] [WORK_DIR]        (its cost: docs/benchmarks.md §11)
#   REPEATS=3            rounds (each: every case at 1 thread, then at 2)
#   THREADS="1 2"        the thread counts of a round (the first is the speed-ups' reference)
#   SAMPLE=FILE          a prepared paper sample (ballast's sample.nscd) instead of the quick one
#                        prepared here: 724 grains deposited for at most 0.4 s, the sleeper
#                        settled for 0.1 s (not at rest, but every thread count runs the same
#                        sample)
#   CASES="paper lmgc90 deposit"  the cases to run
#   ORDER=colored        their sweep order (colored-cells: every row at once, for 4 threads or more)
#   FIXED=1              every part of the step on the count asked (--solve-threads and
#                        --loop-threads N): the threads' raw scaling, where by default the
#                        stepper may choose fewer by measure (what a run gets)
#   PROFILE=1            each run with --solve-profile, and a table of where the solve's threads
#                        spend its region (sweeping, waiting, mixing, thread 0 alone, set-up) at
#                        each count, from the last round (the clock's reads cost a little: take
#                        the speed-ups from a run without it)
#   LATENCY_PROBE=FILE   tools/core_latency.cpp built already (else built here with g++)
#   PAPER_CYCLES=4 LMGC_STEPS=3000 DEPOSIT_GRAINS=7000 DEPOSIT_STEPS=900  their sizes (smaller:
#                        a smoke test of the script, not the issue's figures)
# Quote the load and the cores' round trip: the script prints `uptime` before and after, and the
# round trip of a cache line between two threads (tools/core_latency.cpp) before every run. On a
# virtual machine that round trip follows the host's placement of the vCPUs and decides what a
# second thread gains (docs/record/benchmarks-history.md §11.0): compare tables taken at the same round trip.
# Needs the targets ballast, deposit and lmgc90_deposit_case, and g++ for the probe.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-out/threads_table}
REPEATS=${REPEATS:-3}
THREADS=${THREADS:-1 2}
CASES=${CASES:-paper lmgc90 deposit}
ORDER=${ORDER:-colored}
PAPER_CYCLES=${PAPER_CYCLES:-4}
LMGC_STEPS=${LMGC_STEPS:-3000}
DEPOSIT_GRAINS=${DEPOSIT_GRAINS:-7000}
DEPOSIT_STEPS=${DEPOSIT_STEPS:-900}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BALLAST=$BUILD/examples/ballast/ballast
DEPOSIT=$BUILD/examples/deposit/deposit
LMGC=$BUILD/examples/deposit/lmgc90_deposit_case
for b in "$BALLAST" "$DEPOSIT" "$LMGC"; do
  [ -x "$b" ] || { echo "threads_table: no $b (cmake --build $BUILD --target ballast deposit lmgc90_deposit_case)" >&2; exit 2; }
done
mkdir -p "$WORK"
if [ -n "${LATENCY_PROBE:-}" ]; then  # a probe built elsewhere (a machine without a compiler)
  cp "$LATENCY_PROBE" "$WORK/core_latency"
else
  g++ -O2 -pthread "$ROOT/tools/core_latency.cpp" -o "$WORK/core_latency"
fi
echo "threads_table: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?') on $(nproc) cores; load before: $(uptime)"

SAMPLE=${SAMPLE:-}
if [[ " $CASES " == *" paper "* && -z "$SAMPLE" ]]; then
  SAMPLE=$WORK/sample/sample.nscd
  if [ ! -f "$SAMPLE" ]; then
    echo "threads_table: preparing the quick paper sample (2 threads) …"
    "$BALLAST" --prepare-only --output "$WORK/sample" --overwrite --progress-every 1000 --threads 2 \
      --prep-max-time 0.4 --settle-time 0.1 > "$WORK/sample.log" 2>&1
  fi
fi

# one run of case $1 at $2 threads into folder $3; prints its wall seconds (the driver's own)
run_case() {
  local case=$1 t=$2 out=$3
  local fixed=()
  if [ "${FIXED:-0}" = 1 ]; then fixed=(--solve-threads "$t" --loop-threads "$t"); fi
  if [ "${PROFILE:-0}" = 1 ]; then fixed+=(--solve-profile); fi
  case $case in
    paper)
      "$BALLAST" --sample "$SAMPLE" --cycles "$PAPER_CYCLES" --order "$ORDER" --threads "$t" "${fixed[@]}" --vtk-every 0 --checkpoint-every 0 \
        --output "$out" --overwrite --progress-every 1000 > "$out.log" 2>&1
      awk -F' = ' '$1 == "wall_time" {print $2}' "$out/summary.txt" ;;
    lmgc90)
      "$LMGC" --sample-file "$ROOT/tests/data/lmgc90/deposit_700.txt" --no-vtk --order "$ORDER" --threads "$t" "${fixed[@]}" --steps "$LMGC_STEPS" \
        --output "$out" --overwrite --progress-every 1000 > "$out.log" 2>&1
      awk -F' = ' '$1 == "wall_time" {print $2}' "$out/summary.txt" ;;
    deposit)
      "$DEPOSIT" --grains "$DEPOSIT_GRAINS" --steps "$DEPOSIT_STEPS" --order "$ORDER" --threads "$t" "${fixed[@]}" --no-vtk \
        --output "$out" --overwrite --progress-every 1000 > "$out.log" 2>&1
      awk -F' = ' '$1 == "wall_time" {print $2}' "$out/summary.txt" ;;
  esac
}

# final_state and untimed_csv
source "$ROOT/tools/run_files.sh"

# a key's value in a run's summary.txt (0 where it has none)
key() { awk -F' = ' -v k="$2" '$1 == k {v = $2} END {print v + 0}' "$1/summary.txt"; }

declare -A WALL SOLVE
LATENCY=""
for r in $(seq 1 "$REPEATS"); do
  for case in $CASES; do
    for t in $THREADS; do
      out=$WORK/$case/t${t}_r$r
      mkdir -p "$WORK/$case"
      lat=$("$WORK/core_latency" 3)
      LATENCY+=" $lat"
      w=$(run_case "$case" "$t" "$out") || { echo "threads_table: $case at $t threads failed: see $out.log" >&2; exit 1; }
      WALL[$case,$t]="${WALL[$case,$t]:-} $w"
      SOLVE[$case,$t]="${SOLVE[$case,$t]:-} $(key "$out" solve_seconds)"
      echo "  round $r: $case, $t thread(s): $(printf '%.3f' "$w") s (round trip before it: $lat ns)"
      # the phases, from the summary's step-watch keys: which of them the threads speed up
      echo "    phases, s: $(awk -F' = ' '$1 ~ /^(detect|prepare|solve|end_step)_seconds$/ {
        sub(/_seconds$/, "", $1); printf "%s %.3f  ", $1, $2}' "$out/summary.txt")"
    done
  done
done

# a speed-up a / b as "1.23×" ("—" where b is not positive: a run without that key)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {if (b > 0) printf "%.2f×", a / b; else printf "—"}'; }
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{v[NR] = $1} END {print (NR % 2 ? v[(NR + 1) / 2] : 0.5 * (v[NR / 2] + v[NR / 2 + 1]))}'; }

status=0
ref=${THREADS%% *}
echo
echo "load after: $(uptime)"
echo "round trip of a cache line between two threads before the runs: median $(echo "$LATENCY" | median) ns," \
  "from $(echo "$LATENCY" | tr ' ' '\n' | grep -v '^$' | sort -g | head -1) to $(echo "$LATENCY" | tr ' ' '\n' | grep -v '^$' | sort -g | tail -1) ns"
echo
# (an if, not `[ … ] && echo` inside $(…): under set -e a false test there ends the script)
fixed_note=""
if [ "${FIXED:-0}" = 1 ]; then fixed_note=", every part on the count asked"; fi
header="| run (wall s, medians of $REPEATS, --order $ORDER$fixed_note) |"
for t in $THREADS; do header+=" $t thread(s) |"; done
for t in $THREADS; do [ "$t" = "$ref" ] || header+=" speed-up $t/$ref |"; done
for t in $THREADS; do [ "$t" = "$ref" ] || header+=" the solve's $t/$ref |"; done
header+=" same bits |"
echo "$header"
echo "$header" | sed 's/[^|]/-/g; s/--*/---/g'
for case in $CASES; do
  declare -A MED=()
  row="| $case |"
  case $case in
    paper) row="| paper sample, $PAPER_CYCLES cycles |" ;;
    lmgc90) row="| LMGC90 case, $LMGC_STEPS steps |" ;;
    deposit) row="| deposit, $DEPOSIT_GRAINS grains, $DEPOSIT_STEPS steps |" ;;
  esac
  for t in $THREADS; do
    MED[$t]=$(echo "${WALL[$case,$t]}" | median)
    row+=" $(printf '%.2f' "${MED[$t]}") |"
  done
  for t in $THREADS; do [ "$t" = "$ref" ] || row+=" $(ratio "${MED[$ref]}" "${MED[$t]}") |"; done
  # the solve's speed-up: the ratio of the solve seconds' medians
  for t in $THREADS; do
    [ "$t" = "$ref" ] || row+=" $(ratio "$(echo "${SOLVE[$case,$ref]}" | median)" "$(echo "${SOLVE[$case,$t]}" | median)") |"
  done
  # every run of the case against the first: the final state and steps.csv but for its timings
  first=$WORK/$case/t${ref}_r1
  same=yes
  for d in "$WORK/$case"/t*_r*; do
    [ -d "$d" ] || continue
    cmp -s <(final_state "$first") <(final_state "$d") || { same=NO; echo "threads_table: $d: final state differs from $first" >&2; }
    cmp -s <(untimed_csv "$first/steps.csv") <(untimed_csv "$d/steps.csv") || { same=NO; echo "threads_table: $d: steps.csv differs from $first" >&2; }
  done
  [ "$same" = yes ] || status=1
  row+=" $same |"
  echo "$row"
done

if [ "${PROFILE:-0}" = 1 ]; then
  echo
  echo "Where the solve's threads spend its region (round $REPEATS; each part's thread-seconds as a share of region × threads):"
  echo
  echo "| case | threads | region s | sweeping | waiting | mixing | thread 0 alone | set-up |"
  echo "|---|---|---|---|---|---|---|---|"
  for case in $CASES; do
    for t in $THREADS; do
      d=$WORK/$case/t${t}_r$REPEATS
      awk -v c="$case" -v t="$t" -v r="$(key "$d" solve_region_seconds)" -v w="$(key "$d" solve_thread_seconds)" \
        -v s="$(key "$d" solve_sweeping_seconds)" -v q="$(key "$d" solve_waiting_seconds)" -v m="$(key "$d" solve_mixing_seconds)" \
        -v z="$(key "$d" solve_serial_seconds)" -v u="$(key "$d" solve_setup_seconds)" 'BEGIN {
          if (w <= 0) w = 1
          printf "| %s | %s | %.3f | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% |\n", c, t, r, 100*s/w, 100*q/w, 100*m/w, 100*z/w, 100*u/w}'
    done
  done
fi
exit $status
