#!/bin/sh
# The Slurm scripts' arguments (issue 36, defect 5), without Slurm: a stand-in sbatch records what
# it was asked. N of submit-study.sh and submit-parts.sh is checked as a decimal whole number from
# 1 to 256 before any arithmetic (never run as shell code), with a usage line and exit 2, nothing
# submitted; the .sbatch scripts pass the job file after "--", so a path starting with "-" is a file.
. tests/lib.sh
root=$(pwd)
command -v bash >/dev/null || { skip "no bash for the Slurm scripts"; finish; exit $?; }
mkdir -p "$T/bin"
printf '#!/bin/sh\necho "$*" >>"%s/sbatch.calls"\necho 42\n' "$T" >"$T/bin/sbatch"
chmod +x "$T/bin/sbatch"
for script in submit-study.sh submit-parts.sh; do
    for n in 'PWD[$(touch '"$T"'/ran)]' 0 -1 300 257 abc '' 1.5 ' 4' 0x10 99999999999999999999; do
        rm -f "$T/sbatch.calls"
        PATH=$T/bin:$PATH WORKER=$WORKER bash "$root/ci/slurm/$script" j.yaml out "$n" >"$T/out.txt" 2>"$T/err.txt"
        rc=$?
        check "$script N='$n': exit 2 (got $rc), one usage line: $(cat "$T/err.txt")" \
            eval '[ "$rc" -eq 2 ] && [ "$(grep -c "usage: .*N" "$T/err.txt")" -eq 1 ]'
        check "$script N='$n': nothing submitted, nothing run" eval '[ ! -e "$T/sbatch.calls" ] && [ ! -e "$T/ran" ]'
    done
    for n in 1 256 08; do
        rm -f "$T/sbatch.calls"
        PATH=$T/bin:$PATH WORKER=$WORKER bash "$root/ci/slurm/$script" j.yaml out "$n" >"$T/out.txt" 2>"$T/err.txt"
        rc=$?
        want=$(expr "$n" - 1)
        check "$script N=$n: submitted as array 0-$want (exit $rc): $(cat "$T/sbatch.calls" 2>/dev/null)" \
            eval '[ "$rc" -eq 0 ] && grep -q -- "--array=0-$want " "$T/sbatch.calls"'
    done
done

# the .sbatch scripts run as Slurm would (the task's variables set), on a job file named "-j.yaml"
mkdir -p "$T/w"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nheight: 6\nprocesses: 1\n' "$root" >"$T/w/-j.yaml"
(cd "$T/w" && JOB=-j.yaml OUT=o PARTS=2 SLURM_ARRAY_TASK_ID=0 WORKER=$WORKER bash "$root/ci/slurm/part.sbatch" &&
    JOB=-j.yaml OUT=o PARTS=2 SLURM_ARRAY_TASK_ID=1 WORKER=$WORKER bash "$root/ci/slurm/part.sbatch") \
    >/dev/null 2>"$T/part.txt"
rc=$?
check "part.sbatch: a job file named -j.yaml renders its parts (exit $rc): $(cat "$T/part.txt")" \
    eval '[ "$rc" -eq 0 ] && [ -f "$T/w/o/-j/-j.part-0-of-2" ] && [ -f "$T/w/o/-j/-j.part-1-of-2" ]'
(cd "$T/w" && JOB=-j.yaml OUT=o WORKER=$WORKER bash "$root/ci/slurm/merge.sbatch") >/dev/null 2>"$T/merge.txt"
rc=$?
check "merge.sbatch: merges them (exit $rc): $(cat "$T/merge.txt")" eval '[ "$rc" -eq 0 ] && [ -f "$T/w/o/-j/-j.png" ]'
printf 'name: st\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nheight: 6\nprocesses: 1\n' "$root" >"$T/w/-s.yaml"
printf 'variants: [{ sampler: jitter, threshold: 50 }]\n' >>"$T/w/-s.yaml"
(cd "$T/w" && JOB=-s.yaml OUT=o WORKER=$WORKER bash "$root/ci/slurm/gather.sbatch") >/dev/null 2>"$T/gather.txt"
rc=$?
check "gather.sbatch: a study named -s.yaml is gathered (exit $rc): $(cat "$T/gather.txt")" \
    eval '[ "$rc" -eq 0 ] && [ -s "$T/w/o/st/summary.csv" ]'
finish
