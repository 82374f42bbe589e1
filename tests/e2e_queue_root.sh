#!/bin/sh
# e2e_queue_root: --queue at the file system's root ("/", "/tmp/..") is refused in one line, exit 2,
# making no running/, done/ or failed/ there; so is a queue that is not a directory. The root cases
# run in a chroot of their own (as root), never against the real "/".
. "$(dirname "$0")/lib.sh"
"$WORKER" --queue "$WORKER" --once 2>"$T/err"; rc=$?
check "a file as the queue: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "a file as the queue: one line naming it" grep -q "^worker: --queue $WORKER: Not a directory" "$T/err"
"$WORKER" --queue "$T/none" --once 2>"$T/err"; rc=$?
check "a missing queue: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "a missing queue: not made" [ ! -e "$T/none" ]
# (not with a sanitizer build: a chroot has no /proc, which its runtime needs)
if [ "$(id -u)" = 0 ] && command -v chroot >/dev/null && command -v ldd >/dev/null &&
    ! ldd "$WORKER" | grep -q 'lib[a-z]*san'; then
    R=$T/root; mkdir -p "$R/tmp"
    cp "$WORKER" "$R/worker"
    for l in $(ldd "$WORKER" | grep -o '/[^ ]*'); do mkdir -p "$R$(dirname "$l")"; cp "$l" "$R$l"; done
    for dir in / /tmp/..; do
        chroot "$R" /worker --queue "$dir" --once 2>"$T/err"; rc=$?
        check "--queue $dir: exit 2 (got $rc)" [ "$rc" -eq 2 ]
        check "--queue $dir: says it is the root: $(cat "$T/err")" grep -q "^worker: --queue $dir: is the file system's root directory" "$T/err"
        check "--queue $dir: one line" [ "$(grep -c . "$T/err")" -eq 1 ]
        check "--queue $dir: made nothing at the root" sh -c "[ ! -e '$R/running' ] && [ ! -e '$R/done' ] && [ ! -e '$R/failed' ]"
    done
    # a queue in a directory of its own still works there
    mkdir "$R/q"
    chroot "$R" /worker --queue /q --once 2>"$T/err"; rc=$?
    check "--queue /q: exit 0 (got $rc: $(cat "$T/err"))" [ "$rc" -eq 0 ]
    check "--queue /q: its folders made" [ -d "$R/q/running" ]
else
    skip "the root cases need root, chroot and a build without sanitizers"
fi
finish
