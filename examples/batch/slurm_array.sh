#!/usr/bin/env bash
# A folder of performances × a list of heads as a Slurm job array: one array task per
# (performance, head), each a `myoshell drive` into OUT/<head name>/<performance>/, all sharing one
# basis cache on a file system the nodes share (docs/batch.md).
#
#   examples/batch/slurm_array.sh submit PERFORMANCES_DIR HEADS_FILE OUT_DIR [-- DRIVE_ARGS...]
#   examples/batch/slurm_array.sh list   PERFORMANCES_DIR HEADS_FILE
#
# list: print the job list, "INDEX<TAB>PERFORMANCE<TAB>HEAD NAME<TAB>HEAD<TAB>LANDMARKS", and stop
#   (the array task INDEX drives that pair). Needs no Slurm.
# submit: write OUT_DIR/jobs.tsv and submit two arrays: tasks 0..H-1 (the first performance on each
#   of the H heads: they build the cache, each head's bases once) and, after they all succeed
#   (--dependency=afterok), tasks H..N-1, which only read the cache. Prints the two job ids.
# Environment: MYOSHELL (the program; default `myoshell` on PATH, resolved at submit), CACHE (the
#   basis cache; default OUT_DIR/cache: on a shared file system, see docs/batch.md on locks over
#   NFS), SBATCH_ARGS (more sbatch options, e.g. "--partition=cpu --mem=1G --time=0:30:00"; size
#   --mem from a test job's peak_rss_mb).
# Each task keeps its --json summary as job.json (peak_rss_mb, basis_cache) and its messages as
# job.log beside its outputs; Slurm's own output goes to OUT_DIR/slurm/<job>_<task>.out.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=joblist.sh
. "$here/joblist.sh"

usage() { sed -n '2,/^set -euo/p' "$here/slurm_array.sh" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }

case "${1:-}" in
  task)  # slurm_array.sh task OUT_DIR: run by each array task
    out=$2
    k=${SLURM_ARRAY_TASK_ID:?slurm_array.sh task runs inside a Slurm array task}
    line=$(sed -n "$((k + 1))p" "$out/jobs.tsv")
    [ -n "$line" ] || { echo "slurm_array.sh: no job $k in $out/jobs.tsv" >&2; exit 2; }
    IFS=$'\t' read -r perf name head landmarks <<< "$line"
    mapfile -t drive_args < "$out/drive_args.txt"
    myo_job "$out" "$(cat "$out/cache_dir.txt")" "$(cat "$out/myoshell.txt")" "$perf" "$name" "$head" "${landmarks:-}" \
      "${drive_args[@]}"
    ;;
  list)
    [ $# -eq 3 ] || usage
    jobs_list=$(myo_job_list "$2" "$3") || exit 2
    awk -F'\t' '{ printf "%d\t%s\t%s\t%s\t%s\n", NR - 1, $1, $2, $3, $4 }' <<< "$jobs_list"
    ;;
  submit)
    [ $# -ge 4 ] || usage
    perf_dir=$2 heads_file=$3 out=$4
    shift 4
    if [ "${1:-}" = "--" ]; then shift; fi
    jobs_list=$(myo_job_list "$perf_dir" "$heads_file") || exit 2
    command -v sbatch > /dev/null || { echo "slurm_array.sh: no sbatch (Slurm's client)" >&2; exit 2; }
    myoshell=$(command -v "${MYOSHELL:-myoshell}") || { echo "slurm_array.sh: no program '${MYOSHELL:-myoshell}' (set MYOSHELL)" >&2; exit 2; }
    mkdir -p "$out/slurm" "${CACHE:-$out/cache}"
    out=$(cd "$out" && pwd)
    cache=$(cd "${CACHE:-$out/cache}" && pwd)
    # Absolute performance paths: the tasks may start in another folder.
    awk -F'\t' -v OFS='\t' -v pwd="$PWD" '{ if ($1 !~ /^\//) $1 = pwd "/" $1; print }' <<< "$jobs_list" > "$out/jobs.tsv"
    printf '%s\n' "$@" > "$out/drive_args.txt"
    [ $# -gt 0 ] || : > "$out/drive_args.txt"
    printf '%s\n' "$cache" > "$out/cache_dir.txt"
    printf '%s\n' "$myoshell" > "$out/myoshell.txt"
    n=$(wc -l < "$out/jobs.tsv")
    h=$(myo_heads "$heads_file" | wc -l)
    # shellcheck disable=SC2086  # SBATCH_ARGS: options split on spaces
    first=$(sbatch --parsable --job-name=myoshell-cache --array=0-$((h - 1)) --output="$out/slurm/%A_%a.out" \
      ${SBATCH_ARGS:-} --wrap "bash '$here/slurm_array.sh' task '$out'")
    echo "cache-building array: $first (tasks 0-$((h - 1)))"
    if [ "$n" -gt "$h" ]; then
      # shellcheck disable=SC2086
      rest=$(sbatch --parsable --job-name=myoshell-drive --array=$h-$((n - 1)) --dependency=afterok:"${first%%;*}" \
        --output="$out/slurm/%A_%a.out" ${SBATCH_ARGS:-} --wrap "bash '$here/slurm_array.sh' task '$out'")
      echo "drive array: $rest (tasks $h-$((n - 1)), after $first)"
    fi
    ;;
  *) usage ;;
esac
