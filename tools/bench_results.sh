#!/bin/bash
# tools/bench_results.sh — regenerate the committed benchmark results of one machine
# (tests/bench/results/<machine>/, docs/benchmarks.md §6).
#
# Usage   tools/bench_results.sh MACHINE [BUILD_DIR]
#   MACHINE     folder name under tests/bench/results (letters, digits, - _ .), e.g. 2core-shared-vm
#   BUILD_DIR   a Release build with the benchmarks and the examples (default: build)
# Env     SAMPLE=path/final_state.nscd  reuse a settled `deposit --grains 700` sample instead of
#         running the deposit (~2 min); RUNS=3 runs of each scaling size and body order;
#         ONLY=scaling (or detection, nlgs, threads, lmgc90) to redo one part, the other files kept;
#         PAPER_SAMPLE=path/sample.nscd  a prepared paper sample for threads_table.md (else it
#         prepares a quick one, ~2 min).
#
# Writes, in tests/bench/results/MACHINE/:
#   machine.txt        CPU, cores, memory, load before and after, date, commit
#   detection.csv      bench_detection, 5 repetitions (Google Benchmark CSV; read the _median rows)
#   nlgs.csv           bench_nlgs's contact update, 5 repetitions
#   nlgs_colouring.csv bench_nlgs's colouring of the colored order, 5 repetitions
#   scaling.csv        `scaling` rows: settled step cost (CPU time) at 700, 7,000 and 70,000 grains
#                      (a settled 700-grain deposit, tiled 1, 10 and 100 times), RUNS runs of each
#                      size, in both body orders (label rows: a wide deposit's; copies)
#   scaling_threads.csv `scaling --nlgs-order colored --threads 1,2`: the settled step at 700,
#                      7,000 and 70,000 grains (body order rows), one and two threads taking
#                      turns on one trajectory, RUNS runs of each size; a row per thread count
#                      (wall time)
#   threads_table.md   tools/threads_table.sh: the paper's sample, the LMGC90 case and a 7,000-grain
#                      deposit at 1 and 2 threads, 3 rounds (its table, with the cores' round trip)
#   scaling.png        contrib/plots/plot_scaling.py on the rows of label 'rows' (and
#   scaling_copies.png  of label 'copies'), if matplotlib is there
#   lmgc90_case.txt    summary.txt of `lmgc90_deposit_case --no-vtk` (10,000 steps, one run),
#   lmgc90_case.csv    and its key = value lines as key,value
#   lmgc90_case_rows.* the same with --order colored-rows --relaxation 1.3
#   lmgc90_case_mixed.* the same with --anderson 3 as well
# Everything runs under nice, one program at a time.
set -euo pipefail
machine=${1:?usage: tools/bench_results.sh MACHINE [BUILD_DIR]}
build=${2:-build}
[[ $machine =~ ^[A-Za-z0-9._-]+$ ]] || { echo "bench_results.sh: MACHINE may hold letters, digits, . _ - only" >&2; exit 2; }
for exe in tests/bench_detection tests/bench_nlgs examples/scaling/scaling examples/deposit/deposit examples/deposit/lmgc90_deposit_case; do
  [[ -x $build/$exe ]] || { echo "bench_results.sh: $build/$exe is missing (a Release build first, and cmake --build $build --target nscd_benchmarks)" >&2; exit 2; }
done
grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt" || { echo "bench_results.sh: $build is not a Release build" >&2; exit 2; }
out=tests/bench/results/$machine
work=$(mktemp -d)
mkdir -p "$out"
runs=${RUNS:-3}

only=${ONLY:-}
part() { [[ -z $only || $only == "$1" ]]; }

part machine && {
  echo "machine = $machine"
  echo "date = $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "commit = $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "cpu = $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "cores = $(nproc)"
  echo "memory = $(free -g | awk '/^Mem:/ {print $2 " GiB"}')"
  echo "load_before = $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/machine.txt"
[[ -n $only ]] && echo "load_before_$only = $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD 2>/dev/null))" >> "$out/machine.txt"

if part detection; then
echo "== detection"
nice "$build/tests/bench_detection" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/detection.csv" --benchmark_out_format=csv
fi
if part nlgs; then
echo "== NLGS update"
# two files: Google Benchmark's CSV needs the same counters in every row
nice "$build/tests/bench_nlgs" --benchmark_filter=ContactUpdate --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/nlgs.csv" --benchmark_out_format=csv
nice "$build/tests/bench_nlgs" --benchmark_filter=ColorContacts --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/nlgs_colouring.csv" --benchmark_out_format=csv
fi

if part scaling; then
echo "== settled step (scaling)"
sample=${SAMPLE:-}
if [[ -z $sample ]]; then
  nice "$build/examples/deposit/deposit" --grains 700 --no-vtk --progress-every 30 --output "$work/dep700" --overwrite
  sample=$work/dep700/final_state.nscd
fi
rm -f "$out/scaling.csv"
for run in $(seq "$runs"); do
  for copies in 1 10 100; do
    for order in rows copies; do  # interleaved: the machine's drift hits both orders alike
      nice "$build/examples/scaling/scaling" --sample "$sample" --copies "$copies" --order "$order" --warmup 20 --steps 50 \
        --machine "$machine" --label "$order" --csv "$out/scaling.csv"
    done
  done
done
for order in rows copies; do
  png=$out/scaling.png
  [[ $order == copies ]] && png=$out/scaling_copies.png
  if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
    /usr/bin/python3 contrib/plots/plot_scaling.py "$out/scaling.csv" --label "$order" -o "$png" --title "$machine, order $order,"
  else
    python3 contrib/plots/plot_scaling.py "$out/scaling.csv" --label "$order" --no-plot
  fi
done
fi

if part threads; then
echo "== settled step, one and two threads in turn (scaling --threads 1,2)"
sample=${SAMPLE:-}
if [[ -z $sample ]]; then
  [[ -f $work/dep700/final_state.nscd ]] ||
    nice "$build/examples/deposit/deposit" --grains 700 --no-vtk --progress-every 30 --output "$work/dep700" --overwrite
  sample=$work/dep700/final_state.nscd
fi
rm -f "$out/scaling_threads.csv"
for run in $(seq "$runs"); do
  for copies in 1 10 100; do
    nice "$build/examples/scaling/scaling" --sample "$sample" --copies "$copies" --order rows --nlgs-order colored \
      --threads 1,2 --turn 5 --warmup 20 --steps 30 --machine "$machine" --label rows-colored --csv "$out/scaling_threads.csv"
  done
done
echo "== small runs, one and two threads in turn (tools/threads_table.sh)"
# (not under nice: a thread that waits for its core at every barrier measures the host, not nscd)
SAMPLE=${PAPER_SAMPLE:-} tools/threads_table.sh "$build" "$work/threads_table" | tee "$work/threads_table.log"
{
  echo "# tools/threads_table.sh on $machine, $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD 2>/dev/null)"
  echo
  sed -n '/^load after/,$p' "$work/threads_table.log"
} > "$out/threads_table.md"
fi

if part lmgc90; then
  echo "== LMGC90 case (10,000 steps)"
  nice "$build/examples/deposit/lmgc90_deposit_case" --no-vtk --progress-every 30 --output "$work/lmgc90" --overwrite
  cp "$work/lmgc90/summary.txt" "$out/lmgc90_case.txt"
  { echo "key,value"; sed -n 's/^\([a-z_0-9]*\) = \([^,]*\)$/\1,\2/p' "$out/lmgc90_case.txt"; } > "$out/lmgc90_case.csv"
  echo "== LMGC90 case, colored-rows order, relaxation 1.3 (the fastest settings without mixing, docs/benchmarks.md §2.2)"
  nice "$build/examples/deposit/lmgc90_deposit_case" --no-vtk --progress-every 30 --order colored-rows --relaxation 1.3 \
    --output "$work/lmgc90_rows" --overwrite
  cp "$work/lmgc90_rows/summary.txt" "$out/lmgc90_case_rows.txt"
  { echo "key,value"; sed -n 's/^\([a-z_0-9]*\) = \([^,]*\)$/\1,\2/p' "$out/lmgc90_case_rows.txt"; } > "$out/lmgc90_case_rows.csv"
  echo "== LMGC90 case, the same with Anderson mixing of depth 5 (theory §9.5b)"
  nice "$build/examples/deposit/lmgc90_deposit_case" --no-vtk --progress-every 30 --order colored-rows --relaxation 1.3 \
    --anderson 3 --output "$work/lmgc90_mixed" --overwrite
  cp "$work/lmgc90_mixed/summary.txt" "$out/lmgc90_case_mixed.txt"
  { echo "key,value"; sed -n 's/^\([a-z_0-9]*\) = \([^,]*\)$/\1,\2/p' "$out/lmgc90_case_mixed.txt"; } > "$out/lmgc90_case_mixed.csv"
fi
echo "load_after${only:+_$only} = $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/machine.txt"
rm -rf "$work"
echo "results in $out"
