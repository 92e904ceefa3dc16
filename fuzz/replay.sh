#!/usr/bin/env bash
# make fuzz-replay: runs every libFuzzer target once over each file of its seed corpus
# (fuzz/corpus/TARGET: valid inputs, the bad-input catalogue, and every fixed finding), so a
# regression in a reader shows up without fuzzing. Exit status 1 at the first target that fails.
set -uo pipefail
cd "$(dirname "$0")/.."
targets=${FUZZ_TARGETS:-fuzz_obj fuzz_vertex_set fuzz_landmarks fuzz_scene fuzz_attachment fuzz_rig fuzz_markers fuzz_retarget_map fuzz_facs_map fuzz_performance fuzz_livelink_packet fuzz_vmc_packet fuzz_web_face}
mkdir -p build-fuzz/logs
for t in $targets; do
  log=build-fuzz/logs/$t.replay.log
  mapfile -t files < <(find "fuzz/corpus/$t" -type f | sort)
  start=$(date +%s%N)
  if ! UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
      "build-fuzz/bin/$t" -timeout=10 -rss_limit_mb=2048 "${files[@]}" >"$log" 2>&1; then
    echo "$t: FAILED replaying fuzz/corpus/$t (log: $log)"
    grep -E "ERROR|Running:|FUZZ property|runtime error|terminate" "$log" | tail -20
    exit 1
  fi
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  printf '%-16s %4d inputs replayed cleanly in %d ms\n' "$t" "${#files[@]}" "$ms"
done
