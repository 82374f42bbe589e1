#!/bin/sh
# e2e_clobber: `diff --map F` and `points --svg/--spectrum/--radial F` write only a new file or
# over a regular one that is not an input: an input image, a FIFO, a symbolic link or a device
# at F is refused (exit 2, one line naming it) and left as it was (issue 27: --map a.png
# overwrote a.png; a device node was replaced).
. "$(dirname "$0")/lib.sh"
printf 'scene: %s/scenes/checker.yaml\nwidth: 4\nheight: 4\nprocesses: 1\noutput: a.png\n' "$(pwd)" >"$T/j.yaml"
"$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>/dev/null
cp "$T/out/j/a.png" "$T/a.png"
cp "$T/a.png" "$T/b.png"
cp "$T/a.png" "$T/keep.png"
mkfifo "$T/fifo"
ln -s keep.png "$T/link.png"
ln "$T/a.png" "$T/hard.png"
refused() { # refused WHAT COMMAND...: exit 2 and one line naming what the file is
    what=$1; shift
    "$@" >/dev/null 2>"$T/err"; rc=$?
    check "$*: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$*: says it is $what: $(cat "$T/err")" grep -q "is $what, not replaced" "$T/err"
    check "$*: one line" [ "$(wc -l <"$T/err")" -eq 1 ]
}
refused "the input $T/a.png" "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/a.png"
check "the input a.png is unchanged" cmp -s "$T/a.png" "$T/keep.png"
refused "the input $T/b.png" "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/b.png"
refused "the input $T/a.png" "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/hard.png"
refused "a FIFO" timeout 10 "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/fifo"
check "the FIFO is still a FIFO" [ -p "$T/fifo" ]
refused "a symbolic link" "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/link.png"
check "the link is still a link" [ -L "$T/link.png" ]
for opt in --svg --spectrum --radial; do
    refused "a FIFO" timeout 10 "$WORKER" points jitter 20 "$opt" "$T/fifo"
    refused "a symbolic link" "$WORKER" points jitter 20 "$opt" "$T/link.png"
done
check "keep.png, the link's target, is unchanged" cmp -s "$T/a.png" "$T/keep.png"
if [ "$(id -u)" = 0 ] && mknod "$T/full" c 1 7 2>/dev/null; then # a copy of /dev/full
    refused "a device" "$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/full"
    check "the device is still a device" [ -c "$T/full" ]
    refused "a device" "$WORKER" points jitter 20 --svg "$T/full"
fi
# a new file, then the same regular file again, are written
"$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/map.png" >/dev/null 2>&1; rc=$?
check "a new --map file is written (rc $rc)" test "$rc" -eq 0 -a -f "$T/map.png"
"$WORKER" diff "$T/a.png" "$T/b.png" --map "$T/map.png" >/dev/null 2>&1; rc=$?
check "a regular --map file is replaced (rc $rc)" [ "$rc" -eq 0 ]
"$WORKER" points jitter 20 --svg "$T/p.svg" >/dev/null 2>&1 && "$WORKER" points jitter 20 --svg "$T/p.svg" >/dev/null 2>&1
check "--svg: new, then regular, written" grep -q "<svg" "$T/p.svg"
check "no temporary file left" [ -z "$(find "$T" -name '.*tmp*')" ]
finish
