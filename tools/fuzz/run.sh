#!/usr/bin/env bash
# tools/fuzz/run.sh — builds the libFuzzer targets (clang++, -fsanitize=fuzzer,address,undefined)
# and runs each for SECONDS seconds (default 180), nice'd, on a seed corpus made from real files.
#
#   tools/fuzz/run.sh [SECONDS] [TARGET...]      targets: checkpoint sample config problem siconos datbox
#
# Build in build-fuzz/ (FUZZ_BUILD to change), corpora and findings in build-fuzz/fuzz-out/<target>/
# (corpus/, crash-*, and <target>.log). A finding is any input that crashes, trips ASan or UBSan,
# or makes a reader throw anything but its documented error type. Keep every crasher as a test in
# tests/unit/test_fuzz_regressions.cpp (docs/user-guide.md, "Fuzzing the readers").
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
seconds="${1:-180}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(checkpoint sample config problem siconos datbox)
build="${FUZZ_BUILD:-$root/build-fuzz}"
jobs="${FUZZ_JOBS:-2}"

cmake -S "$here" -B "$build" -DCMAKE_CXX_COMPILER="${CXX_FUZZ:-clang++}" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
nice cmake --build "$build" -j"$jobs" --target $(printf 'fuzz_%s ' "${targets[@]}")

for t in "${targets[@]}"; do
  out="$build/fuzz-out/$t"
  mkdir -p "$out/corpus"
  # seeds: the committed ones, and real files of the repository
  cp -n "$here/seeds/$t/"* "$out/corpus/" 2>/dev/null || true
  case "$t" in
    checkpoint|sample) cp -n "$root/tests/data/ballast/mini_sample.nscd" "$out/corpus/" ;;
    config) cp -n "$root/examples/deposit/deposit.cfg" "$root/examples/long_run/long_run.cfg" "$out/corpus/" ;;
    siconos) cp -n "$root"/tests/data/siconos-fc2d/FC2D_SliderCrank*.dat "$out/corpus/" ;;
    datbox)  # each folder of tests/data/datbox as one input: its files, each after "#FILE <name>"
      for d in "$root"/tests/data/datbox/*/; do
        for f in "$d"*; do printf '#FILE %s\n' "$(basename "$f")"; cat "$f"; done > "$out/corpus/$(basename "$d").txt"
      done ;;
  esac
  echo "fuzz_$t: ${seconds}s, corpus $out/corpus, log $out/$t.log"
  ( cd "$out" && nice "$build/fuzz_$t" corpus -max_total_time="$seconds" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
      -print_final_stats=1 > "$t.log" 2>&1 ) || echo "fuzz_$t: FOUND A PROBLEM (see $out/$t.log and $out/crash-*)"
  grep -E "^stat::number_of_executed_units|DONE|ERROR:|SUMMARY" "$out/$t.log" | head -5 || true
done
