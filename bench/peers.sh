#!/bin/sh
# bench/peers.sh (`make bench-peers`): our renderer against Blender's Cycles at equal error. Each
# scene (default the book-3 Cornell box, then the seed's chess board) is converted from our own
# scene file (bench/peers.py),
# rendered by Cycles (bench/peers_cycles.py: one thread, unbiased settings, EXR out) and by us
# (the mixture as the book's job; nee with jitter pixels and jitter light sets the pixel's size;
# nee with sobol pixels and light sets, as Cycles' Sobol; nee + sampler_dims: all + sobol; and
# both nee rows again with the book job's t=5 jitter light sets, nee-book and nee-sobol-book;
# one process), PEERS_SEEDS seeds each (6: three pairs), Cycles
# and ours interleaved so that load on the machine hits both alike; then bench/peers.py prints ns
# per sample, the mean over the seed pairs (1,2), (3,4), ... of the MSE between a pair's images,
# the image means (within 3% of Cycles') and the equal-error efficiency 1 / (MSE x seconds per
# image) against Cycles'. Installs Debian's blender with apt-get when it is missing and we are
# root (not part of make test or CI).
# Env: WORKER, PEERS_SCENES (scene files, space-separated; PEERS_SCENE: one), PEERS_SIZE (200), PEERS_THRESHOLD (12.5: 64 spp), PEERS_SEEDS (6, even),
# PEERS_OUT, PEERS_SPHERE (mesh: a sphere as a smooth 512x256 UV-sphere mesh; points: as one
# point of a Cycles point cloud, through which a glass sphere showed no refracted light, as if a
# ray inside it never hit it again: BENCH.md's tables before 2026-12-02 07:00 UTC).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
WORKER=${WORKER:-$root/bin/worker}
SCENES=${PEERS_SCENES:-${PEERS_SCENE:-$root/scenes/cornell-book3.yaml $root/scenes/checker.yaml}}
SIZE=${PEERS_SIZE:-200}
THRESHOLD=${PEERS_THRESHOLD:-12.5}
OUT_ROOT=${PEERS_OUT:-$root/build/peers}
SEEDS=${PEERS_SEEDS:-6}
case $SEEDS in *[!0-9]* | "" | 0) echo "bench-peers: PEERS_SEEDS must be an even count >= 2" >&2; exit 2 ;; esac
[ $((SEEDS % 2)) = 0 ] || { echo "bench-peers: PEERS_SEEDS must be an even count >= 2" >&2; exit 2; }
SPP=$(awk -v t="$THRESHOLD" 'BEGIN { n = int(100 / t); print n * n }')

if ! command -v blender >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "bench-peers: installing blender (apt-get)" >&2
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends blender; } \
            >"${TMPDIR:-/tmp}/bench-peers-apt.log" 2>&1 || true
    fi
    command -v blender >/dev/null 2>&1 || { echo "bench-peers: no blender: apt-get install blender" >&2; exit 1; }
fi
python3 -c 'import yaml' 2>/dev/null || { echo "bench-peers: python3 needs PyYAML: apt-get install python3-yaml" >&2; exit 1; }

# one scene: its renders, then its table (out: $OUT_ROOT/<scene's stem>/)
run_scene() {
    SCENE=$1
    OUT=$OUT_ROOT/$(basename "$SCENE" .yaml)
    rm -rf "$OUT" && mkdir -p "$OUT"
    python3 "$root/bench/peers.py" scene "$SCENE" "$OUT/scene.json"
    # name, then the job keys that make it (KEY=- leaves KEY out: sampler_dims: all refuses light_*)
    # (nee and nee-sobol: each light's set as large as the pixel's and of its kind, so that a
    # pixel's samples take one whole stratified light set, as Cycles' Sobol light dimensions are
    # stratified over a pixel's samples; nee-book and nee-sobol-book: the book job's t=5 jitter
    # light sets, 400 points of which a pixel takes 64 in a random order, as the mixture row)
    variants="mixture:integrator=mixture nee:integrator=nee,light_threshold=$THRESHOLD nee-sobol:integrator=nee,sampler=sobol,light_sampler=sobol,light_threshold=$THRESHOLD nee-sobol-all:integrator=nee,sampler_dims=all,sampler=sobol,light_sampler=-,light_threshold=- nee-book:integrator=nee nee-sobol-book:integrator=nee,sampler=sobol"
    job() { # job NAME SEED KEYS -> $OUT/NAME-sSEED.yaml
        f=$OUT/$1-s$2.yaml
        printf 'name: %s-s%s\nscene: %s\nwidth: %s\nheight: %s\nsampler: jitter\nthreshold: %s\nlight_sampler: jitter\nlight_threshold: 5\nseed: %s\nprocesses: 1\noutput: %s-s%s.pfm\n' \
            "$1" "$2" "$SCENE" "$SIZE" "$SIZE" "$THRESHOLD" "$2" "$1" "$2" >"$f"
        echo "$3" | tr ',' '\n' | while IFS='=' read -r k v; do
            if [ "$v" = - ]; then sed -i "/^$k:/d" "$f"; # "-": the key left out
            elif grep -q "^$k:" "$f"; then sed -i "s/^$k:.*/$k: $v/" "$f"; else echo "$k: $v" >>"$f"; fi
        done
    }
    cpu_s() { sed -n 's/^ *"cpu_s": \([0-9.e+-]*\),*$/\1/p' "$1" | head -n 1; }
    res=$OUT/results.tsv
    : >"$res"
    echo "bench-peers: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)," \
        "load average $(cut -d' ' -f1-3 /proc/loadavg) at start; $(basename "$SCENE") ${SIZE}x$SIZE, $SPP spp"
    for seed in $(seq 1 "$SEEDS"); do
        blender -b --factory-startup -P "$root/bench/peers_cycles.py" -- "$OUT/scene.json" "$OUT/cycles-s$seed" \
            "$seed" "$SPP" "$SIZE" "$SIZE" >"$OUT/cycles-s$seed.log" 2>&1 ||
            { echo "bench-peers: blender failed: $OUT/cycles-s$seed.log" >&2; exit 1; }
        printf 'cycles\t%s\t%s\t%s\t%s\n' "$seed" "$(cut -f1 "$OUT/cycles-s$seed.tsv")" "$OUT/cycles-s$seed.pfm" \
            "$((SIZE * SIZE * SPP))" >>"$res"
        for v in $variants; do
            name=${v%%:*}
            job "$name" "$seed" "${v#*:}"
            "$WORKER" --quiet --out "$OUT" "$OUT/$name-s$seed.yaml"
            j=$OUT/$name-s$seed/$name-s$seed
            printf 'ours-%s\t%s\t%s\t%s\t%s\n' "$name" "$seed" "$(cpu_s "$j.json")" "$j.pfm" \
                "$(sed -n '/"samples"/,/}/s/.*"total": \([0-9]*\).*/\1/p' "$j.json" | head -n 1)" >>"$res"
        done
    done
    mse() { "$WORKER" diff "$1" "$2" --json | sed 's/.*"mse": \([0-9.e+-]*\),.*/\1/'; }
    for a in $(seq 1 2 "$SEEDS"); do
        b=$((a + 1))
        printf 'mse\tcycles\t%s\n' "$(mse "$OUT/cycles-s$a.exr" "$OUT/cycles-s$b.exr")" >>"$res"
        for v in $variants; do
            name=${v%%:*}
            printf 'mse\tours-%s\t%s\n' "$name" "$(mse "$OUT/$name-s$a/$name-s$a.pfm" "$OUT/$name-s$b/$name-s$b.pfm")" >>"$res"
        done
    done
    echo "load average $(cut -d' ' -f1-3 /proc/loadavg) at the end"
    python3 "$root/bench/peers.py" table "$res"
}
rc=0
for scene in $SCENES; do
    run_scene "$scene" || rc=1
done
exit $rc
