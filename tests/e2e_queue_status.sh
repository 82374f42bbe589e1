#!/bin/sh
# End to end: `worker status DIR [--json]` on a queue with waiting, running, done and failed jobs,
# and `worker requeue DIR NAME... | --failed`.
. tests/lib.sh
root=$(pwd)
tiny() { # tiny FILE [yaml lines...]
    f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; for l in "$@"; do echo "$l"; done; } >"$f"
}
Q=$T/q; mkdir -p "$Q"

# an empty queue
"$WORKER" status "$Q" >"$T/s0.txt"; rc=$?
check "empty: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "empty: says 0 of each" grep -q "0 waiting, 0 running, 0 done, 0 failed" "$T/s0.txt"
"$WORKER" status "$T/nowhere" 2>"$T/s0.err"; rc=$?
check "no such queue: exit 2 (got $rc)" eval '[ "$rc" -eq 2 ] && grep -q "nowhere" "$T/s0.err"'
"$WORKER" status 2>/dev/null; rc=$?
check "no DIR: exit 2 (got $rc)" [ "$rc" -eq 2 ]

# one done, one failed
tiny "$Q/ok.yaml"; tiny "$Q/bad.yaml" "seed: -3"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/w1.log"
check "setup: ok done, bad failed" eval '[ -f "$Q/done/ok.yaml" ] && [ -f "$Q/failed/bad.yaml" ]'

# one running: a slow job under a worker whose lease is renewed twice a second
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 200"; echo "height: 200"; echo "threshold: 2"
  echo "light_threshold: 50"; echo "processes: 1"; } >"$Q/slow.yaml"
"$WORKER" --queue "$Q" --lease-timeout 2 --quiet 2>"$T/w2.log" & wpid=$!
for _ in $(seq 1 500); do
    [ -f "$Q/running/slow.yaml.lease" ] && ! grep -q "^progress  *0 " "$Q/running/slow.yaml.lease" && break
    sleep 0.02
done
check "running: the lease carries progress" grep -Eq "^progress +[1-9][0-9]* +200 " "$Q/running/slow.yaml.lease"
# two waiting, queued while it renders: the later one first, by priority
tiny "$Q/a.yaml"; tiny "$Q/b.yaml" "priority: 5"
touch -d '2020-01-01 00:00:00Z' "$Q/a.yaml"
"$WORKER" status "$Q" >"$T/s1.txt"; rc=$?
"$WORKER" status "$Q" --json >"$T/s1.json"; rcj=$?
kill -TERM "$wpid"; wait "$wpid"
cat "$T/s1.txt"
check "status: exit 0 (got $rc, $rcj)" eval '[ "$rc" -eq 0 ] && [ "$rcj" -eq 0 ]'
check "status: counts" grep -q "2 waiting, 1 running, 1 done, 1 failed" "$T/s1.txt"
check "status: a live worker's job is not said gone" eval 'grep -q "slow.yaml  host" "$T/s1.txt" && ! grep -q "gone" "$T/s1.txt"'
check "status: waiting in claim order, priority first" \
    sh -c "grep -A2 '^waiting' '$T/s1.txt' | sed -n 2p | grep -q '1. b.yaml  priority 5' &&
           grep -A2 '^waiting' '$T/s1.txt' | sed -n 3p | grep -q '2. a.yaml  priority 0  queued 2020-01-01T00:00:00Z'"
check "status: running with host, pid, attempt, rows, elapsed and ETA" \
    grep -Eq "^  slow.yaml  host $(hostname)  pid $wpid  attempt 1  [0-9]+% \([0-9]+/200 rows\)  elapsed [0-9]+ s  ETA [0-9]+ s$" "$T/s1.txt"
check "status: done with finish time, wall, cpu and samples" \
    grep -Eq "^  ok.yaml  finished [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}Z  wall [0-9.]+ s  cpu [0-9.]+ s  samples 1024$" "$T/s1.txt"
check "status: failed with its reason's first line" grep -Eq "^  bad.yaml  .*bad.yaml:[0-9]+:[0-9]+: seed" "$T/s1.txt"
if command -v python3 >/dev/null 2>&1; then
    check "json: what the text says" python3 - "$T/s1.json" "$wpid" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
w, r, d, f = s["waiting"], s["running"], s["done"], s["failed"]
assert [x["file"] for x in w] == ["b.yaml", "a.yaml"] and w[0]["priority"] == 5, w
assert len(r) == 1 and r[0]["file"] == "slow.yaml" and r[0]["pid"] == int(sys.argv[2]), r
assert r[0]["attempt"] == 1 and r[0]["rows"] == 200 and 0 < r[0]["percent"] <= 100, r
assert r[0]["elapsed_s"] >= 0 and r[0]["eta_s"] >= 0, r
assert len(d) == 1 and d[0]["file"] == "ok.yaml" and d[0]["samples"] == 1024 and d[0]["wall_s"] > 0, d
assert d[0]["finished"].endswith("Z"), d
assert len(f) == 1 and f[0]["file"] == "bad.yaml" and "seed" in f[0]["reason"], f
PY
else
    check "json: has the four lists" grep -q '"waiting".*"running".*"done".*"failed"' "$T/s1.json"
fi

# requeue: a failed job by name (its log goes), a done one; refused over a waiting one
"$WORKER" requeue "$Q" bad 2>"$T/r1.err"; rc=$?
check "requeue bad: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "requeue bad: back in the queue" eval '[ -f "$Q/bad.yaml" ] && [ ! -e "$Q/failed/bad.yaml" ]'
check "requeue bad: its log gone" [ ! -e "$Q/failed/bad.log" ]
tiny "$Q/dup.yaml"; mkdir -p "$Q/failed"; tiny "$Q/failed/dup.yaml"
"$WORKER" requeue "$Q" dup.yaml 2>"$T/r2.err"; rc=$?
check "requeue over a waiting job: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "requeue over a waiting job: both kept" eval '[ -f "$Q/dup.yaml" ] && [ -f "$Q/failed/dup.yaml" ]'
check "requeue over a waiting job: says so" grep -q "waits in the queue already" "$T/r2.err"
"$WORKER" requeue "$Q" nosuch 2>"$T/r3.err"; rc=$?
check "requeue unknown: exit 2 (got $rc)" eval '[ "$rc" -eq 2 ] && grep -q "nosuch.yaml: not in" "$T/r3.err"'
"$WORKER" requeue "$Q" ok.yaml 2>/dev/null; rc=$?
check "requeue a done job: exit 0, back in the queue (got $rc)" eval '[ "$rc" -eq 0 ] && [ -f "$Q/ok.yaml" ]'
rm "$Q/dup.yaml"
tiny "$Q/failed/c.yaml"
"$WORKER" requeue "$Q" --failed 2>"$T/r4.err"; rc=$?
check "requeue --failed: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "requeue --failed: failed/ holds no job" [ -z "$(ls "$Q/failed" | grep 'yaml$')" ]
check "requeue --failed: both back" eval '[ -f "$Q/c.yaml" ] && [ -f "$Q/dup.yaml" ]'
"$WORKER" requeue "$Q" 2>/dev/null; rc=$?
check "requeue without names: exit 2 (got $rc)" [ "$rc" -eq 2 ]
# a running job whose worker (on this host) is gone: said so, with no ETA
Q3=$T/q3; mkdir -p "$Q3/running"
tiny "$Q3/running/orphan.yaml"
sh -c 'exit 0' & dead=$!; wait "$dead" # a pid no process holds now
lease_text "$dead" >"$Q3/running/orphan.yaml.lease"
"$WORKER" status "$Q3" >"$T/s3.txt"; "$WORKER" status "$Q3" --json >"$T/s3.json"
check "a dead worker's job: status says it is gone ($(grep orphan "$T/s3.txt"))" \
    grep -q "orphan.yaml .*ETA --  (its worker is gone: the next worker to scan takes it back)" "$T/s3.txt"
check "a dead worker's job: worker_gone in the JSON" \
    python3 -c "import json; r = json.load(open('$T/s3.json'))['running']; assert r[0]['worker_gone'] is True, r"
# a failed job named by its name: (its log's name), not its file's stem: the log's job line finds it
Q2=$T/q2; mkdir -p "$Q2"
tiny "$Q2/sigfile.yaml" "name: signame" "reference: $root/scenes/textures/planet.png"
"$WORKER" --queue "$Q2" --once --quiet 2>/dev/null
check "setup: sigfile failed, its log named signame" eval '[ -f "$Q2/failed/sigfile.yaml" ] && [ -f "$Q2/failed/signame.log" ]'
"$WORKER" requeue "$Q2" signame 2>"$T/r5.err"; rc=$?
check "requeue by the job's name: exit 0, the file back (got $rc: $(cat "$T/r5.err"))" \
    eval '[ "$rc" -eq 0 ] && [ -f "$Q2/sigfile.yaml" ] && [ ! -e "$Q2/failed/signame.log" ]'
# status on a folder that is no queue (an output folder of --out): it says so, exit 2 (issue 36)
O=$T/outdir; tiny "$T/plainjob.yaml"
"$WORKER" "$T/plainjob.yaml" --out "$O" --quiet 2>/dev/null
"$WORKER" status "$O" >"$T/nq.txt" 2>&1; rc=$?
check "status on an output folder: exit 2 (got $rc), it says it is no queue: $(cat "$T/nq.txt")" \
    eval '[ "$rc" -eq 2 ] && [ "$(grep -c "not a queue" "$T/nq.txt")" -eq 1 ] && [ "$(grep -c . "$T/nq.txt")" -eq 1 ]'
mkdir -p "$T/fresh"; tiny "$T/fresh/a.yaml"
"$WORKER" status "$T/fresh" >/dev/null 2>&1; rc=$?
check "status on a folder of waiting jobs no worker has seen yet: a queue (exit $rc)" [ "$rc" -eq 0 ]
# a job put in a folder of the queue: the --once worker that finds nothing to do names it
Q5=$T/q5; mkdir -p "$Q5/jobs"; tiny "$Q5/jobs/deep.yaml"
"$WORKER" --queue "$Q5" --once 2>"$T/deep.txt"
check "a job in a folder of the queue: the worker says where a job goes: $(cat "$T/deep.txt")" \
    grep -q "no job waiting, nothing to do; $Q5/jobs/deep.yaml is in a folder of the queue, where no worker looks: a job goes in $Q5/ itself" "$T/deep.txt"
finish
