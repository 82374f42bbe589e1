#!/bin/bash
# Split one job over N Slurm array tasks (--part I/N), then merge once all of them succeeded.
# Prints the merge step's job id; pass extra sbatch options (e.g. --wait) after N.
#
#   ci/slurm/submit-parts.sh JOB.yaml OUT_DIR N [sbatch options for the merge step...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ $# -ge 3 ] || { echo "usage: $0 JOB.yaml OUT_DIR N [sbatch options...]" >&2; exit 2; }
job=$1 out=$2 n=$3
shift 3
export JOB=$job OUT=$out PARTS=$n WORKER=${WORKER:-worker}
parts=$(sbatch --parsable --array="0-$((n - 1))" --export=ALL "$here/part.sbatch")
parts=${parts%%;*}
echo "parts: job $parts (array 0-$((n - 1)))" >&2
sbatch --parsable --dependency="afterok:$parts" --kill-on-invalid-dep=yes --export=ALL "$@" "$here/merge.sbatch"
