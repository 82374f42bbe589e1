#!/bin/sh
# failure_modes: calibrate the verdict's fireflies test (docs/compare.md, "Failure modes"). Runs N
# A/A studies of light-tailed variants (two labels of sampler: random, light_sampler: random on the
# near-field rect light, integrator nee, 32x32, 8 seeds of their own, thresholds 25 and 12.5) and N
# furnace studies (tests/data/furnace-fireflies.yaml: the mixture against nee, 24x24, 8 seeds of
# their own, thresholds 25 and 12.5). Prints how many A/A studies flagged heavy_tailed (false
# alarms; and structured), and how many furnace studies flagged the mixture heavy_tailed (hits), the mixture biased,
# and nee heavy_tailed or biased.
#   sh bench/failure_modes.sh [N]     (default 40; takes minutes; KEEP=DIR keeps each summary.csv,
#   ONLY=aa runs the A/A studies alone)
set -eu
N=${1:-40}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORKER=${WORKER:-$ROOT/bin/worker}
T=$(mktemp -d "${TMPDIR:-/tmp}/failure_modes.XXXXXX")
trap 'rm -rf "$T"' EXIT INT TERM

study() { # name kind first-seed
    s=$3
    {
        echo "name: $1"
        echo "processes: 1"
        echo "seeds: [$s, $((s + 1)), $((s + 2)), $((s + 3)), $((s + 4)), $((s + 5)), $((s + 6)), $((s + 7))]"
        echo "sweep: { threshold: [25, 12.5] }"
        echo "variants:"
        if [ "$2" = aa ]; then
            echo "  - { label: a, sampler: random, light_sampler: random }"
            echo "  - { label: b, sampler: random, light_sampler: random }"
            echo "scenes: [$ROOT/tests/data/near-light.yaml]"
            echo "width: 32"
            echo "integrator: nee"
            echo "light_threshold: 10"
            echo "reference: { sampler: jitter, light_sampler: jitter, threshold: 2, light_threshold: 2 }"
        else
            echo "  - { label: mixture, integrator: mixture }"
            echo "  - { label: nee, integrator: nee }"
            echo "scenes: [$ROOT/tests/data/furnace-fireflies.yaml]"
            echo "width: 24"
            echo "reference: { sampler: jitter, threshold: 3, integrator: nee }"
        fi
    } >"$T/$1.yaml"
    "$WORKER" "$T/$1.yaml" --out "$T/out" --quiet 2>/dev/null || { echo "$1: the study failed" >&2; exit 1; }
    python3 - "$T/out/$1/verdict.json" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))["studies"][0]["scenes"][0]["failures"]
print(" ".join(sorted({x["variant"] + ":" + x["kind"] for x in f})) or "none")
PY
    if [ -n "${KEEP:-}" ]; then cp "$T/out/$1/summary.csv" "$KEEP/$1.csv"; fi
    rm -rf "$T/out/$1"
}

aa_heavy=0 aa_structured=0 hit=0 mix_biased=0 nee_flag=0 i=0
start=$(date +%s)
while [ "$i" -lt "$N" ]; do
    r=$(study "aa$i" aa $((1 + 8 * i)))
    case $r in *:heavy_tailed*) aa_heavy=$((aa_heavy + 1)) ;; esac
    case "$r " in *:structured\ *) aa_structured=$((aa_structured + 1)) ;; esac
    r2=skipped
    [ "${ONLY:-}" = aa ] || r2=$(study "fu$i" fu $((1 + 8 * i)))
    case $r2 in *mixture:heavy_tailed*) hit=$((hit + 1)) ;; esac
    case $r2 in *mixture:biased*) mix_biased=$((mix_biased + 1)) ;; esac
    case $r2 in *nee:heavy_tailed* | *nee:biased*) nee_flag=$((nee_flag + 1)) ;; esac
    i=$((i + 1))
    echo "study $i/$N: A/A [$r]; furnace [$r2]" >&2
done
echo "$(($(date +%s) - start)) s wall, load average now $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
echo "A/A (random, near-field light): heavy_tailed in $aa_heavy of $N, structured in $aa_structured of $N"
echo "furnace: mixture heavy_tailed in $hit of $N, mixture biased in $mix_biased, nee heavy_tailed or biased in $nee_flag"
