#!/bin/bash
# tools/many_cores.sh — issue #37's figures on a machine with many cores and no compiler (a lent
# machine: no Debian packages, no network, a copy of this working tree). `pack` puts what the
# runs need into one folder here: the drivers, every library `ldd` lists but the C library's own,
# the probes built, and the runs' samples (a 700-grain deposit's final state for `scaling`, the
# quick paper sample, the paper's first sample fully prepared). `run`, in the working tree's copy
# there, runs from that folder, in this order, within BUDGET seconds (540; a lent machine runs a
# command for 600 s at most), each later part only where the time left allows it:
#   the machine (nproc, the probes: tools/core_throughput.cpp, tools/core_latency.cpp);
#   `scaling --copies 100 --order rows --nlgs-order colored --threads 1,2,4,… --solve-profile`
#   (72,400 grains; each count's solves part by part);
#   tools/threads_table.sh at the same counts: the paper sample, the LMGC90 case, a 7,000-grain
#   deposit, each run's state compared across the counts;
#   the 20,000-cycle target (`long`, below; stopped 90 s before the budget ends);
#   the LMGC90 case in --order colored-cells (its rows at once), at the same counts;
#   the paper sample and the LMGC90 case once more with --solve-profile (where their solves'
#   threads spend their time).
# Everything goes to OUT: run.txt (all of it) and the tables. `long` alone: the paper's first
# sample (long_run.cfg's seed 2006: the same sample, and so the same cycles, as the
# 20,000-cycle run of docs/studies.md §5.9) at the defaults, as a user runs it, for LONG_CYCLES
# on LONG_THREADS threads (stopped cleanly after LONG_SECONDS), then its first LONG_BASE_CYCLES
# on one thread; prints the wall time a cycle, what 20,000 cycles would take at that pace, and
# the speed-up on the same cycles, which must match bit for bit.
#
# Usage: tools/many_cores.sh pack BUILD_DIR PACK_DIR      (here; PACK_DIR git-ignored, e.g. out/)
#        tools/many_cores.sh run PACK_DIR OUT              (there; THREADS="1 2 4 8 16" REPEATS=1
#                                                           BUDGET=540; FIXED=1: the small runs on the
#                                                           counts asked; COPIES=100 SCALING_STEPS=30,
#                                                           and threads_table.sh's sizes, for a smoke test)
#        tools/many_cores.sh long PACK_DIR OUT             (there; LONG_THREADS=8 LONG_CYCLES=1000
#                                                           LONG_SECONDS=420 LONG_BASE_CYCLES=20)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DRIVERS="examples/ballast/ballast examples/deposit/deposit examples/deposit/lmgc90_deposit_case examples/scaling/scaling"
[ $# -eq 3 ] || { sed -n 2,31p "$0" >&2; exit 2; }
mode=$1

if [ "$mode" = pack ]; then
  BUILD=$2 PACK=$3
  mkdir -p "$PACK/lib" "$PACK/data"
  for d in $DRIVERS; do
    [ -x "$BUILD/$d" ] || { echo "many_cores: no $BUILD/$d (cmake --build $BUILD --target scaling ballast deposit lmgc90_deposit_case)" >&2; exit 2; }
    mkdir -p "$PACK/$(dirname "$d")"
    cp "$BUILD/$d" "$PACK/$d"
    # every library but libc, libm and the loader, which the other machine has
    ldd "$BUILD/$d" | awk '$3 ~ /^\// {print $3}' | grep -Ev '/(libc|libm|ld-linux[^/]*)\.so' | xargs -r cp -L -t "$PACK/lib"
  done
  g++ -O2 -pthread "$ROOT/tools/core_latency.cpp" -o "$PACK/core_latency"
  g++ -O2 -fopenmp "$ROOT/tools/core_throughput.cpp" -o "$PACK/core_throughput"
  ldd "$PACK/core_throughput" | awk '$3 ~ /^\// {print $3}' | grep -Ev '/(libc|libm|ld-linux[^/]*)\.so' | xargs -r cp -L -t "$PACK/lib"
  export LD_LIBRARY_PATH=$PACK/lib
  B=$PACK/examples
  [ -f "$PACK/data/dep700/final_state.nscd" ] ||
    "$B/deposit/deposit" --grains 700 --no-vtk --output "$PACK/data/dep700" --overwrite --threads 2 > "$PACK/data/dep700.log" 2>&1
  [ -f "$PACK/data/sample/sample.nscd" ] ||
    "$B/ballast/ballast" --prepare-only --output "$PACK/data/sample" --overwrite --progress-every 1000 --threads 2 \
      --prep-max-time 0.4 --settle-time 0.1 > "$PACK/data/sample.log" 2>&1
  # the paper's first sample, fully prepared (long: the 20,000-cycle run's own)
  [ -f "$PACK/data/full/sample.nscd" ] ||
    "$B/ballast/ballast" --config "$ROOT/examples/long_run/long_run.cfg" --prepare-only --output "$PACK/data/full" \
      --overwrite --progress-every 1000 > "$PACK/data/full.log" 2>&1
  rm -f "$PACK/data/dep700/steps.csv" "$PACK/data/sample/"*.csv "$PACK/data/full/"*.csv
  du -sh "$PACK"
  exit 0
fi

# the sum of cycles.csv's wall_time over its first n cycles (all: n = 0), and the cycles summed
wall_of() {
  awk -F, -v n="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_time") c = i; next }
                     c && (n == 0 || NR - 1 <= n) { s += $c; k++ } END { printf "%.6f %d\n", s, k }' "$1"
}

# untimed_csv (the cycles but for their wall time)
source "$ROOT/tools/run_files.sh"

# The 20,000-cycle target (`long`): PACK OUT SECONDS, the run on LONG_THREADS threads stopped
# after SECONDS at most; prints its table.
long_target() {
  local PACK=$1 OUT=$2 SECONDS_MAX=$3
  local T=${LONG_THREADS:-8} CYCLES=${LONG_CYCLES:-1000} BASE=${LONG_BASE_CYCLES:-20}
  local B=$PACK/examples/ballast/ballast S=$PACK/data/full/sample.nscd
  [ -f "$S" ] || { echo "many_cores: no $S (pack again)" >&2; return 2; }
  echo "many_cores long: $(nproc) cores; the paper's first sample, $CYCLES cycles on $T threads (at most $SECONDS_MAX s)"
  # SIGTERM: ballast ends its cycle, writes its checkpoint and exits 143
  timeout -s TERM "$SECONDS_MAX" "$B" --sample "$S" --cycles "$CYCLES" --threads "$T" --vtk-every 0 \
    --checkpoint-every 0 --progress-every 30 --output "$OUT/long_t$T" --overwrite || { rc=$?; [ $rc -eq 124 ] || [ $rc -eq 143 ]; }
  "$B" --sample "$S" --cycles "$BASE" --threads 1 --vtk-every 0 --checkpoint-every 0 --progress-every 30 \
    --output "$OUT/long_t1" --overwrite
  local all done one k many same=no
  read -r all done < <(wall_of "$OUT/long_t$T/cycles.csv" 0)
  read -r one k < <(wall_of "$OUT/long_t1/cycles.csv" 0)
  # (on the cycles both runs made: the many threads' run may have stopped first)
  if [ "$done" -lt "$k" ]; then
    k=$done
    read -r one _ < <(wall_of "$OUT/long_t1/cycles.csv" "$k")
  fi
  read -r many _ < <(wall_of "$OUT/long_t$T/cycles.csv" "$k")
  # the same cycles, bit for bit, but for their wall time
  cmp -s <(untimed_csv "$OUT/long_t1/cycles.csv" "$k") <(untimed_csv "$OUT/long_t$T/cycles.csv" "$k") && same=yes
  awk -v t="$T" -v all="$all" -v done="$done" -v one="$one" -v many="$many" -v k="$k" -v same="$same" 'BEGIN {
    printf "| threads | cycles | wall s a cycle | 20,000 cycles at that pace | cycles 1-%d: 1 thread / %d threads | the same cycles |\n", k, t
    printf "|---|---|---|---|---|---|\n"
    printf "| %d | %d | %.3f | %.2f h | %.2f / %.2f s (%.2fx) | %s |\n", t, done, all / done, 20000 * all / done / 3600, one, many, one / many, same
  }'
}

if [ "$mode" = long ]; then
  PACK=$(cd "$2" && pwd) OUT=$3
  export LD_LIBRARY_PATH=$PACK/lib
  mkdir -p "$OUT"
  long_target "$PACK" "$OUT" "${LONG_SECONDS:-420}" 2>&1 | tee "$OUT/long.txt"
  exit 0
fi

[ "$mode" = run ] || { echo "many_cores: pack, run or long" >&2; exit 2; }
PACK=$(cd "$2" && pwd) OUT=$3
THREADS=${THREADS:-1 2 4 8 16}
REPEATS=${REPEATS:-1}
COPIES=${COPIES:-100}
SCALING_STEPS=${SCALING_STEPS:-30}
# the seconds this call may take (a lent machine runs a command for 600 s at most): the probes,
# scaling and the table first, then the rest as long as the budget allows
BUDGET=${BUDGET:-540}
t0=$(date +%s)
left() { echo $((BUDGET - $(date +%s) + t0)); }
mkdir -p "$OUT"
export LD_LIBRARY_PATH=$PACK/lib
{
  echo "many_cores: $(nproc) cores; $(uptime)"
  grep -m1 'model name' /proc/cpuinfo || true
  "$PACK/core_throughput" 3
  echo "round trip of a cache line: $("$PACK/core_latency" 3) ns"
  "$PACK/examples/scaling/scaling" --sample "$PACK/data/dep700/final_state.nscd" --copies "$COPIES" --order rows \
    --nlgs-order colored --threads "$(echo "$THREADS" | tr ' ' ',')" --warmup 10 --steps "$SCALING_STEPS" --solve-profile
  # the small runs: the pack's folder holds the drivers as a build folder does
  LATENCY_PROBE=$PACK/core_latency SAMPLE=$PACK/data/sample/sample.nscd THREADS=$THREADS REPEATS=$REPEATS FIXED=${FIXED:-0} \
    bash "$ROOT/tools/threads_table.sh" "$PACK" "$OUT/threads_table"
  # then what the budget leaves: the 20,000-cycle target (long; 90 s kept for its one-thread
  # cycles), the LMGC90 case in cells, where the solves' threads spend their time
  long_s=$(( $(left) - 90 ))
  [ "$long_s" -gt "${LONG_SECONDS:-420}" ] && long_s=${LONG_SECONDS:-420}
  if [ "$long_s" -ge 60 ]; then
    long_target "$PACK" "$OUT" "$long_s" | tee "$OUT/long.txt"
  else echo "many_cores: long left out, $(left) s of BUDGET=$BUDGET left"; fi
  if [ "$(left)" -ge 150 ]; then
    LATENCY_PROBE=$PACK/core_latency THREADS=$THREADS REPEATS=$REPEATS FIXED=${FIXED:-0} CASES=lmgc90 ORDER=colored-cells \
      bash "$ROOT/tools/threads_table.sh" "$PACK" "$OUT/threads_table_cells"
  else echo "many_cores: the cells' table left out, $(left) s of BUDGET=$BUDGET left"; fi
  # (--solve-profile)
  if [ "$(left)" -ge 200 ]; then
    LATENCY_PROBE=$PACK/core_latency SAMPLE=$PACK/data/sample/sample.nscd THREADS=$THREADS REPEATS=1 FIXED=${FIXED:-0} \
      CASES="paper lmgc90" PROFILE=1 bash "$ROOT/tools/threads_table.sh" "$PACK" "$OUT/threads_profile"
  else echo "many_cores: the profiles left out, $(left) s of BUDGET=$BUDGET left"; fi
} 2>&1 | tee "$OUT/run.txt"
