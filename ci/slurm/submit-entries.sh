#!/bin/bash
# Spread a study (a compare job or suite) over a Slurm array of one task per entry of its plan
# (`worker plan`: each reference's two halves, each image; a render above the entry target cut
# into row parts, merged once by the task that ends its last part), then gather once all of them
# succeeded (afterok). The entry names go to OUT/.entries-<stem>.txt, one a line, in claim order
# (references first: an image's task waits for the tasks rendering its reference). Resumable:
# submitted again, every task finds its render current (merged, or in the cache) and renders
# nothing. Prints the gather's job id; pass extra sbatch options (e.g. --wait) after OUT_DIR.
#
#   ci/slurm/submit-entries.sh STUDY.yaml OUT_DIR [sbatch options for the gather step...]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
[ $# -ge 2 ] || { echo "usage: $0 STUDY.yaml OUT_DIR [sbatch options...]" >&2; exit 2; }
job=$1 out=$2
shift 2
mkdir -p "$out"
stem=$(basename "$job"); stem=${stem%.*}
list=$out/.entries-$stem.txt
"${WORKER:-worker}" plan -- "$job" | awk '$1 ~ /^[ab]-[a-z]+-[0-9].*\.yaml$/ { print $1 }' >"$list.tmp"
mv "$list.tmp" "$list"
n=$(wc -l <"$list")
[ "$n" -ge 1 ] || { echo "$0: $job: no entries (see worker plan $job)" >&2; exit 2; }
export JOB=$job OUT=$out ENTRIES=$list WORKER=${WORKER:-worker}
array=$(sbatch --parsable --array="0-$((n - 1))" --export=ALL "$here/entry.sbatch")
array=${array%%;*}
echo "entries: job $array (array 0-$((n - 1)): $n entries)" >&2
sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes --export=ALL "$@" "$here/gather.sbatch"
