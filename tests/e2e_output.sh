#!/bin/sh
# Output safety: a full disk or an --out that cannot be written gives an error, exit status and
# no partial file (images are written to a temporary file and renamed).
. tests/lib.sh
root=$(pwd)
printf 'scene: %s/scenes/checker.yaml\nname: big\nwidth: 160\nheight: 120\nthreshold: 50\n' "$root" >"$T/big.yaml"

leftovers() { find "$1" -type f 2>/dev/null | wc -l; }

# 1. A full disk: a 16 KiB tmpfs where we may mount one, else a 16 KiB file-size limit.
mkdir -p "$T/full"
if mount -t tmpfs -o size=16k tmpfs "$T/full" 2>/dev/null; then
    how="16 KiB tmpfs"
    "$WORKER" --quiet --out "$T/full" "$T/big.yaml" 2>"$T/err1"; rc=$?
    umount_later="$T/full"
else
    how="16 KiB file-size limit"
    (ulimit -f 16; "$WORKER" --quiet --out "$T/full" "$T/big.yaml") 2>"$T/err1"; rc=$?
    umount_later=""
fi
echo "full disk via $how"
check "full disk: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "full disk: the error says why" grep -Eq 'No space left|File too large' "$T/err1"
check "full disk: no image, no sidecar, no temporary file" [ "$(leftovers "$T/full")" -eq 0 ]
[ -n "$umount_later" ] && umount "$umount_later"

# 2. --out is a regular file: bad input, nothing rendered.
: >"$T/afile"
"$WORKER" --quiet --out "$T/afile" "$T/big.yaml" 2>"$T/err2"; rc=$?
check "--out is a file: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "--out is a file: message" grep -q 'a file is in the way' "$T/err2"
check "--out is a file: left untouched" [ ! -s "$T/afile" ]

# 3. A read-only folder (a read-only tmpfs where we may mount one: root ignores permissions).
mkdir -p "$T/ro"
if mount -t tmpfs -o ro,size=16k tmpfs "$T/ro" 2>/dev/null; then
    "$WORKER" --quiet --out "$T/ro" "$T/big.yaml" 2>"$T/err3"; rc=$?
    check "read-only --out: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "read-only --out: message" grep -q 'Read-only file system' "$T/err3"
    umount "$T/ro"
elif [ "$(id -u)" != 0 ]; then
    chmod 555 "$T/ro"
    "$WORKER" --quiet --out "$T/ro" "$T/big.yaml" 2>"$T/err3"; rc=$?
    check "read-only --out: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "read-only --out: message" grep -q 'Permission denied' "$T/err3"
    chmod 755 "$T/ro"
fi
check "read-only --out: nothing inside" [ "$(leftovers "$T/ro")" -eq 0 ]

# 4. --out (or a folder on its way) is a dangling symbolic link: no folder can be made there, so
#    bad input (exit 2) before rendering, not a whole render that then fails to write (exit 1).
ln -s "$T/nowhere/at/all" "$T/dangling"
"$WORKER" --quiet --out "$T/dangling" "$T/big.yaml" 2>"$T/err4"; rc=$?
check "dangling symlink --out: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "dangling symlink --out: names it" grep -q "cannot create directory $T/dangling: " "$T/err4"
"$WORKER" --quiet --out "$T/dangling/deeper" "$T/big.yaml" 2>"$T/err5"; rc=$?
check "dangling symlink on the way: exit 2 (got $rc)" [ "$rc" -eq 2 ]
finish
