# submit-array.sh: sourced by submit-parts.sh and submit-study.sh (not run alone). Both submit
# part.sbatch as an array of N tasks (task I: `worker JOB --out OUT --part I/N`), then one step
# that runs once all of them succeeded (afterok), and print that step's job id.
#
#   submit_array USAGE LABEL NAME STEP JOB OUT N [sbatch options for the step...]
# USAGE: the job file's word in the usage line (JOB.yaml); LABEL: what the array is called on
# stderr; NAME: the array's --job-name ("": part.sbatch's own); STEP: the dependent step's
# .sbatch file beside this one.
submit_array() {
    local usage=$1 label=$2 name=$3 step=$4 here
    here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
    shift 4
    local line="usage: $0 $usage OUT_DIR N [sbatch options...] (N: tasks, a whole number from 1 to 256)"
    [ $# -ge 3 ] || { echo "$line" >&2; exit 2; }
    local job=$1 out=$2 n=$3 array named=()
    shift 3
    # N is checked as text before any arithmetic: $((...)) would run a command substitution in it
    # (PWD[$(cmd)]), and 0, -1 or 300 are no array Slurm (or --part, at most 256) takes
    case $n in
    '' | *[!0-9]* | ????*) echo "$0: N must be a whole number from 1 to 256, got '$n'; $line" >&2; exit 2 ;;
    esac
    n=$((10#$n))
    [ "$n" -ge 1 ] && [ "$n" -le 256 ] || { echo "$0: N must be from 1 to 256, got $n; $line" >&2; exit 2; }
    [ -n "$name" ] && named=(--job-name="$name")
    export JOB=$job OUT=$out PARTS=$n WORKER=${WORKER:-worker}
    array=$(sbatch --parsable --array="0-$((n - 1))" ${named[@]+"${named[@]}"} --export=ALL "$here/part.sbatch")
    array=${array%%;*}
    echo "$label: job $array (array 0-$((n - 1)))" >&2
    sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes --export=ALL "$@" "$here/$step"
}
