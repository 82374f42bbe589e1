#!/bin/sh
# End to end: a worker whose output folder cannot be written (read-only, full disk) is the machine's
# fault, not the jobs': it hands its claim back to the queue, says so in one line, and stops with
# exit 2; nothing goes to failed/. A plain run's output folder errors exit 2 (bad usage), like a file
# in the way.
. tests/lib.sh
# nobody (below) may not reach the checkout (a clone under a 0700 mktemp folder): the scene and
# the worker it runs are copies in $T, which is made readable
chmod 755 "$T"
cp scenes/checker.yaml "$T/checker.yaml" && mkdir -p "$T/bin" && cp "$WORKER" "$T/bin/worker"
chmod 644 "$T/checker.yaml"; chmod 755 "$T/bin" "$T/bin/worker"
job() { printf 'scene: %s/checker.yaml\nwidth: 8\nheight: 8\nthreshold: 50\nprocesses: 1\n' "$T" >"$1"; }
queue() { # queue DIR: a fresh world-writable queue of two jobs
    rm -rf "$1"; mkdir -p "$1"; chmod 777 "$1"; job "$1/a.yaml"; job "$1/b.yaml"; chmod 666 "$1"/*.yaml
}
jobs_intact() { # jobs_intact DIR LOG: no job filed as failed, both still waiting, the log says why it stopped
    [ -z "$(ls "$1/failed")" ] && [ -f "$1/a.yaml" ] && [ -f "$1/b.yaml" ] &&
        grep -q 'this worker stops, exit 2), returned to the queue' "$2" && ! grep -q 'failed/' "$2"
}

# a read-only done/, as a user who cannot write it (root writes anywhere: run as nobody)
Q=$T/q1; queue "$Q"
as_user() { if [ "$(id -u)" -eq 0 ]; then setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; else "$@"; fi; }
if [ "$(id -u)" -ne 0 ] || command -v setpriv >/dev/null; then
    as_user sh -c "mkdir -p '$Q/done' && chmod 555 '$Q/done' && '$T/bin/worker' --queue '$Q' --once" 2>"$T/ro.log"
    rc=$?
    check "read-only done/: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "read-only done/: the jobs wait in the queue, none failed" jobs_intact "$Q" "$T/ro.log"
    check "read-only done/: one job taken, then the worker stops" [ "$(grep -c 'claimed by' "$T/ro.log")" -eq 1 ]
else
    skip "running as root without setpriv: a read-only folder cannot be made unwritable"
fi

# a full disk under done/ (the shim fails writes there with ENOSPC): the same
need_shim full
Q=$T/q2; queue "$Q"; mkdir -p "$Q/done"
SHIM_FULL=$Q/done LD_PRELOAD=$T/full.so "$WORKER" --queue "$Q" --once 2>"$T/full.log"
rc=$?
check "full disk: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "full disk: the jobs wait in the queue, none failed" jobs_intact "$Q" "$T/full.log"
check "full disk: the log says why" grep -q 'No space left on device' "$T/full.log"
check "full disk: no empty output folder left" [ -z "$(ls "$Q/done")" ]

# a compare job: refused at its claim (read-only done/) or at a render (full disk), never failed/
study() { printf 'name: cmp\nscenes: [%s/checker.yaml]\nwidth: 8\nheight: 6\nprocesses: 1\nseeds: [1, 2]\nvariants: [{ sampler: jitter, threshold: 50 }]\n' "$T" >"$1"; }
Q=$T/q4; rm -rf "$Q"; mkdir -p "$Q"; chmod 777 "$Q"; study "$Q/cmp.yaml"; chmod 666 "$Q/cmp.yaml"
if [ "$(id -u)" -ne 0 ] || command -v setpriv >/dev/null; then
    as_user sh -c "mkdir -p '$Q/done' && chmod 555 '$Q/done' && '$T/bin/worker' --queue '$Q' --once" 2>"$T/cro.log"
    rc=$?
    check "compare job, read-only done/: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "compare job, read-only done/: back in the queue, not failed" \
        sh -c "[ -f '$Q/cmp.yaml' ] && [ -z \"\$(ls '$Q/failed')\" ] && grep -q 'returned to the queue' '$T/cro.log'"
fi
Q=$T/q5; mkdir -p "$Q/done"; study "$Q/cmp.yaml"
SHIM_FULL=$Q/done LD_PRELOAD=$T/full.so "$WORKER" --queue "$Q" --once 2>"$T/cfull.log"
rc=$?
check "compare job, full disk at a render: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "compare job, full disk at a render: the render back in the study's queue, none failed" \
    sh -c "[ -f '$Q/spread/cmp/b-img-0-00000.yaml' ] && [ -z \"\$(ls '$Q/spread/cmp/failed')\" ] && grep -q 'No space left on device.*returned to the queue' '$T/cfull.log'"
"$WORKER" --queue "$Q" --once 2>/dev/null
check "compare job: a worker with room then gathers it" [ -s "$Q/done/cmp/verdict.json" ]

# a job error still goes to failed/ (and the worker goes on)
Q=$T/q3; queue "$Q"; printf 'scene: nowhere.yaml\nwidth: 8\n' >"$Q/bad.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/bad.log"
check "a bad job is filed in failed/" [ -f "$Q/failed/bad.yaml" ]
check "the good ones are done" sh -c "[ -f '$Q/done/a.yaml' ] && [ -f '$Q/done/b.yaml' ]"

# a plain run: the output folder errors exit 2, whatever step finds them
job "$T/p.yaml"
mkdir -p "$T/real"; ln -s "$T/real" "$T/link"
"$WORKER" "$T/p.yaml" --out "$T/link/o" 2>/dev/null
check "--out under a symbolic link that is fine renders" [ $? -eq 0 ]
ln -s "$T/real" "$T/p"
"$WORKER" "$T/p.yaml" --out "$T" 2>"$T/link.log"
rc=$?
check "--out whose job folder is a symbolic link: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "--out whose job folder is a symbolic link: said" grep -q 'is a symbolic link' "$T/link.log"
rm -f "$T/p"; : >"$T/p"
"$WORKER" "$T/p.yaml" --out "$T" 2>/dev/null
rc=$?
check "--out whose job folder is a plain file: exit 2 (got $rc)" [ "$rc" -eq 2 ]
rm -f "$T/p"
SHIM_FULL=$T/full LD_PRELOAD=$T/full.so "$WORKER" "$T/p.yaml" --out "$T/full" 2>"$T/plainfull.log"
rc=$?
check "--out on a full disk: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "--out on a full disk: no partial output" [ -z "$(ls "$T/full/p" 2>/dev/null)" ]
finish
