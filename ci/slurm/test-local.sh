#!/usr/bin/env bash
# Bring up a one-node Slurm on localhost (munged, slurmctld, slurmd from Debian's slurm-wlm and
# munge, all state in one temporary folder), run the examples beside this script through it,
# check their results, and stop the daemons it started, by PID, also on failure.
#   WORKER=bin/worker bash ci/slurm/test-local.sh      (make test-slurm does this)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
WORKER=$(cd "$(dirname "${WORKER:-$root/bin/worker}")" && pwd)/$(basename "${WORKER:-worker}")
t0=$(date +%s.%N)
elapsed() { awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }
say() { echo "slurm: [$(elapsed) s] $*"; }
. "$root/tests/lib_study.sh"

for tool in munged slurmctld slurmd sbatch sinfo scancel; do
    command -v "$tool" >/dev/null || PATH=$PATH:/usr/sbin:/sbin
    command -v "$tool" >/dev/null || { echo "slurm: $tool missing: apt-get install slurm-wlm munge" >&2; exit 1; }
done
[ -x "$WORKER" ] || { echo "slurm: no worker binary at $WORKER (run make first)" >&2; exit 1; }

S=$(mktemp -d /tmp/worker-slurm.XXXXXX)
chmod 0755 "$S" # munged refuses a socket folder others may write to
daemons=() jobs=()
cleanup() {
    rc=$?
    set +e
    [ ${#jobs[@]} -gt 0 ] && scancel "${jobs[@]}" 2>/dev/null
    for ((i = ${#daemons[@]} - 1; i >= 0; i--)); do # slurmd, slurmctld, then munged
        pid=${daemons[i]}
        kill -TERM "$pid" 2>/dev/null || continue
        for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
    done
    if [ "$rc" -ne 0 ]; then
        for log in "$S"/*.log "$S"/*.stderr; do [ -f "$log" ] && { echo "--- $log"; tail -n 20 "$log"; }; done
    fi
    [ -n "${KEEP:-}" ] && echo "slurm: kept $S" || rm -rf "$S"
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Free TCP ports for slurmctld and slurmd, so that two runs on one machine do not collide.
free_port() {
    local p
    for _ in $(seq 1 50); do
        p=$((20000 + RANDOM % 20000))
        ss -Htln "sport = :$p" 2>/dev/null | grep -q . || { echo "$p"; return; }
    done
    echo "$p"
}
ctld_port=$(free_port) slurmd_port=$(free_port)
[ "$slurmd_port" != "$ctld_port" ] || slurmd_port=$((ctld_port + 1))

# munge: our own key and socket
mkdir -p "$S/munge" "$S/state" "$S/spool" "$S/out"
chmod 0700 "$S/munge"
dd if=/dev/urandom of="$S/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 0400 "$S/munge/munge.key"
munged -F --force --key-file="$S/munge/munge.key" --socket="$S/munge/socket" \
    --pid-file="$S/munge/munged.pid" --log-file="$S/munged.log" --seed-file="$S/munge/seed" \
    >>"$S/munged.stderr" 2>&1 &
daemons+=($!)
for _ in $(seq 1 100); do [ -S "$S/munge/socket" ] && break; sleep 0.05; done
[ -S "$S/munge/socket" ] || { echo "slurm: munged did not start" >&2; exit 1; }

cat >"$S/slurm.conf" <<EOF
ClusterName=workertest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$S/munge/socket
SlurmUser=root
SlurmdUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
MinJobAge=4
ReturnToService=2
MailProg=/bin/true
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/slurmctld.log
SlurmdLogFile=$S/slurmd.log
PlugStackConfig=$S/plugstack.conf
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
: >"$S/plugstack.conf"
export SLURM_CONF=$S/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >>"$S/slurmctld.stderr" 2>&1 &
daemons+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >>"$S/slurmd.stderr" 2>&1 &
daemons+=($!)
for _ in $(seq 1 300); do
    state=$(sinfo -h -n localhost -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.2
done
[ "$state" = idle ] || { echo "slurm: node not idle after 60 s (state '$state')" >&2; exit 1; }
say "munged, slurmctld and slurmd up (ports $ctld_port, $slurmd_port), node idle"

pass=0 fail=0
check() { # check "description" command...
    local d=$1; shift
    if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $d" >&2; fi
}
waited() { # waited WHAT CMD...: CMD (it submits with --wait) run in $S/out, where the task logs go;
    # the job id it prints into $out (cancelled on cleanup), its exit status into $rc
    local what=$1; shift
    set +e
    out=$(cd "$S/out" && "$@")
    rc=$?
    set -e
    out=${out%%;*}
    jobs+=("$out")
    say "$what $out finished (sbatch --wait exit $rc)"
}
tiny() { # tiny FILE [yaml lines]: a 16x16 render of a few milliseconds
    local f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"
      echo "threshold: 50"; echo "light_threshold: 50"; echo "processes: 1"
      for l in "$@"; do echo "$l"; done; } >"$f"
}

# 1. an array job of 4 tasks, each `worker --queue DIR --once`, drains a queue of 12 jobs
Q=$S/queue
mkdir -p "$Q"
for i in $(seq 1 12); do tiny "$Q/j$i.yaml"; done
waited "queue array job" env WORKER="$WORKER" QUEUE="$Q" sbatch --parsable --wait --array=0-3 --export=ALL \
    "$here/queue.sbatch"
check "queue: sbatch --wait exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "queue: 12 job files in done/" [ "$(ls "$Q"/done/*.yaml 2>/dev/null | wc -l)" -eq 12 ]
check "queue: 12 images" [ "$(ls "$Q"/done/j*/j*.png 2>/dev/null | wc -l)" -eq 12 ]
check "queue: none failed" [ -z "$(ls -A "$Q/failed" 2>/dev/null)" ]
check "queue: none left waiting" [ -z "$(ls "$Q"/*.yaml 2>/dev/null)" ]
check "queue: none left running" [ -z "$(ls -A "$Q/running" 2>/dev/null)" ]
check "queue: 4 task logs" [ "$(ls "$S"/out/worker-queue-*.out 2>/dev/null | wc -l)" -eq 4 ]
once=0
for i in $(seq 1 12); do
    [ "$(cat "$S"/out/worker-queue-*.out | grep -cE "(^| )j$i: 16x16")" -eq 1 ] && once=$((once + 1))
done
check "queue: each job rendered exactly once ($once of 12)" [ "$once" -eq 12 ]

# 2. one job split over a 4-task array (--part I/4), merged by a dependent job: same bytes as
#    a plain render
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 40"; echo "height: 30"; echo "threshold: 25"
  echo "light_threshold: 50"; } >"$S/split.yaml"
"$WORKER" --quiet --out "$S/plain" "$S/split.yaml" 2>/dev/null || true
waited "part array + dependent merge job" env WORKER="$WORKER" "$here/submit-parts.sh" "$S/split.yaml" "$S/parts" 4 --wait
check "parts: merge step exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "parts: the merge step ran after the parts" grep -q "split: merged 4 parts, 40x30" "$S/out/worker-merge-$out.out"
check "parts: 4 part files" [ "$(ls "$S"/parts/split/split.part-*-of-4 2>/dev/null | wc -l)" -eq 4 ]
check "parts: merged image == plain render" cmp -s "$S/plain/split/split.png" "$S/parts/split/split.png"
check "parts: sidecar records 4 parts" grep -q '"parts": 4' "$S/parts/split/split.json"
# 3. a study spread over a 3-task array (each --part I/3 of its images), gathered by a dependent
#    job: the one-process run's images and verdict; each image rendered once; a resubmission
#    renders nothing again (sidecars' job hash)
small_study study "$root" "1, 2, 3" "jitter random" >"$S/study.yaml"
"$WORKER" --quiet --out "$S/plain-study" "$S/study.yaml" 2>/dev/null || true
for round in 1 2; do
    waited "study round $round: render array + dependent gather job" \
        env WORKER="$WORKER" "$here/submit-study.sh" "$S/study.yaml" "$S/studies" 3 --wait
    check "study $round: gather exits 0 (got $rc)" [ "$rc" -eq 0 ]
    check "study $round: the gather ran after the renders" grep -q "^study: 24 images" "$S/out/worker-gather-$out.out"
    rendered=$(cat "$S"/out/worker-part-*.out | grep "^study: part " | sed 's/.*: part [0-9]*\/3: \([0-9]*\) image.*/\1/' | awk '{s += $1} END {print s + 0}')
    want=24; [ "$round" -eq 2 ] && want=0
    check "study $round: $want images rendered by the array in all (got $rendered)" [ "$rendered" -eq "$want" ]
    rm -f "$S"/out/worker-part-*.out
done
same=0
for f in "$S"/plain-study/study/*.png; do cmp -s "$f" "$S/studies/study/$(basename "$f")" && same=$((same + 1)); done
check "study: 24 images == the one-process run's ($same)" [ "$same" -eq 24 ]
check "study: summary, chart, report, verdict" eval '[ -s "$S/studies/study/summary.csv" ] && [ -s "$S/studies/study/chart.svg" ] && [ -s "$S/studies/study/report.html" ]'
ranks() { python3 -c 'import json,sys
for st in json.load(open(sys.argv[1]))["studies"]:
    for sc in st["scenes"]:
        print(sc["scene"], [(k, sc[k]["status"], [(x["variant"], x["rank"]) for x in sc[k]["ranking"]]) for k in ("equal_samples", "slopes")])' "$1"; }
check "study: the same verdict at equal samples and by slope" [ "$(ranks "$S/plain-study/study/verdict.json")" = "$(ranks "$S/studies/study/verdict.json")" ]
# 4. a study whose renders are cut into row parts (entry_cpu_s: 0.01), one array task per entry of
#    its plan (submit-entries.sh) and the dependent gather: the one-process run's bytes, each part
#    rendered once, each cut render merged once; a resubmission renders nothing. The job renders
#    with 2 processes, the tasks with --processes 1: a merged sidecar records the hash the gather
#    (also --processes 1) looks for
{ small_study cut "$root" "1, 2" "jitter random" | sed 's/^width: 10/width: 40/; s/^height: 8/height: 32/; s/^processes: 1/processes: 2/'
  echo "entry_cpu_s: 0.01"; } >"$S/cut.yaml"
"$WORKER" --quiet --out "$S/plain-cut" "$S/cut.yaml" 2>/dev/null || true
for round in 1 2; do
    waited "cut study round $round: entry array + dependent gather job" \
        env WORKER="$WORKER" "$here/submit-entries.sh" "$S/cut.yaml" "$S/cut" --wait
    check "cut $round: gather exits 0 (got $rc)" [ "$rc" -eq 0 ]
    n=$(wc -l <"$S/cut/.entries-cut.txt")
    parts=$(grep -c -- '-p[0-9]*-[0-9]*.yaml$' "$S/cut/.entries-cut.txt")
    check "cut $round: one array task per entry ($n), renders cut into parts ($parts)" \
        eval '[ "$(ls "$S"/out/worker-entry-*.out | wc -l)" -eq "$n" ] && [ "$parts" -ge 2 ]'
    check "cut $round: the gather ran after the entries, rendering nothing" \
        grep -q "^cut: 16 images .* 16 of them current from an earlier run" "$S/out/worker-gather-$out.out"
    rendered=$(cat "$S"/out/worker-entry-*.out | grep -c ': rendered' || true)
    merged=$(cat "$S"/out/worker-entry-*.out | grep -c 'merged into its image and sidecar' || true)
    cut=$(grep -c -- '-p0-[0-9]*.yaml$' "$S/cut/.entries-cut.txt")
    if [ "$round" -eq 1 ]; then
        check "cut 1: every entry rendered once ($rendered of $n), each cut render merged once ($merged of $cut)" \
            eval '[ "$rendered" -eq "$n" ] && [ "$merged" -eq "$cut" ]'
    else
        check "cut 2: a resubmission renders nothing ($rendered renders, $merged merges)" \
            eval '[ "$rendered" -eq 0 ] && [ "$merged" -eq 0 ]'
    fi
    rm -f "$S"/out/worker-entry-*.out
done
same=0
for f in "$S"/plain-cut/cut/*.png "$S"/plain-cut/cut/*.exr; do cmp -s "$f" "$S/cut/cut/$(basename "$f")" && same=$((same + 1)); done
check "cut: 32 images == the one-process run's ($same)" [ "$same" -eq 32 ]
check "cut: no part file left" [ -z "$(find "$S/cut" -name '*.part-*')" ]
say "done"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
