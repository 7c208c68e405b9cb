#!/bin/bash
# tools/measure_cost.sh — the measurements behind the Slurm cost model of the batch studies
# (examples/study_common/slurm.cpp, docs/studies.md §2.2): a preparation and 10 loading cycles
# of ballast at two sizes (181 and 724 grains), with their processor time and largest resident
# memory (GNU time). Usage: tools/measure_cost.sh BUILD_DIR [WORK_DIR]  (about 5 min of CPU)
set -euo pipefail
B=${1:?usage: tools/measure_cost.sh BUILD_DIR [WORK_DIR]}/examples/ballast/ballast
W=${2:-out/measure_cost}
[ -x "$B" ] || { echo "measure_cost: no ballast at $B (cmake --build BUILD_DIR --target ballast)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "measure_cost: needs GNU time (Debian: apt-get install time)" >&2; exit 2; }
mkdir -p "$W"
for size in quarter full; do
  opts=()
  [ "$size" = quarter ] && opts=(--grading-fraction 0.25 --box-width 0.5 --pads 25 --sleeper-width 0.1)
  /usr/bin/time -f "$size prepare: %U user %S sys %e wall %M maxrss_kB" "$B" --prepare-only --output "$W/$size/sample" \
    --overwrite --progress-every 100 "${opts[@]}" > "$W/$size.prep.log" 2>&1
  tail -1 "$W/$size.prep.log"
  /usr/bin/time -f "$size run: %U user %S sys %e wall %M maxrss_kB" "$B" --sample "$W/$size/sample/sample.nscd" --cycles 10 \
    --vtk-every 0 --output "$W/$size/run" --overwrite --progress-every 100 > "$W/$size.run.log" 2>&1
  tail -1 "$W/$size.run.log"
  grep -E "^(grains|steps_per_cycle|mean_sweeps|cpu_time_per_cycle|time_per_cycle) " "$W/$size/run/summary.txt"
done
