#!/bin/sh
# poisson_domain: torus (default) and square give different sets and images, the sidecar says
# which, a bad value is an error at its line:col, and compare variants take the key.
. tests/lib.sh
job() { # job NAME DOMAIN-LINE
    printf 'name: %s\nscene: checker\nwidth: 12\nsampler: poisson\nthreshold: 20\nmax_depth: 4\nformat: pfm\n%b' "$1" "$2" >"$T/$1.yaml"
}
job torus ''
job square 'poisson_domain: square\n'
job torus2 'poisson_domain: torus\n'
for n in torus square torus2; do "$WORKER" "$T/$n.yaml" --out "$T/out" --quiet >/dev/null 2>&1; done
check "default is torus: same image as poisson_domain: torus" cmp -s "$T/out/torus/torus.pfm" "$T/out/torus2/torus2.pfm"
check "square renders another image" sh -c "! cmp -s '$T/out/torus/torus.pfm' '$T/out/square/square.pfm'"
check "sidecar records the domain" grep -q '"poisson_domain": "square"' "$T/out/square/square.json"
check "sidecar records the default" grep -q '"poisson_domain": "torus"' "$T/out/torus/torus.json"
printf 'scene: checker\nwidth: 8\nsampler: poisson\npoisson_domain: disk\n' >"$T/bad.yaml"
"$WORKER" "$T/bad.yaml" --out "$T/out" >/dev/null 2>"$T/err"; rc=$?
check "bad domain exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "bad domain named at its line:col" grep -q 'bad.yaml:4:17: poisson_domain: must be torus or square, got "disk"' "$T/err"
cat >"$T/cmp.yaml" <<'YAML'
name: domains
scenes: [checker]
width: 8
max_depth: 3
seeds: [1]
sweep: { threshold: [20] }
variants:
  - { label: torus, sampler: poisson }
  - { label: square, sampler: poisson, poisson_domain: square }
YAML
"$WORKER" "$T/cmp.yaml" --out "$T/cout" --quiet >/dev/null 2>"$T/cerr"; rc=$?
check "a compare job takes poisson_domain in its variants (exit $rc)" [ "$rc" -eq 0 ]
check "the square variant's sidecar says square" sh -c "grep -l '\"poisson_domain\": \"square\"' '$T'/cout/domains/*/*square*.json '$T'/cout/domains/*square*.json 2>/dev/null | grep -q ."
finish
