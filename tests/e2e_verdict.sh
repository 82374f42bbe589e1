#!/bin/sh
# The verdict on a tiny real study: a variant that leaves out indirect light (max_depth 2 against a
# max_depth 6 reference) is biased and flagged `biased` with its percentage, the full one is not;
# the reference's own relMSE, measured from its halves, is in verdict.json. `worker verdict DIR`
# judges the folder again from its summary.csv: the same verdict, for a study and a suite, and
# the checks it skipped named when images or sidecars are gone.
# And the seed's square-domain Poisson light sets on a near-field light are flagged biased, the
# toroidal ones and random not.
. tests/lib.sh
root=$(pwd)
ln -s "$root/scenes" "$T/scenes"
cat >"$T/bias.yaml" <<'YAML'
name: bias
scenes: [cornell]
width: 8
max_depth: 6
reference: { sampler: jitter, threshold: 4 }
seeds: [1, 2, 3, 4, 5, 6]
sweep: { threshold: [25, 20] }
variants:
  - { label: full, sampler: jitter }
  - { label: depth2, sampler: jitter, max_depth: 2 }
YAML
"$WORKER" --quiet --out "$T/out" "$T/bias.yaml" 2>"$T/bias.err"; rc=$?
check "bias study: exit 0 (got $rc: $(tail -n 1 "$T/bias.err"))" [ "$rc" -eq 0 ]
check "bias study: depth2 is biased, full is not; reference_relmse measured" python3 - "$T/out/bias/verdict.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
biased = {f['variant']: f for f in x['failures'] if f['kind'] == 'biased'}
assert list(biased) == ['depth2'], x['failures']
assert -40 < biased['depth2']['value'] < -5 and biased['depth2']['standard_errors'] < -4, biased
assert 'off the reference' in biased['depth2']['text'], biased
assert 0 < x['reference_relmse'] < 0.1, x['reference_relmse']
PY
check "bias study: a reproducibility block in verdict.json and the report" python3 - "$T/out/bias/verdict.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))['reproducibility']
assert 'bias.yaml' in r['command'] and r['version'] and len(r['program_hash']) == 16, r
assert r['compiler'] and r['cores'] >= 1 and len(r['load_average']) == 3, r
PY
check "... and in the report" grep -q 'Command <code>.*bias.yaml</code>.*load average' "$T/out/bias/report.html"
check "bias study: the report's stability line says it" grep -q 'biased: mean radiance -[0-9.]*% off the reference' "$T/out/bias/report.html"

# worker verdict: the same verdict from the folder (figures to summary.csv's 6 digits)
same_verdict() { # same_verdict A.json B.json: statuses, ranks and failure kinds agree
    python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
def shape(d):
    return [(s['study'], x['scene'], [(k, x[k]['status'], [(e['variant'], e['rank']) for e in x[k]['ranking']])
                                      for k in ('equal_samples', 'equal_cpu_time', 'slopes')],
             sorted((f['variant'], f['kind']) for f in x['failures']), round(x['reference_relmse'] or 0, 8))
            for s in d['studies'] for x in s['scenes']]
assert shape(a) == shape(b), (shape(a), shape(b))
PY
}
"$WORKER" verdict "$T/out/bias" --json >"$T/again.json" 2>"$T/again.err"; rc=$?
check "worker verdict --json: exit 0 (got $rc: $(cat "$T/again.err"))" [ "$rc" -eq 0 ]
check "worker verdict --json: the verdict the run wrote" same_verdict "$T/out/bias/verdict.json" "$T/again.json"
# a row's point is told by its settings columns, not by its image's name: images renamed (and their
# files with them) to names that say nothing of their point, the same verdict. cost.csv names a
# point by its image's name (docs/compare.md), so both copies judge without it, from the images'
# own CPU times: the same figures on both sides, where the run's timed blocks would differ
cp -r "$T/out" "$T/plain"; rm "$T/plain/bias/cost.csv"
cp -r "$T/plain" "$T/renamed"
python3 - "$T/renamed/bias" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.reader(open(d + '/summary.csv', newline='')))
col = rows[0].index('image')
for i, r in enumerate(rows[1:]):
    old, new = r[col][:-4], 'img%d' % (len(rows) - i)
    for ext in ('.png', '.exr', '.json'):
        os.rename(d + '/' + old + ext, d + '/' + new + ext)
    r[col] = new + '.png'
csv.writer(open(d + '/summary.csv', 'w', newline=''), lineterminator='\n').writerows(rows)
PY
"$WORKER" verdict "$T/renamed/bias" --json >"$T/renamed.json" 2>"$T/renamed.err"; rc=$?
check "images renamed: exit 0 (got $rc: $(cat "$T/renamed.err"))" [ "$rc" -eq 0 ]
"$WORKER" verdict "$T/plain/bias" --json >"$T/plain.json" 2>/dev/null
check "images renamed: the verdict of the same folder unrenamed" same_verdict "$T/plain.json" "$T/renamed.json"
"$WORKER" verdict "$T/out/bias" >"$T/again.txt" 2>"$T/again.err"; rc=$?
check "worker verdict: sentences, failures and the winner (exit $rc)" \
    grep -q '^bias: cornell: failure: depth2: biased: ' "$T/again.txt"
check "worker verdict: the summary line" grep -q '^bias: at equal CPU time: bias: ' "$T/again.txt"
check "worker verdict: nothing written" [ ! -e "$T/out/bias/verdict.json.tmp" ]
"$WORKER" verdict "$T/out/bias" --quiet >"$T/quiet.txt" 2>"$T/quiet.err"; rc=$?
check "worker verdict --quiet (a common option) is taken: the same sentences (exit $rc)" \
    sh -c "[ $rc -eq 0 ] && cmp -s '$T/quiet.txt' '$T/again.txt'"
# without the float images and sidecars: the checks on them are skipped, and said so
cp -r "$T/out" "$T/bare"
rm "$T"/bare/bias/*.exr "$T"/bare/bias/*-s[0-9].json
"$WORKER" verdict "$T/bare/bias" --json >"$T/bare.json" 2>"$T/bare.err"; rc=$?
check "images gone: exit 0 (got $rc: $(cat "$T/bare.err"))" [ "$rc" -eq 0 ]
check "images gone: the skipped checks are named" python3 - "$T/bare.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
w = ' '.join(x['warnings'])
assert 'skipped: the share of the error that repeats in every seed' in w and 'bias check' in w, w
assert 'skipped: non-finite samples' in w, w
assert not any(f['kind'] in ('biased', 'structured_error') for f in x['failures']), x['failures']
assert x['equal_samples']['ranking'] and x['slopes']['status'], x
PY
# today's sidecars name the count nonfinite_samples: worker verdict reads it (it read only the
# name before issue 26, nonfinite_dropped, and so never saw one)
cp -r "$T/out" "$T/nf"
for f in "$T"/nf/bias/*depth2*-s1.json; do
    sed -i 's/"nonfinite_samples": [0-9]*/"nonfinite_samples": 500/' "$f"
done
"$WORKER" verdict "$T/nf/bias" --json >"$T/nf.json" 2>"$T/nf.err"; rc=$?
check "non-finite samples in a sidecar: the failure non_finite (exit $rc)" python3 - "$T/nf.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
assert any(f['kind'] == 'non_finite' for f in x['failures']), x['failures']
PY
# a row whose relmse is no error (nan) is left out of the ranking, and the verdict says so
cp -r "$T/out" "$T/nanrow"
python3 - "$T/nanrow/bias/summary.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline='')))
col = rows[0].index('relmse')
rows[1][col] = 'nan'
csv.writer(open(sys.argv[1], 'w', newline=''), lineterminator='\n').writerows(rows)
PY
"$WORKER" verdict "$T/nanrow/bias" --json >"$T/nanrow.json" 2>"$T/nanrow.err"; rc=$?
check "a nan relmse: exit 0 and said as left out (exit $rc)" python3 - "$T/nanrow.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
assert any('left out: 1 image whose relmse in summary.csv is not an error' in w for w in x['warnings']), x['warnings']
PY
# a suite: its summary.csv's study column finds each study's folder
mkdir -p "$T/s"
ln -s "$root/scenes" "$T/s/scenes"
sed 's/^name: bias$/name: one/; s/width: 8/width: 4/' "$T/bias.yaml" >"$T/s/one.yaml"
sed 's/^name: bias$/name: two/; s/width: 8/width: 4/; s/seeds: .*/seeds: [1, 2, 3, 4]/' "$T/bias.yaml" >"$T/s/two.yaml"
printf 'name: suite\nstudies: [one.yaml, two.yaml]\n' >"$T/s/suite.yaml"
"$WORKER" --quiet --out "$T/out" "$T/s/suite.yaml" 2>"$T/suite.err"; rc=$?
check "suite: exit 0 (got $rc: $(tail -n 1 "$T/suite.err"))" [ "$rc" -eq 0 ]
"$WORKER" verdict "$T/out/suite" --json >"$T/suite.json" 2>"$T/suite.err"; rc=$?
check "worker verdict on a suite: exit 0 (got $rc: $(cat "$T/suite.err"))" [ "$rc" -eq 0 ]
check "worker verdict on a suite: the suite's verdict" same_verdict "$T/out/suite/verdict.json" "$T/suite.json"
# bad usage and a folder that is not a compare output
"$WORKER" verdict 2>"$T/e1"; rc=$?
check "no folder: exit 2 (got $rc)" eval '[ "$rc" -eq 2 ] && grep -q "usage: worker verdict DIR" "$T/e1"'
"$WORKER" verdict "$T/s" 2>"$T/e2"; rc=$?
check "no summary.csv: exit 2 (got $rc), one line" eval '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/e2")" -eq 1 ] &&
    grep -q "summary.csv" "$T/e2"'
# a malformed summary.csv: file:line and the reason, exit 2; rows ended by CR alone still parse
mkdir -p "$T/m"
head -n 1 "$T/out/bias/summary.csv" >"$T/m/summary.csv"
printf 'cornell,full,25\n' >>"$T/m/summary.csv"
"$WORKER" verdict "$T/m" 2>"$T/e3"; rc=$?
fields=$(head -n 1 "$T/m/summary.csv" | awk -F, '{ print NF }')
check "a short row: exit 2 (got $rc) naming file:line: $(cat "$T/e3")" eval '[ "$rc" -eq 2 ] &&
    grep -q "m/summary.csv:2:1: 3 fields, the header has $fields" "$T/e3"'
tr '\n' '\r' <"$T/out/bias/summary.csv" >"$T/m/summary.csv"
"$WORKER" verdict "$T/m" >/dev/null 2>"$T/e4"; rc=$?
check "CR line ends: exit 0 (got $rc: $(tail -n 1 "$T/e4"))" [ "$rc" -eq 0 ]
# The seed's square-domain Poisson sets as light sampler on a near-field light are biased (issue 26):
# the verdict of a small study flags them `biased`; the toroidal default and random are not.
cp tests/data/near-light.yaml "$T/near-light.yaml"
cat >"$T/poisson.yaml" <<'YAML'
name: poissonbias
scenes: [near-light.yaml]
width: 24
max_depth: 2
integrator: nee
sampler: jitter
threshold: 25
reference: { sampler: jitter, threshold: 5, light_sampler: jitter, light_threshold: 5 }
seeds: [1, 2, 3, 4, 5, 6, 7, 8]
sweep: { light_threshold: [20] }
variants:
  - { label: torus, light_sampler: poisson }
  - { label: square, light_sampler: poisson, poisson_domain: square }
  - { label: random, light_sampler: random }
YAML
"$WORKER" --quiet --out "$T/out" "$T/poisson.yaml" 2>"$T/poisson.err"; rc=$?
check "poisson bias study: exit 0 (got $rc: $(tail -n 1 "$T/poisson.err"))" [ "$rc" -eq 0 ]
check "poisson bias study: square is flagged biased, torus and random are not" python3 - "$T/out/poissonbias/verdict.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
biased = {f['variant']: f for f in x['failures'] if f['kind'] == 'biased'}
assert list(biased) == ['square'], x['failures']
assert biased['square']['value'] < -1 and biased['square']['standard_errors'] < -4, biased
PY
finish
