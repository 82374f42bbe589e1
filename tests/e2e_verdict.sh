#!/bin/sh
# The verdict on a tiny real study: a variant that leaves out indirect light (max_depth 2 against a
# max_depth 6 reference) is biased and flagged `biased` with its percentage, the full one is not;
# the reference's own relMSE, measured from its halves, is in verdict.json.
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
check "bias study: the report's stability line says it" grep -q 'biased: mean radiance -[0-9.]*% off the reference' "$T/out/bias/report.html"
finish
