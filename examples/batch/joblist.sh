# shellcheck shell=bash
# Shared by parallel.sh and slurm_array.sh (sourced, not run): the job list of a batch, one job a
# line, tab-separated: PERFORMANCE_FILE  HEAD_NAME  HEAD  LANDMARKS (empty for 'default' and folders).
# Jobs go performance-major: line k (from 0) is performance k / H, head k % H, for H heads.
#
# The heads file: one head a line, "NAME HEAD [LANDMARKS]" (blank lines and # comments skipped):
#   default  default
#   ict      /data/ict
#   small    /data/small.obj  /data/small_landmarks.json
# NAME names the output folder OUT/NAME/<performance's file name without extension>/.

# myo_performances DIR: the performance files in DIR (.csv, .jsonl, .json), sorted by name.
myo_performances() {
  find "$1" -maxdepth 1 -type f \( -name '*.csv' -o -name '*.jsonl' -o -name '*.json' \) | LC_ALL=C sort
}

# myo_heads FILE: the heads file's lines, tab-separated NAME HEAD LANDMARKS.
myo_heads() {
  local name head landmarks rest
  while read -r name head landmarks rest || [ -n "$name" ]; do
    case "$name" in '' | '#'*) continue ;; esac
    if [ -z "$head" ] || [ -n "$rest" ]; then
      echo "$1: expected 'NAME HEAD [LANDMARKS]', got: $name $head $landmarks $rest" >&2
      return 2
    fi
    printf '%s\t%s\t%s\n' "$name" "$head" "$landmarks"
  done < "$1"
}

# myo_job_list PERFORMANCES_DIR HEADS_FILE: the job list (above) on stdout.
myo_job_list() {
  local heads perfs perf
  [ -d "$1" ] || { echo "$1: not a folder of performances" >&2; return 2; }
  [ -f "$2" ] || { echo "$2: no such heads file" >&2; return 2; }
  heads=$(myo_heads "$2") || return 2
  [ -n "$heads" ] || { echo "$2: no heads" >&2; return 2; }
  perfs=$(myo_performances "$1")
  [ -n "$perfs" ] || { echo "$1: no performance files (.csv, .jsonl, .json)" >&2; return 2; }
  while IFS= read -r perf; do
    while IFS= read -r head; do printf '%s\t%s\n' "$perf" "$head"; done <<< "$heads"
  done <<< "$perfs"
}

# myo_job OUT CACHE MYOSHELL PERFORMANCE HEAD_NAME HEAD LANDMARKS [drive args...]: one job. Writes
# OUT/HEAD_NAME/<performance>/ (the drive's outputs, job.json: its --json summary with peak_rss_mb
# and basis_cache, job.log: its messages). Exit status: the drive's.
myo_job() {
  local out=$1 cache=$2 myoshell=$3 perf=$4 name=$5 head=$6 landmarks=$7
  shift 7
  local base dir
  base=$(basename "$perf")
  dir="$out/$name/${base%.*}"
  mkdir -p "$dir"
  local args=(drive "$perf" --head "$head" --out "$dir" --cache "$cache" --json)
  [ -n "$landmarks" ] && args+=(--landmarks "$landmarks")
  # One thread a job unless told otherwise (the recipes run a job per core; a Slurm task gets the
  # cores it asked for): a drive's --threads defaults to every core, which jobs side by side share.
  case " $* " in
    *" --threads "*) ;;
    *) args+=(--threads "${SLURM_CPUS_PER_TASK:-1}") ;;
  esac
  "$myoshell" "${args[@]}" "$@" > "$dir/job.json" 2> "$dir/job.log"
}
