#!/bin/bash
# Spread a study (a compare job or suite) over N Slurm array tasks, each rendering its share of the
# images (`worker JOB --out OUT --part I/N`; a reference is rendered once, by the first task that
# needs it), then gather once all of them succeeded (afterok). Resumable: submitted again, the
# tasks skip every image whose sidecar records the same job hash. Prints the gather's job id; pass
# extra sbatch options (e.g. --wait) after N.
#
#   ci/slurm/submit-study.sh STUDY.yaml OUT_DIR N [sbatch options for the gather step...]
set -euo pipefail
. "$(dirname "$0")/submit-array.sh"
submit_array STUDY.yaml renders worker-study gather.sbatch "$@"
