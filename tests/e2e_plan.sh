#!/bin/sh
# e2e_plan: `worker plan JOB` lists the entries a queue would spread a study into (each reference's
# two halves, each image; a render over the entry target cut into row parts, references first), each
# with its estimated CPU, and the wall time on N workers; writes nothing; bad input is one line
# (issue 40).
. "$(dirname "$0")/lib.sh"
root=$(pwd)
mkdir -p "$T/w"
cd "$T/w" || exit 1
cat >cmp.yaml <<EOT
name: cmp
scenes: [$root/scenes/checker.yaml]
width: 24
height: 24
reference: { sampler: jitter, threshold: 5 }
seeds: [1, 2]
variants:
  - { sampler: uniform, threshold: 10 }
  - { sampler: jitter, threshold: 5 }
EOT
sed 's/^name: cmp/name: cmp\nentry_cpu_s: 0.01/' cmp.yaml >key.yaml
printf 'name: bad\nscenes: [%s/scenes/checker.yaml]\nentry_cpu_s: 0\nvariants: [{ sampler: uniform }]\n' "$root" >bad.yaml
ls -lAR >"$T/before"
"$WORKER" plan cmp.yaml --json >"$T/whole.json" 2>"$T/err"; rc=$?
check "exit 0 (got $rc: $(cat "$T/err"))" [ "$rc" -eq 0 ]
py() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); e=d['entries']; $1" "$2"; }
check "at the default target (60 CPU s) nothing is cut: two halves and four images" \
    [ "$(py 'print(len(e), sum(x["parts"] for x in e), [x["kind"] for x in e][:2])' "$T/whole.json")" = "6 6 ['reference', 'reference']" ]
"$WORKER" plan cmp.yaml --json --entry-cpu-s 0.01 --workers 3 --cores 2 >"$T/cut.json" 2>"$T/err"; rc=$?
check "cut: exit 0 ($(cat "$T/err"))" [ "$rc" -eq 0 ]
check "cut: more entries, renders over the target in row parts, references first" \
    py 'n=len(e); r=[x["kind"]=="reference" for x in e]; assert n>6 and any(x["parts"]>1 for x in e); assert r==sorted(r,reverse=True); assert all(x["parts"]<=24 for x in e)' "$T/cut.json"
check "cut: each part's CPU is its render's over the parts; the total is the uncut plan's" \
    py 'import json; w=json.load(open("'"$T/whole.json"'")); assert abs(sum(x["est_cpu_s"] for x in e)-d["total_cpu_s"])<1e-6*d["total_cpu_s"]; assert d["total_cpu_s"]>0' "$T/cut.json"
check "cut: within images, the longest first" \
    py 'c=[x["est_cpu_s"] for x in e if x["kind"]=="image"]; assert c==sorted(c,reverse=True)' "$T/cut.json"
"$WORKER" plan cmp.yaml --json --entry-cpu-s 0.01 --workers 1 --cores 2 >"$T/one.json"
check "makespan: one worker takes longer than three" \
    python3 -c "import json,sys; a=json.load(open(sys.argv[1]))['makespan_s']; b=json.load(open(sys.argv[2]))['makespan_s']; assert a>b>0, (a,b)" "$T/one.json" "$T/cut.json"
"$WORKER" plan key.yaml --json >"$T/key.json" 2>"$T/err"
check "the job key entry_cpu_s: cuts as the option does ($(cat "$T/err"))" py 'assert any(x["parts"]>1 for x in e)' "$T/key.json"
"$WORKER" plan cmp.yaml --workers 2 >"$T/text" 2>"$T/err"
check "text: entries and the wall time" eval 'grep -q "^cmp: plan: nothing rendered, nothing written$" "$T/text" && grep -q "^  wall      about .* on 2 workers of" "$T/text"'
ls -lAR >"$T/after"
check "writes nothing" cmp -s "$T/before" "$T/after"
"$WORKER" plan cmp.yaml --workers 0 >"$T/out" 2>"$T/err"; rc=$?
check "bad --workers: exit 2, one line" eval '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && [ ! -s "$T/out" ]'
"$WORKER" plan bad.yaml >"$T/out" 2>"$T/err"; rc=$?
check "bad entry_cpu_s: file:line:col and key ($(cat "$T/err"))" eval '[ "$rc" -eq 2 ] && grep -q "^bad.yaml:3:14: entry_cpu_s: must be in" "$T/err" && [ ! -s "$T/out" ]'
"$WORKER" plan --help >"$T/help"
check "--help" grep -q "^usage: worker plan JOB.yaml" "$T/help"
# the seed's experiment on 32 two-core workers: no entry above 1/16 of the whole, at most 4 minutes
"$WORKER" plan "$root/jobs/seed-experiment.yaml" --workers 32 --cores 2 --json >"$T/seed.json" 2>"$T/err"
check "seed experiment on 32 x 2 cores: entries at most 1/16 of the CPU, makespan at most 240 s ($(cat "$T/err"))" \
    py 't=d["total_cpu_s"]; assert max(x["est_cpu_s"] for x in e)<=t/16 and d["makespan_s"]<=240, (t, d["makespan_s"])' "$T/seed.json"
finish
