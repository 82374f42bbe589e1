#!/bin/bash
# Split one job over N Slurm array tasks (--part I/N), then merge once all of them succeeded.
# Prints the merge step's job id; pass extra sbatch options (e.g. --wait) after N.
#
#   ci/slurm/submit-parts.sh JOB.yaml OUT_DIR N [sbatch options for the merge step...]
set -euo pipefail
. "$(dirname "$0")/submit-array.sh"
submit_array JOB.yaml parts "" merge.sbatch "$@"
