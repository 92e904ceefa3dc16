#!/usr/bin/env bash
# A folder of performances × a list of heads, driven with GNU parallel (Debian package `parallel`)
# on the cores of one machine: one `myoshell drive` per (performance, head), each into its own
# folder OUT/<head name>/<performance>/, all sharing one basis cache (docs/batch.md).
#
#   examples/batch/parallel.sh [--dry-run] PERFORMANCES_DIR HEADS_FILE OUT_DIR [-- DRIVE_ARGS...]
#
# PERFORMANCES_DIR: the .csv / .jsonl / .json performances (docs/performance_input.md).
# HEADS_FILE: one head a line, "NAME HEAD [LANDMARKS]" (examples/batch/joblist.sh).
# DRIVE_ARGS: passed to every drive (e.g. --format glb,pc2 --library builtin).
# --dry-run: print the job list (job index, performance, head name, head, landmarks) and stop.
# Environment: MYOSHELL (the program; default `myoshell` on PATH), JOBS (parallel jobs at once;
# default one per core), CACHE (the basis cache folder; default OUT_DIR/cache).
#
# The cache is built once first: the first performance's jobs (one per head, different bases, so
# they never wait for each other) compute and store each head's bases; the cache folder is then
# made read-only (chmod a-w, restored at the end) and the other jobs only read it. Each job's
# --json summary is kept as job.json beside its outputs (peak_rss_mb: its peak memory; basis_cache:
# "hit" once the cache is built), its messages as job.log; parallel's job logs are OUT_DIR/joblog_*.tsv.
# Exit status: 0 when every job succeeded, 1 when one failed (listed), 2 on a bad argument.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=joblist.sh
. "$here/joblist.sh"

if [ "${1:-}" = "--job" ]; then  # one job, as parallel runs it
  shift
  myo_job "$@"
  exit
fi

dry=0
if [ "${1:-}" = "--dry-run" ]; then dry=1; shift; fi
if [ $# -lt 3 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
fi
perf_dir=$1 heads_file=$2 out=$3
shift 3
if [ "${1:-}" = "--" ]; then shift; fi
drive_args=("$@")

jobs_list=$(myo_job_list "$perf_dir" "$heads_file") || exit 2
if [ $dry = 1 ]; then
  awk -F'\t' '{ printf "%d\t%s\t%s\t%s\t%s\n", NR - 1, $1, $2, $3, $4 }' <<< "$jobs_list"
  exit 0
fi
command -v parallel > /dev/null || { echo "parallel.sh: GNU parallel is not installed (apt-get install parallel)" >&2; exit 2; }
myoshell=${MYOSHELL:-myoshell}
command -v "$myoshell" > /dev/null || { echo "parallel.sh: no program '$myoshell' (set MYOSHELL)" >&2; exit 2; }
cache=${CACHE:-$out/cache}
jobs=${JOBS:-100%}
mkdir -p "$out" "$cache"
out=$(cd "$out" && pwd)
cache=$(cd "$cache" && pwd)

heads=$(myo_heads "$heads_file" | wc -l)
printf '%s\n' "$jobs_list" | head -n "$heads" > "$out/jobs_first.tsv"
printf '%s\n' "$jobs_list" | tail -n +"$((heads + 1))" > "$out/jobs_rest.tsv"

run() {  # run LOG LIST: the jobs of LIST through parallel; its exit status is the failures' count
  parallel --will-cite --jobs "$jobs" --colsep '\t' --joblog "$1" --halt never \
    bash "$here/parallel.sh" --job "$out" "$cache" "$myoshell" '{1}' '{2}' '{3}' '{4}' "${drive_args[@]}" :::: "$2"
}

failed=0
run "$out/joblog_first.tsv" "$out/jobs_first.tsv" || failed=1
if [ -s "$out/jobs_rest.tsv" ]; then
  chmod a-w "$cache"
  trap 'chmod u+w "$cache"' EXIT
  run "$out/joblog_rest.tsv" "$out/jobs_rest.tsv" || failed=1
fi
if [ $failed = 1 ]; then
  echo "parallel.sh: failed jobs (exit status, command):" >&2
  awk -F'\t' 'FNR > 1 && $7 != 0 { print "  " $7 "\t" $9 }' "$out"/joblog_*.tsv >&2
  exit 1
fi
echo "parallel.sh: $(printf '%s\n' "$jobs_list" | wc -l) jobs done in $out"
