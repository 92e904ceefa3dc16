#!/usr/bin/env bash
# make fuzz: runs each libFuzzer target for FUZZ_SECONDS (default 60) on its seed corpus
# (fuzz/corpus/TARGET, read only) and a work corpus that grows across runs
# (build-fuzz/corpus/TARGET), then prints executions and findings per target. A finding (crash,
# undefined behaviour, CheckError, unexpected exception, timeout > 10 s, > 2 GB memory, leak)
# stops that target and lands in fuzz/findings/TARGET-{crash,timeout,oom,leak}-SHA1; replay one
# with `build-fuzz/bin/TARGET FILE`. Exit status 1 when anything was found.
set -uo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
targets=${FUZZ_TARGETS:-fuzz_obj fuzz_vertex_set fuzz_landmarks fuzz_scene fuzz_attachment fuzz_rig fuzz_markers fuzz_retarget_map fuzz_facs_map fuzz_performance fuzz_livelink_packet fuzz_vmc_packet fuzz_web_face}
bin=build-fuzz/bin
mkdir -p fuzz/findings build-fuzz/logs

maxLen() {  # longest input per target: a few times the largest seed
  case $1 in
    fuzz_obj) echo 8192 ;;
    fuzz_vertex_set) echo 2048 ;;
    fuzz_performance) echo 8192 ;;  # a Live Link Face row is 600 bytes
    *) echo 4096 ;;
  esac
}

found=0
printf '%-16s %8s %12s %9s %8s %9s  %s\n' target seconds executions exec/s corpus findings log
for t in $targets; do
  work=build-fuzz/corpus/$t
  log=build-fuzz/logs/$t.log
  mkdir -p "$work"
  before=$(find fuzz/findings -name "$t-*" -type f | wc -l)
  start=$(date +%s)
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
    "$bin/$t" "$work" "fuzz/corpus/$t" -dict="fuzz/dict/$t.dict" -max_len="$(maxLen "$t")" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="fuzz/findings/$t-" >"$log" 2>&1
  rc=$?
  took=$(( $(date +%s) - start ))
  execs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log" | tail -1)
  rate=$(awk '/stat::average_exec_per_sec/ {print $2}' "$log" | tail -1)
  corpus=$(find "$work" -type f | wc -l)
  after=$(find fuzz/findings -name "$t-*" -type f | wc -l)
  new=$((after - before))
  if [ "$rc" -ne 0 ] || [ "$new" -gt 0 ]; then
    found=1
    [ "$new" -eq 0 ] && new="rc=$rc"
  fi
  printf '%-16s %8s %12s %9s %8s %9s  %s\n' "$t" "$took" "${execs:-?}" "${rate:-?}" "$corpus" "$new" "$log"
done
if [ "$found" -ne 0 ]; then
  echo "findings in fuzz/findings/ (see the logs above):"
  ls -1 fuzz/findings | sed 's/^/  /'
  exit 1
fi
