#!/bin/sh
# equal_time: calibrate the verdict at equal CPU time (docs/compare.md, "Equal CPU time"). Runs N
# A/A studies (six variants that differ only in label: their images are byte for byte the same)
# and N power studies (random against jitter, pixels and lights alike, light threshold 10), each
# on the near-field rect light at 32x32, integrator nee, 8 seeds of its own, thresholds 25 and 12.5,
# processes 1, with the cost design as shipped. Prints how many separated any two variants at equal
# CPU time (A/A: false separations) and how many ranked jitter alone first (power).
#   sh bench/equal_time.sh [N] [quiet|hog]     (default 40 hog; takes minutes)
# hog: a process burning one core for 0.5 s of every 1.5 s runs beside the whole calibration.
set -eu
N=${1:-40}
LOAD=${2:-hog}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORKER=${WORKER:-$ROOT/bin/worker}
T=$(mktemp -d "${TMPDIR:-/tmp}/equal_time.XXXXXX")
HOG=
cleanup() {
    if [ -n "$HOG" ]; then kill "$HOG" 2>/dev/null || true; fi
    rm -rf "$T"
}
trap cleanup EXIT INT TERM
if [ "$LOAD" = hog ]; then
    python3 -c '
import time
while True:
    t = time.process_time()
    while time.process_time() - t < 0.5:
        pass
    time.sleep(1.0)
' &
    HOG=$!
fi

study() { # name kind first-seed
    s=$3
    {
        echo "name: $1"
        echo "scenes: [$ROOT/tests/data/near-light.yaml]"
        echo "width: 32"
        echo "processes: 1"
        echo "integrator: nee"
        echo "light_threshold: 10"
        echo "reference: { sampler: jitter, light_sampler: jitter, threshold: 2, light_threshold: 2 }"
        echo "seeds: [$s, $((s + 1)), $((s + 2)), $((s + 3)), $((s + 4)), $((s + 5)), $((s + 6)), $((s + 7))]"
        echo "sweep: { threshold: [25, 12.5] }"
        echo "variants:"
        if [ "$2" = aa ]; then
            for l in a b c d e f; do echo "  - { label: $l, sampler: random, light_sampler: random }"; done
        else
            echo "  - { sampler: random, light_sampler: random }"
            echo "  - { sampler: jitter, light_sampler: jitter }"
        fi
    } >"$T/$1.yaml"
    "$WORKER" "$T/$1.yaml" --out "$T/out" --quiet 2>/dev/null || { echo "$1: the study failed" >&2; exit 1; }
    python3 - "$T/out/$1/verdict.json" "$2" <<'EOF'
import json, sys
v = json.load(open(sys.argv[1]))["studies"][0]["scenes"][0]["equal_cpu_time"]
if sys.argv[2] == "aa":
    print("separated" if v["status"] != "inconclusive" else "tie", v["winner"])
else:
    print("separated" if v["status"] == "clear" and v["winner"] == "jitter" else "missed", v["winner"])
EOF
}

aa=0
power=0
i=0
start=$(date +%s)
while [ "$i" -lt "$N" ]; do
    r=$(study "aa$i" aa $((1 + 8 * i)))
    case $r in separated*) aa=$((aa + 1)) ;; esac
    r2=$(study "pw$i" pw $((1 + 8 * i)))
    case $r2 in separated*) power=$((power + 1)) ;; esac
    i=$((i + 1))
    echo "study $i/$N: A/A $r; random vs jitter $r2" >&2
done
echo "load: $LOAD, $(($(date +%s) - start)) s wall, load average now $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
echo "A/A at equal CPU time: $aa of $N studies separated some variant"
echo "power (random vs jitter at equal CPU time): $power of $N studies ranked jitter alone first"
