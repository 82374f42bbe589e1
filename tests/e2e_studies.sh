#!/bin/sh
# A tiny version of each shipped study (jobs/studies/*.yaml: 12 pixels wide, two thresholds, a
# cheap reference, the study's own variants, scenes and settings) runs, and its verdict.json has
# the structure scripts read: per scene the rankings at equal samples and equal CPU time and by
# slope, with ranks by the tie rule, the failure modes, the warnings and the sentences.
. tests/lib.sh
root=$(pwd)
n=0
for f in "$root"/jobs/studies/*.yaml; do
    [ -f "$f" ] || continue
    n=$((n + 1))
    study=$(basename "$f" .yaml)
    mkdir -p "$T/jobs/studies"
    # shrink: size, sweep and reference; scene names and paths resolve as from the real file
    python3 - "$f" "$T/jobs/studies/$study.yaml" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
text = re.sub(r'(?m)^width: *\d+', 'width: 12', text)
text = re.sub(r'(?m)^height: *\d+', 'height: 12', text)
text = re.sub(r'(?m)^(sweep: *\{.*\})', lambda m: re.sub(r'\[[^\]]*\]', '[50, 25]', m.group(1)), text)
text = re.sub(r'(?m)^reference: *\{[^}]*\}', 'reference: { sampler: jitter, threshold: 20 }', text)
assert 'sweep: { threshold: [50, 25]' in text and 'width: 12' in text, 'study file shape changed: ' + sys.argv[1]
open(sys.argv[2], 'w').write(text)
PY
    check "$study: shrunk" [ -s "$T/jobs/studies/$study.yaml" ]
    # scene names resolve against the shipped scenes/ as from jobs/studies/
    [ -e "$T/scenes" ] || ln -s "$root/scenes" "$T/scenes"
    "$WORKER" --quiet --out "$T/out" "$T/jobs/studies/$study.yaml" 2>"$T/$study.err"; rc=$?
    check "$study: tiny run exits 0 (got $rc: $(tail -n 1 "$T/$study.err"))" [ "$rc" -eq 0 ]
    check "$study: the summary line names the winner" grep -q "; at equal CPU time: $study:" "$T/$study.err"
    check "$study: verdict.json's structure" python3 - "$T/out/$study/verdict.json" "$study" "$T/out/$study/summary.csv" <<'PY'
import csv, json, sys
d = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[3])))
variants = sorted(set(r['variant'] for r in rows))
scenes = list(dict.fromkeys(r['scene'] for r in rows))
assert d['job'] == sys.argv[2] and 'tie_rule' in d and len(d['studies']) == 1, d.keys()
s = d['studies'][0]
assert s['study'] == sys.argv[2] and [x['scene'] for x in s['scenes']] == scenes, s
for x in s['scenes']:
    for k, at, val in (('equal_samples', 'at_samples_per_pixel', 'relmse'), ('equal_cpu_time', 'at_cpu_s', 'relmse'),
                       ('slopes', None, 'slope')):
        r = x[k]
        assert r['status'] in ('clear', 'tie', 'inconclusive'), r
        assert at is None or r[at] > 0, r
        assert sorted(e['variant'] for e in r['ranking']) == variants, (k, r)
        ranks = [e['rank'] for e in r['ranking']]
        assert ranks == sorted(ranks) and ranks[0] == 1, (k, ranks)
        for e in r['ranking']:
            assert e.get('cannot_tell') or e['ci95_lo'] <= e[val] <= e['ci95_hi'], e
            assert isinstance(e['reached'], bool), e
        top = [e['variant'] for e in r['ranking'] if e['rank'] == 1]
        assert r['status'] != 'clear' or len(top) == 1, r
        assert r['status'] != 'inconclusive' or len(top) == len(variants), r
        assert r['winner'] == ('inconclusive' if r['status'] == 'inconclusive' else ' = '.join(top)), r
    for fl in x['failures']:
        assert fl['variant'] in variants and fl['kind'] in ('structured_error', 'stops_falling', 'non_finite',
                                                            'sampler_share', 'biased', 'heavy_tailed',
                                                            'structured') and fl['text'], fl
    assert all(isinstance(w, str) for w in x['warnings']) and x['sentences'], x
    # a threshold 20 reference has 25 samples, under 4x threshold 25's 16: the guard says so
    assert any('fewer than 4x' in w for w in x['warnings']), x['warnings']
PY
    check "$study: the report opens with the verdict" grep -q '<section id="verdict"><h2>Verdict</h2>' "$T/out/$study/report.html"
done
check "five studies shipped (found $n)" [ "$n" -eq 5 ]
finish
