#!/usr/bin/env bash
# make fuzz-replay: runs every fuzz target once over each file of its seed corpus
# (fuzz/corpus/TARGET: valid inputs, the bad-input catalogue, and every fixed finding), so a
# regression in a reader shows up without fuzzing. Exit status 1 at the first target that fails.
# Usage: fuzz/replay.sh [BUILD_DIR]: the sanitized build's replay programs (build-asan, the
# default: make fuzz-replay) or libFuzzer's targets (build-fuzz), which take the same arguments.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
targets=${FUZZ_TARGETS:-fuzz_obj fuzz_vertex_set fuzz_landmarks fuzz_scene fuzz_attachment fuzz_rig fuzz_markers fuzz_retarget_map fuzz_facs_map fuzz_performance fuzz_livelink_packet fuzz_vmc_packet fuzz_web_face}
mkdir -p "$build/logs"
for t in $targets; do
  log=$build/logs/$t.replay.log
  mapfile -t files < <(find "fuzz/corpus/$t" -type f | sort)
  start=$(date +%s%N)
  if ! UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
      "$build/bin/$t" -timeout=10 -rss_limit_mb=2048 "${files[@]}" >"$log" 2>&1; then
    echo "$t: FAILED replaying fuzz/corpus/$t (log: $log)"
    grep -E "ERROR|Running:|FUZZ property|runtime error|terminate" "$log" | tail -20
    exit 1
  fi
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  printf '%-16s %4d inputs replayed cleanly in %d ms\n' "$t" "${#files[@]}" "$ms"
done
