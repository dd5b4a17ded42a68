#!/usr/bin/env bash
# A study across a Slurm cluster: one array task per shard, all writing into
# one directory on a shared file system, then one job that writes the
# statistics, figures and REPORT.md once every shard has finished.
#
#   sbatch --array=1-8 deploy/slurm/study-array.sh paper-scratch /shared/results/paper-scratch
#   sbatch --dependency=afterok:<array job id> deploy/slurm/study-array.sh paper-scratch /shared/results/paper-scratch
#
# The first line plays shard K of N (K = the array task id, N = the array's
# size); the second, started without an array, plays whatever is missing
# (nothing, if every shard finished) and writes the report. Arguments: a
# preset name (or a study file with STUDY_CONFIG=1) and the shared output
# directory. COORDINATOR: the coordinator executable (default: coordinator on
# PATH). Each task uses the cores Slurm gives it (--cpus-per-task).
#SBATCH --job-name=adv-study
#SBATCH --cpus-per-task=2
#SBATCH --time=02:00:00
#SBATCH --output=adv-study-%A_%a.log
set -euo pipefail

if [ $# -ne 2 ]; then
    echo "usage: sbatch [--array=1-N] $0 PRESET|STUDY_FILE OUT_DIR" >&2
    exit 2
fi
coordinator=${COORDINATOR:-coordinator}
if [ "${STUDY_CONFIG:-0}" = 1 ]; then which=(--config "$1"); else which=(--preset "$1"); fi
threads=${SLURM_CPUS_PER_TASK:-1}
shard=()
if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
    shard=(--shard "$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))/${SLURM_ARRAY_TASK_COUNT:?}")
fi
exec "$coordinator" study "${which[@]}" --out "$2" --threads "$threads" --quiet "${shard[@]}"
