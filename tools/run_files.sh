#!/bin/bash
# tools/run_files.sh — sourced by the tools that compare runs (threads_table.sh, ab_threads.sh,
# many_cores.sh): a run's files without what the machine decided (its timings, the threads a
# step chose by measure), so that runs on any number of threads compare byte for byte.

# final_state DIR: the run's final_state.nscd, or ballast's last checkpoint but for the
# processor time it records.
final_state() {
  if [ -f "$1/final_state.nscd" ]; then cat "$1/final_state.nscd"; else grep -av '^x "state.cpu_seconds"' "$1/checkpoint.nscd"; fi
}

# untimed_csv FILE [ROWS]: a run's CSV (steps.csv, cycles.csv) without its timing columns
# (wall_time, those named *_s) and the threads each step chose (*_threads); with ROWS, the
# header and the first ROWS rows only.
untimed_csv() {
  awk -F, -v n="${2:-0}" 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = $i !~ /(_s|_threads)$|^wall_time$/ }
    n > 0 && NR > n + 1 { exit }
    { s = ""; for (i = 1; i <= NF; ++i) if (keep[i]) s = s $i ","; print s }' "$1"
}
