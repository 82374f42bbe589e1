#!/bin/sh
# A study spread over a queue survives a kill -9 at every instant of its spreading and gathering
# (issue 36, defect 4): the worker is killed (by the shim tests/shim/race.c) just before, and just
# after, each step that moves or writes something -- the study folder's rename into spread/, the job
# filed in spread/X/job/, a reference half, an image, its sidecar, its entry filed, each of the
# gather's outputs, the job moved to done/, the gather entry filed -- then --once workers take over.
# Each time: the study ends gathered, its images and references are the one-machine run's bytes,
# its summary the same figures, every entry filed once in the study's done/, nothing in failed/,
# nothing "already gathered" that never was, and no lease, lock or temporary file left.
. tests/lib.sh
need_shim race
root=$(pwd)
study() {
    printf 'name: ks\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nheight: 6\nprocesses: 1\n' "$root"
    printf 'light_threshold: 50\nreference: { sampler: jitter, threshold: 25 }\nseeds: [1, 2]\n'
    printf 'variants: [{ sampler: jitter, threshold: 50 }]\n'
}
study >"$T/ks.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/ks.yaml" 2>"$T/plain.log"
check "the one-machine run: $(cat "$T/plain.log")" [ -s "$T/plain/ks/verdict.json" ]
# the summary's figures but for the times (wall_s, cpu_s, sampler_share)
figures() { cut -d, -f1-6,10- "$1"; }
ref=$(basename "$(ls "$T"/plain/.cache/ref-checker-*-a.exr)")

n=0
# killed WHEN SUFFIX WHAT GATHERED: a worker killed just WHEN (before or after) the first rename to a path
# ending in SUFFIX, then --once workers until the study is gathered: one is enough, and it takes the
# killed worker's claims back at once (their holder gone on this host: under the default
# --lease-timeout of 60 s, a claim judged by its age alone would hold it past the 50 s allowed); GATHERED is 1 when the killed worker had filed the job in done/ (the next
# worker then only files the gather entry, saying "already gathered"), else 0
killed() {
    n=$((n + 1)); Q=$T/q$n; mkdir -p "$Q"; study >"$Q/ks.yaml"
    if [ "$1" = before ]; then
        SHIM_KILL_BEFORE=$2 LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once --quiet >/dev/null 2>"$T/k$n.log"
    else
        SHIM_KILL_AFTER=$2 LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once --quiet >/dev/null 2>"$T/k$n.log"
    fi
    rc=$?
    check "$3 ($1): the worker was killed there (exit $rc)" [ "$rc" -eq 137 ]
    rcs=""
    for i in 1 2 3; do
        [ "$i" -gt 1 ] && [ -f "$Q/done/ks.yaml" ] && break
        timeout 50 "$WORKER" --queue "$Q" --once --poll 0.1 >/dev/null 2>>"$T/r$n.log"
        rcs="$rcs $?"
    done
    S=$Q/spread/ks
    check "$3 ($1): the next --once worker gathers the study (exit$rcs): $(tail -n 3 "$T/r$n.log")" \
        eval '[ "$rcs" = " 0" ] && [ -f "$Q/done/ks.yaml" ] && [ -s "$Q/done/ks/verdict.json" ]'
    check "$3 ($1): its gather ran" \
        eval '[ -s "$Q/done/ks/summary.csv" ] && [ -s "$Q/done/ks/chart.svg" ] && [ -s "$Q/done/ks/report.html" ]'
    said=$(grep -c 'already gathered' "$T/r$n.log")
    check "$3 ($1): 'already gathered' said only when it was (job in done/ before the kill): $said" \
        [ "$said" -eq "$4" ]
    check "$3 ($1): the job file only in done/: $(ls "$Q" "$Q/running" "$S/job" 2>&1 | tr '\n' ' ')" \
        eval '[ -z "$(ls "$Q/running" "$S/job" | grep yaml)" ] && [ -z "$(ls "$Q" | grep yaml)" ]'
    check "$3 ($1): every entry filed once in the study's done/, none failed or waiting: $(ls "$S/done" "$S/failed" "$S" | tr '\n' ' ')" \
        eval '[ "$(ls "$S/done" | grep -c "yaml$")" -eq 5 ] && [ -z "$(ls "$S/failed" "$S/running" "$S" "$Q/failed" | grep "yaml$")" ]'
    same=0
    for f in "$T"/plain/ks/*.png "$T"/plain/ks/*.exr "$T"/plain/.cache/*.exr; do
        g=$Q/done/ks/$(basename "$f")
        case $f in */.cache/*) g=$Q/done/.cache/$(basename "$f") ;; esac
        cmp -s "$f" "$g" && same=$((same + 1))
    done
    check "$3 ($1): images and references the one-machine run's bytes ($same of 7)" [ "$same" -eq 7 ]
    check "$3 ($1): the summary's figures the one-machine run's" \
        [ "$(figures "$T/plain/ks/summary.csv")" = "$(figures "$Q/done/ks/summary.csv" 2>/dev/null)" ]
    left=$(find "$Q" -name '.*tmp*' -o -name '*.lease' -o -name '*.lock' -o -name '.ks.*')
    check "$3 ($1): no temporary, lease or lock file left: $left" [ -z "$left" ]
}

for when in before after; do
    killed "$when" /spread/ks "the study folder's rename into spread/" 0
    killed "$when" /spread/ks/job/ks.yaml "the job filed in the study's job/" 0
    killed "$when" "/.cache/$ref" "a reference half" 0
    killed "$when" /ks/checker-jitter-t50-t50-s1.png "an image" 0
    killed "$when" /ks/checker-jitter-t50-t50-s1.json "its sidecar" 0
    killed "$when" /spread/ks/done/b-img-0-00000.yaml "its entry filed" 0
    for out in summary.csv chart.svg report.html verdict.json; do
        killed "$when" "/done/ks/$out" "the gather's $out" 0
    done
    killed "$when" /done/ks.yaml "the job moved to done/" "$([ "$when" = after ] && echo 1 || echo 0)"
    killed "$when" /spread/ks/done/c-gather.yaml "the gather entry filed" "$([ "$when" = before ] && echo 1 || echo 0)"
done
finish
