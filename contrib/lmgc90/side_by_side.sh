#!/usr/bin/env bash
# contrib/lmgc90/side_by_side.sh — runs each scene of tests/data/datbox made by datbox_scenes.py in
# LMGC90 (run_datbox.py) and in nscd (datbox_run) with the same settings, REPEAT times each, one
# after the other, and prints compare_datbox.py's table with the median CPU times (issue #39,
# docs/benchmarks.md section 9).
#
#   LMGC90_PYTHONPATH=/work/lmgc90/build contrib/lmgc90/side_by_side.sh [REPEAT] [SCENE...]
#
# Runs in ${WORK:-/tmp/side_by_side}/<scene>/{lmgc90,nscd}; needs build/examples/datbox/datbox_run.
# DATA=DIR takes the scenes from DIR/<scene> instead of tests/data/datbox (datbox_scenes.py --scale).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
repeat="${1:-3}"
shift || true
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(disks_jcbox polygons_jcbox disk_drum block_wall)
work="${WORK:-/tmp/side_by_side}"
data="${DATA:-$root/tests/data/datbox}"
py="${PYTHON:-/usr/bin/python3}"
common=(--theta 0.5 --tol 1.666e-4 --norm QM/16 --relaxation 1 --sweeps 1000 --check-every 10)

settings() {  # the time step and the number of steps of each scene
  case "$1" in
    disks_jcbox|polygons_jcbox) echo "5e-3 400" ;;
    disk_drum) echo "1e-2 500" ;;
    block_wall) echo "1e-3 300" ;;
    *) echo "unknown scene $1" >&2; exit 2 ;;
  esac
}

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

for s in "${scenes[@]}"; do
  read -r dt steps < <(settings "$s")
  d="$work/$s"
  mkdir -p "$d"
  : > "$d/lmgc90_cpu.txt"
  : > "$d/nscd_cpu.txt"
  for ((k = 1; k <= repeat; ++k)); do
    PYTHONPATH="${LMGC90_PYTHONPATH:-/work/lmgc90/build}" nice "$py" "$root/contrib/lmgc90/run_datbox.py" \
      --datbox "$data/$s" --workdir "$d/lmgc90" --dt "$dt" --steps "$steps" "${common[@]}" > "$d/lmgc90.log"
    grep '^cpu_time' "$d/lmgc90/summary.txt" | awk '{print $3}' >> "$d/lmgc90_cpu.txt"
    nice /usr/bin/time -f '%U %S' -o "$d/nscd_time.txt" "$root/build/examples/datbox/datbox_run" --datbox "$data/$s" \
      --dt "$dt" --steps "$steps" "${common[@]}" --output-every 0 --overwrite --output "$d/nscd" --write-datbox "$d/nscd/DATBOX" > "$d/nscd.log"
    awk '{print $1 + $2}' "$d/nscd_time.txt" >> "$d/nscd_cpu.txt"
  done
  echo "== $s: dt $dt, $steps steps, ${common[*]}; CPU times (s) LMGC90 $(tr '\n' ' ' < "$d/lmgc90_cpu.txt"), nscd $(tr '\n' ' ' < "$d/nscd_cpu.txt")"
  "$py" "$root/contrib/lmgc90/compare_datbox.py" --lmgc90 "$d/lmgc90" --nscd "$d/nscd" \
    --lmgc90-cpu "$(median < "$d/lmgc90_cpu.txt")" --nscd-cpu "$(median < "$d/nscd_cpu.txt")"
done
