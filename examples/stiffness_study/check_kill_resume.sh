#!/bin/bash
# check_kill_resume.sh — the batch path survives being stopped (issue #11): a stiffness-study
# run planned with --plan-only and run by GNU parallel is
#   1. stopped by SIGTERM to GNU parallel (Ctrl-C, a scheduler): ballast ends its cycle with a
#      checkpoint and exits 143;
#   2. rerun as a requeued Slurm task would (bash -c "line N of commands.txt") and killed with
#      kill -9 once a wall-time checkpoint (--checkpoint-wall, --checkpoint-every 0) is newer;
#   3. finished by the same GNU parallel command (--resume-failed; ballast --continue resumes);
# its cycles.csv must equal, wall-clock column aside, that of one uninterrupted ballast run.
# Usage: check_kill_resume.sh STIFFNESS_STUDY BALLAST WORK_DIR
set -euo pipefail
STUDY=$1 BALLAST=$2 W=$3
N=60
fail() { echo "check_kill_resume: FAIL: $*" >&2; exit 1; }
rows() { if [ -f "$1" ]; then echo $(( $(wc -l < "$1") - 1 )); else echo 0; fi; }
cycles_done() { sed -n 's/^x "state\.cycles_done" "\([0-9]*\)"$/\1/p' "$1" 2>/dev/null | head -1; }
wait_rows() {  # file, rows, timeout (s)
  for _ in $(seq $(( $3 * 20 ))); do [ "$(rows "$1")" -ge "$2" ] && return 0; sleep 0.05; done
  fail "$1 did not reach $2 rows in $3 s"
}
rm -rf "$W"
mkdir -p "$W"
load=(--ballast-option load-mean=-100 --ballast-option load-amplitude=-50)
"$STUDY" --plan-only --samples 1 --k-factors 1 --cycles $N --grading-fraction 0.05 --box-width 0.2 --pads 10 \
  --sleeper-width 0.06 "${load[@]}" --ballast-option checkpoint-every=0 --ballast-option checkpoint-wall=0.2 \
  --ballast "$BALLAST" --output "$W/study" > "$W/plan.log"
S=$W/study
R=$S/k1_s2006
parallel --joblog "$S/joblog_prepare.txt" --resume-failed -j 1 :::: "$S/prepare.txt"
# the reference: the same run, uninterrupted
"$BALLAST" --sample "$S/sample_2006/sample.nscd" --seed 2006 --k-factor 1 --cycles $N --vtk-every 0 --load-mean -100 \
  --load-amplitude -50 --output "$W/reference" --progress-every 100 > "$W/reference.log"

# 1. SIGTERM to GNU parallel while the run is under way
parallel --joblog "$S/joblog.txt" --resume-failed -j 1 --termseq TERM,60000,KILL,25 :::: "$S/commands.txt" &
P=$!
wait_rows "$R/cycles.csv" 5 60
kill -TERM $P
wait $P || true
grep -q "SIGTERM: stopped after cycle" "$R/log.txt" || fail "ballast did not stop with a checkpoint on SIGTERM: $(tail -3 "$R/log.txt")"
c1=$(cycles_done "$R/checkpoint.nscd")
[ -n "$c1" ] && [ "$c1" -lt $N ] || fail "after SIGTERM: checkpoint at cycle '${c1}', expected fewer than $N"
[ "$(rows "$R/cycles.csv")" -eq "$c1" ] || fail "after SIGTERM: cycles.csv has $(rows "$R/cycles.csv") rows, the checkpoint $c1 cycles"
echo "1. SIGTERM: stopped at cycle $c1 with a checkpoint"

# 2. the line rerun as a requeued Slurm task would run it, then kill -9 after a wall-time checkpoint
line=$(sed -n 1p "$S/commands.txt")
bash -c "$line" &
B=$!
for _ in $(seq 1200); do
  c2=$(cycles_done "$R/checkpoint.nscd")
  [ -n "$c2" ] && [ "$c2" -gt "$c1" ] && [ "$c2" -lt $N ] && break
  sleep 0.05
done
kill -9 $B
wait $B || true
c2=$(cycles_done "$R/checkpoint.nscd")
[ "$c2" -gt "$c1" ] && [ "$c2" -lt $N ] || fail "no wall-time checkpoint between cycle $c1 and $N (at '$c2')"
grep -q "resuming $R at cycle $c1" "$R/log.txt" || fail "the rerun line did not resume at cycle $c1"
echo "2. kill -9 after the wall-time checkpoint at cycle $c2 (rows written: $(rows "$R/cycles.csv"))"

# 3. the same GNU parallel command finishes it
parallel --joblog "$S/joblog.txt" --resume-failed -j 1 :::: "$S/commands.txt"
grep -q "resuming $R at cycle $c2" "$R/log.txt" || fail "GNU parallel's rerun did not resume at cycle $c2"
strip() { awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_time") w = i } { s = ""; for (i = 1; i <= NF; ++i) if (i != w) s = s (s == "" ? "" : ",") $i; print s }' "$1"; }
[ "$(rows "$R/cycles.csv")" -eq $N ] || fail "the resumed run has $(rows "$R/cycles.csv") cycles, not $N"
diff <(strip "$R/cycles.csv") <(strip "$W/reference/cycles.csv") > "$W/diff.txt" || fail "cycles.csv differs from the uninterrupted run: $W/diff.txt"
"$STUDY" --gather "$S" > "$W/gather.log" || fail "gather failed: $(cat "$W/gather.log")"
echo "3. resumed to cycle $N: cycles.csv identical to the uninterrupted run (wall_time aside); gathered"
