#!/bin/sh
# A study spread over a queue whose folder is tampered with (issue 36, defects 2, 8, 9, 11): an entry
# replaced by a FIFO, a folder or a dangling link is filed in the study's failed/ with one line and
# the worker ends (never polls for ever); status says the study waits for a requeue (no ETA); the
# requeue writes the entry anew and the study completes with the one-machine bytes. Files the study
# wrote and reads back (study.job, the job file in job/, done/c-gather.yaml, its folders) are checked
# against its record: a changed one ends the study in failed/ with one line, never in done/.
. tests/lib.sh
need_shim race
root=$(pwd)
study() {
    printf 'name: hs\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nheight: 6\nprocesses: 1\n' "$root"
    printf 'light_threshold: 50\nseeds: [1, 2]\nvariants: [{ sampler: jitter, threshold: 50 }]\n'
}
study >"$T/hs.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/hs.yaml" 2>"$T/plain.log"
# spread N: queue $T/qN ($Q) holding the study spread (its job filed in job/), nothing rendered: the
# spreading worker is killed just after filing it; S is the study's folder
spread() {
    Q=$T/q$1; S=$Q/spread/hs; mkdir -p "$Q"; study >"$Q/hs.yaml"
    SHIM_KILL_AFTER=/spread/hs/job/hs.yaml LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once --quiet \
        >/dev/null 2>"$T/spread$1.log"
}
# once N: one --once worker (--lease-timeout 1, at most 30 s: 124 when it had to be stopped) on $Q,
# its log $T/wN.log, its exit status in rc
once() {
    timeout 30 "$WORKER" --queue "$Q" --once --quiet --lease-timeout 1 --poll 0.1 >/dev/null 2>"$T/w$1.log"
    rc=$?
}
same_images() { # same_images: the done images are the one-machine run's bytes
    for f in "$T"/plain/hs/*.png; do cmp -s "$f" "$Q/done/hs/$(basename "$f")" || return 1; done
}

# 1. an entry replaced by a FIFO, a folder, a dangling link
n=0
for kind in fifo folder link; do
    n=$((n + 1)); spread "e$n"
    e=$S/b-img-0-00001.yaml; rm "$e"
    case $kind in fifo) mkfifo "$e" ;; folder) mkdir "$e" ;; link) ln -s "$T/nowhere" "$e" ;; esac
    once "e$n"
    check "entry a $kind: the --once worker ends within 30 s (exit $rc, 124: stopped): $(tail -n 2 "$T/we$n.log")" \
        [ "$rc" -ne 124 ]
    check "... exit 2 (an entry that cannot run, as in the plain queue)" [ "$rc" -eq 2 ]
    check "... the entry filed in the study's failed/ with its log" \
        eval '[ -e "$S/failed/b-img-0-00001.yaml" ] || [ -L "$S/failed/b-img-0-00001.yaml" ]; [ -s "$S/failed/b-img-0-00001.log" ]'
    check "... one line says what it is" \
        [ "$(grep -c "b-img-0-00001.yaml: cannot run: .*moved to" "$T/we$n.log")" -eq 1 ]
    check "... and one that the study waits for a requeue" \
        [ "$(grep -c "waits for its failed renders .* to be requeued: worker requeue" "$T/we$n.log")" -eq 1 ]
    check "... the other image rendered, no gather" \
        eval '[ -f "$S/done/b-img-0-00000.yaml" ] && [ ! -f "$Q/done/hs.yaml" ]'
    "$WORKER" status "$Q" >"$T/st$n.txt" 2>&1
    check "status: the study waits for a requeue, no ETA: $(grep hs.yaml "$T/st$n.txt")" \
        grep -q 'hs.yaml  study hs  1/2 renders done, 1 failed, 0 running .*ETA -- (waits for its failed renders to be requeued' "$T/st$n.txt"
    "$WORKER" status "$Q" --json >"$T/st$n.json" 2>&1
    check "status --json: eta_s null, waits_for_requeue" python3 -c 'import json,sys
s=json.load(open(sys.argv[1]))["studies"][0]
assert s["eta_s"] is None and s["waits_for_requeue"] is True and s["failed"] == 1, s' "$T/st$n.json"
    "$WORKER" requeue "$Q" hs >"$T/rq$n.txt" 2>&1; rrc=$?
    check "requeue: the entry written anew (exit $rrc): $(cat "$T/rq$n.txt")" \
        eval '[ "$rrc" -eq 0 ] && [ -f "$S/b-img-0-00001.yaml" ] && [ ! -L "$S/b-img-0-00001.yaml" ] && [ -z "$(ls "$S/failed")" ]'
    once "f$n"
    check "... then the study completes with the one-machine bytes (exit $rc)" \
        eval '[ "$rc" -eq 0 ] && [ -s "$Q/done/hs/verdict.json" ] && same_images'
done

# 2. files of the study changed after it was spread: the study ends in failed/ with one line
# broken N WHAT: after spread N was changed by WHAT, one worker: the job file in failed/, its log
# naming what is wrong (PATTERN), nothing gathered; status showed the study (not hidden) before
broken() {
    "$WORKER" status "$Q" >"$T/bs$1.txt" 2>&1
    check "$2: status still shows the study, damaged: $(grep hs "$T/bs$1.txt")" \
        grep -q "hs.yaml  study hs .*its folder is damaged: .*$3" "$T/bs$1.txt"
    once "b$1"
    check "$2: the study ends in failed/ (exit $rc): $(tail -n 1 "$T/wb$1.log")" \
        eval '[ "$rc" -eq 2 ] && [ -f "$Q/failed/hs.yaml" ] && [ ! -e "$Q/done/hs.yaml" ] && [ ! -e "$S/job/hs.yaml" ]'
    check "$2: one line says what is wrong" [ "$(grep -c "hs.yaml: the study's folder was changed: .*$3" "$T/wb$1.log")" -eq 1 ]
    check "$2: its log too" grep -q "error: the study's folder was changed: .*$3" "$Q/failed/hs.log"
    check "$2: the log ends with a newline" [ "$(tail -c 1 "$Q/failed/hs.log" | od -An -tx1 | tr -d ' ')" = 0a ]
}
spread 1; sed -i 's/^name: hs/name: victim/' "$S/study.job"
broken 1 "name: victim in study.job" "study.job: not the job that was spread"
check "... nothing written to done/victim/" [ ! -e "$Q/done/victim" ]
spread 2; rm "$S/study.job"
broken 2 "study.job removed" "study.job: missing"
spread 3; echo '# forged' >"$S/done/c-gather.yaml"
broken 3 "a forged done/c-gather.yaml" "c-gather.yaml: filed as done, but the study was never gathered"
spread 4; printf '# edited\n' >>"$S/job/hs.yaml"
broken 4 "an edited job/hs.yaml" "job/hs.yaml: changed since the study was spread"
spread 5; mkdir "$T/elsewhere"; rmdir "$S/done"; ln -s "$T/elsewhere" "$S/done"
broken 5 "done/ a symbolic link" "done is a symbolic link to a directory, not a folder"
check "... nothing written through it" [ -z "$(ls "$T/elsewhere")" ]
"$WORKER" requeue "$Q" hs >/dev/null 2>&1
once r5
check "queued again, the study is spread anew and completes (exit $rc)" \
    eval '[ "$rc" -eq 0 ] && [ -s "$Q/done/hs/verdict.json" ] && same_images'

# 3. a forged entry (no name the study wrote): set aside in failed/ with one line; the study completes
spread 6; echo '# forged' >"$S/0.yaml"; echo '# forged' >"$S/b-img-0-00099.yaml"
once 6
check "forged entries: the study completes (exit $rc, 2: what was set aside): $(tail -n 2 "$T/w6.log")" \
    eval '[ "$rc" -eq 2 ] && [ -s "$Q/done/hs/verdict.json" ] && same_images'
check "... each said in one line, in the study's failed/" \
    eval '[ "$(grep -c "0.yaml: not an entry of the study" "$T/w6.log")" -eq 1 ] && [ -f "$S/failed/b-img-0-00099.yaml" ]'
finish
