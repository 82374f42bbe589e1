#!/bin/sh
# make bench: render each benchmark job RUNS times with 1 and with 2 processes, print a table of
# medians (spread = min..max) and write bench/results.json. Figures come from the sidecars.
set -eu
WORKER=${WORKER:-bin/worker}
RUNS=${RUNS:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
json=bench/results.json.tmp
field() { # field FILE KEY -> the first number after "KEY":
    sed -n "s/.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1
}
median() { sort -g | awk '{a[NR] = $1} END {m = a[int((NR + 1) / 2)]; printf "%s %s %s\n", m, a[1], a[NR]}'; }

printf '%-14s %9s %9s %7s %9s %8s %8s %8s %6s %7s\n' job ns/sample spread seg/smp Mrays/s rss_MB wall1_s wall2_s ratio smp_shr
{
echo "{"
echo "  \"machine\": \"$(nproc) cores, $(uname -m), $(awk -F': ' '/model name/ {print $2; exit}' /proc/cpuinfo 2>/dev/null)\","
echo "  \"runs\": $RUNS,"
echo "  \"jobs\": {"
} >"$json"
first=1
for job in bench/jobs/*.yaml; do
    name=$(basename "$job" .yaml)
    [ "$name" = hd-rss ] && continue
    : >"$out/ns"; : >"$out/w1"; : >"$out/w2"
    for r in $(seq 1 "$RUNS"); do
        for p in 1 2; do
            "$WORKER" --quiet --force --processes $p --out "$out/$p" "$job" 2>/dev/null # every run renders
            sc="$out/$p/$name/$name.json"
            if [ $p = 1 ]; then
                field "$sc" ns_per_sample >>"$out/ns"
                field "$sc" wall_s >>"$out/w1"
                cp "$sc" "$out/last1.json"
            else
                field "$sc" wall_s >>"$out/w2"
            fi
        done
    done
    set -- $(median <"$out/ns"); ns=$1; ns_lo=$2; ns_hi=$3
    w1=$(median <"$out/w1" | cut -d' ' -f1); w2=$(median <"$out/w2" | cut -d' ' -f1)
    sc=$out/last1.json
    cam=$(sed -n '/"rays"/,/}/p' "$sc" | field /dev/stdin camera)
    tot=$(sed -n '/"rays"/,/}/p' "$sc" | field /dev/stdin total)
    cpu=$(field "$sc" cpu_s); rss=$(field "$sc" peak_rss_kb); share=$(field "$sc" sampling_share)
    seg=$(awk -v t="$tot" -v c="$cam" 'BEGIN {printf "%.2f", t / c}')
    mrays=$(awk -v t="$tot" -v c="$cpu" 'BEGIN {printf "%.2f", t / c / 1e6}')
    ratio=$(awk -v a="$w1" -v b="$w2" 'BEGIN {printf "%.2f", a / b}')
    printf '%-14s %9.0f %4.0f-%-4.0f %7s %9s %8.1f %8.2f %8.2f %6s %7.3f\n' "$name" "$ns" "$ns_lo" "$ns_hi" "$seg" \
        "$mrays" "$(awk -v k="$rss" 'BEGIN {print k / 1024}')" "$w1" "$w2" "$ratio" "$share"
    [ $first = 1 ] || echo "    ," >>"$json"
    first=0
    cat >>"$json" <<JSON
    "$name": {"ns_per_camera_sample": $ns, "ns_min": $ns_lo, "ns_max": $ns_hi, "segments_per_sample": $seg,
      "mrays_per_s": $mrays, "peak_rss_kb": $rss, "wall_1p_s": $w1, "wall_2p_s": $w2, "speedup_2p": $ratio,
      "sampler_share": $share}
JSON
done
"$WORKER" --quiet --processes 1 --out "$out/hd" bench/jobs/hd-rss.yaml 2>/dev/null
hd_rss=$(field "$out/hd/hd-rss/hd-rss.json" peak_rss_kb)
fb_kb=$((1920 * 1080 * 3 * 4 / 1024))
echo "1920x1080 render: peak RSS $((hd_rss / 1024)) MB, of which the float framebuffer is $((fb_kb / 1024)) MB"
echo "  },"  >>"$json"
echo "  \"hd_1920x1080\": {\"peak_rss_kb\": $hd_rss, \"framebuffer_kb\": $fb_kb}," >>"$json"
echo "  \"bridson\": [" >>"$json"
build/bench_bridson | sed 's/^/    /; $!s/$/,/' >>"$json"
echo "  ]" >>"$json"
echo "}" >>"$json"
mv "$json" bench/results.json
build/bench_bridson | awk -F'[:,]' '{printf "bridson t=%s pool=%s: %s us/point (median of %s)\n", $2, $4, $10, $8}'
echo "wrote bench/results.json"
