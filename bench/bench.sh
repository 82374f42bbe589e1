#!/bin/sh
# make bench: render each benchmark job RUNS times with 1 and with 2 processes (interleaved, so
# load drift hits both alike), print a table of medians with their spread (min-max), measure
# the peak RSS of a 1920x1080 render and Bridson's cost per point; write bench/results.json.
# Render figures come from the sidecars: ns/sample is CPU seconds * 1e9 / camera samples.
set -eu
WORKER=${WORKER:-bin/worker}
BRIDSON=${BRIDSON:-build/bench_bridson}
RUNS=${RUNS:-5}
# the seed's cornell (a fresh Bridson set per pixel and light) takes ~20 s a run: fewer runs
SLOW_JOBS=${SLOW_JOBS:-cornell}
RUNS_SLOW=${RUNS_SLOW:-3}
JOBS=${JOBS:-"checker cornell-book3 cornell final cornell-pool pool-t1"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
json=bench/results.json.tmp

field() { # field FILE KEY -> the first number after "KEY":
    sed -n "s/.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1
}
stats() { # numbers on stdin -> "median min max"
    sort -g | awk '{a[NR] = $1} END {
        m = NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2
        printf "%s %s %s\n", m, a[1], a[NR] }'
}
# CPU balance of a multi-process render: total CPU / (processes * the busiest one's CPU). The
# wall-time speedup on idle cores is at most processes * this; unlike wall time it does not
# depend on what else the machine runs.
balance() {
    sed -n '/"per_process"/,/]/p' "$1" | sed -n 's/.*"cpu_s": \([0-9.e+-]*\).*/\1/p' |
        awk '{s += $1; n++; if ($1 > m) m = $1} END {b = 0; if (n && m > 0) b = s / (n * m); printf "%.3f\n", b}'
}

load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo unknown)
machine="$(nproc) cores, $(uname -m), $(awk -F': ' '/model name/ {print $2; exit}' /proc/cpuinfo 2>/dev/null)"
echo "make bench: medians of n runs each with 1 and 2 processes (spread = min-max); $machine;" \
    "load average $load at start"
printf '%-13s %2s %6s %11s %7s %7s %6s %7s %11s %7s %11s %5s %7s %7s\n' job n ns/smp spread seg/smp Mrays/s \
    rss_MB wall_1p spread wall_2p spread 2p/1p balance smp_shr
{
    echo "{"
    echo "  \"machine\": \"$machine\","
    echo "  \"load_average_at_start\": \"$load\","
    echo "  \"runs\": $RUNS, \"runs_slow_jobs\": $RUNS_SLOW,"
    echo "  \"spread\": \"min and max over the runs\","
    echo "  \"jobs\": {"
} >"$json"
first=1
for name in $JOBS; do
    job=bench/jobs/$name.yaml
    for f in ns w1 w2 share bal; do : >"$out/$f"; done
    runs=$RUNS
    case " $SLOW_JOBS " in *" $name "*) runs=$RUNS_SLOW ;; esac
    for r in $(seq 1 "$runs"); do
        for p in 1 2; do
            rm -rf "$out/$p"
            "$WORKER" --quiet --force --processes $p --out "$out/$p" "$job" >/dev/null 2>&1 # every run renders
            sc="$out/$p/$name/$name.json"
            if [ $p = 1 ]; then
                field "$sc" ns_per_sample >>"$out/ns"
                field "$sc" wall_s >>"$out/w1"
                field "$sc" sampling_share >>"$out/share"
                cp "$sc" "$out/last1.json"
            else
                field "$sc" wall_s >>"$out/w2"
                balance "$sc" >>"$out/bal"
            fi
        done
    done
    set -- $(stats <"$out/ns") $(stats <"$out/w1") $(stats <"$out/w2")
    ns=$1 ns_lo=$2 ns_hi=$3 w1=$4 w1_lo=$5 w1_hi=$6 w2=$7 w2_lo=$8 w2_hi=$9
    share=$(stats <"$out/share" | cut -d' ' -f1)
    bal=$(stats <"$out/bal" | cut -d' ' -f1)
    sc=$out/last1.json
    cam=$(sed -n '/"rays"/,/}/p' "$sc" | field /dev/stdin camera)
    tot=$(sed -n '/"rays"/,/}/p' "$sc" | field /dev/stdin total)
    rss=$(field "$sc" peak_rss_kb)
    seg=$(awk -v t="$tot" -v c="$cam" 'BEGIN {printf "%.2f", t / c}')
    mrays=$(awk -v s="$seg" -v n="$ns" 'BEGIN {printf "%.2f", s / n * 1e3}')
    ratio=$(awk -v a="$w1" -v b="$w2" 'BEGIN {printf "%.2f", a / b}')
    printf '%-13s %2s %6.0f %5.0f-%-5.0f %7s %7s %6.1f %7.2f %5.2f-%-5.2f %7.2f %5.2f-%-5.2f %5s %7s %7.3f\n' \
        "$name" "$runs" "$ns" "$ns_lo" "$ns_hi" "$seg" "$mrays" "$(awk -v k="$rss" 'BEGIN {print k / 1024}')" \
        "$w1" "$w1_lo" "$w1_hi" "$w2" "$w2_lo" "$w2_hi" "$ratio" "$bal" "$share"
    [ $first = 1 ] || echo "    ," >>"$json"
    first=0
    cat >>"$json" <<JSON
    "$name": {"runs": $runs, "ns_per_camera_sample": $ns, "ns_min": $ns_lo, "ns_max": $ns_hi,
      "segments_per_sample": $seg, "mrays_per_cpu_s": $mrays, "peak_rss_kb": $rss,
      "wall_1p_s": $w1, "wall_1p_min": $w1_lo, "wall_1p_max": $w1_hi,
      "wall_2p_s": $w2, "wall_2p_min": $w2_lo, "wall_2p_max": $w2_hi,
      "speedup_2p": $ratio, "cpu_balance_2p": $bal, "sampler_share": $share}
JSON
done

# Peak RSS of a 1920x1080 render (the whole process tree, via GNU time when present; else the
# render children only), against the same scene rendered 8x8: the difference less the float
# framebuffer is what the render costs beyond framebuffer + scene.
peak_kb() { # peak_kb JOB -> kB
    if [ -x /usr/bin/time ]; then
        /usr/bin/time -f %M -o "$out/time" "$WORKER" --quiet --force --processes 1 --out "$out/hd" "$1" >/dev/null 2>&1
        cat "$out/time"
    else
        "$WORKER" --quiet --force --processes 1 --out "$out/hd" "$1" >/dev/null 2>&1
        n=$(basename "$1" .yaml)
        field "$out/hd/$n/$n.json" peak_rss_kb
    fi
}
hd_kb=$(peak_kb bench/jobs/hd-rss.yaml)
small_kb=$(peak_kb bench/jobs/hd-small.yaml)
fb_kb=$((1920 * 1080 * 3 * 4 / 1024))
extra_kb=$((hd_kb - small_kb - fb_kb))
echo "1920x1080 render: peak RSS $((hd_kb / 1024)) MB = 8x8 baseline $((small_kb / 1024)) MB" \
    "+ float framebuffer $((fb_kb / 1024)) MB + $((extra_kb / 1024)) MB more"
echo "  }," >>"$json"
echo "  \"hd_1920x1080\": {\"peak_rss_kb\": $hd_kb, \"baseline_8x8_kb\": $small_kb, \"framebuffer_kb\": $fb_kb, \"extra_kb\": $extra_kb}," >>"$json"

"$BRIDSON" >"$out/bridson"
echo "  \"bridson\": [" >>"$json"
sed 's/^/    /; $!s/$/,/' "$out/bridson" >>"$json"
echo "  ]" >>"$json"
echo "}" >>"$json"
mv "$json" bench/results.json
awk -F'[:,}]' '{k = $16; gsub(/[ "]/, "", k); if (k == "poisson") k = "bridson"
    printf "%s t=%s pool=%s: %s us/point CPU (median of %s, spread %s-%s)\n", k, $2, $4, $10, $8, $12, $14}' \
    "$out/bridson" | sed 's/  */ /g'
echo "wrote bench/results.json"
