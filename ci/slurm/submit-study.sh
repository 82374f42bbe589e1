#!/bin/bash
# Spread a study (a compare job or suite) over N Slurm array tasks, each rendering its share of the
# images (`worker JOB --out OUT --part I/N`; a reference is rendered once, by the first task that
# needs it), then gather once all of them succeeded (afterok). Resumable: submitted again, the
# tasks skip every image whose sidecar records the same job hash. Prints the gather's job id; pass
# extra sbatch options (e.g. --wait) after N.
#
#   ci/slurm/submit-study.sh STUDY.yaml OUT_DIR N [sbatch options for the gather step...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ $# -ge 3 ] || { echo "usage: $0 STUDY.yaml OUT_DIR N [sbatch options...]" >&2; exit 2; }
job=$1 out=$2 n=$3
shift 3
export JOB=$job OUT=$out PARTS=$n WORKER=${WORKER:-worker}
renders=$(sbatch --parsable --array="0-$((n - 1))" --job-name=worker-study --export=ALL "$here/part.sbatch")
renders=${renders%%;*}
echo "renders: job $renders (array 0-$((n - 1)))" >&2
sbatch --parsable --dependency="afterok:$renders" --kill-on-invalid-dep=yes --export=ALL "$@" "$here/gather.sbatch"
