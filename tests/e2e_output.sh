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
check "full disk: exit 2, the output folder's fault (got $rc)" [ "$rc" -eq 2 ]
check "full disk: the error says why" grep -Eq 'No space left|File too large' "$T/err1"
check "full disk: the error names the output, not a temporary name: $(cat "$T/err1")" \
    sh -c "grep -q 'cannot write $T/full/big/big\.[a-z]*: ' '$T/err1' && ! grep -q '\.tmp\.' '$T/err1'"
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

# 4b. A re-render whose sidecar cannot be written (a 1 KiB file-size limit: the 1x1 PPM fits, the
#     sidecar does not) fails with exit 2 (the output folder cannot be written) and leaves the earlier image and sidecar as they were;
#     the new image used to replace the old one and then be removed with nothing in its place.
printf 'scene: %s/scenes/checker.yaml\nname: dot\nwidth: 1\nheight: 1\nthreshold: 50\noutput: dot.ppm\n' "$root" >"$T/dot.yaml"
"$WORKER" --quiet --out "$T/o4b" "$T/dot.yaml" 2>/dev/null
cp "$T/o4b/dot/dot.ppm" "$T/dot-before.ppm"; cp "$T/o4b/dot/dot.json" "$T/dot-before.json"
(ulimit -f 1; "$WORKER" --quiet --force --out "$T/o4b" "$T/dot.yaml") 2>"$T/err4b"; rc=$?
check "sidecar too big: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "sidecar too big: the error names the sidecar" grep -q "cannot write $T/o4b/dot/dot.json: File too large" "$T/err4b"
check "sidecar too big: the earlier image kept" cmp -s "$T/dot-before.ppm" "$T/o4b/dot/dot.ppm"
check "sidecar too big: the earlier sidecar kept" cmp -s "$T/dot-before.json" "$T/o4b/dot/dot.json"
check "sidecar too big: no temporary file left" [ -z "$(ls -A "$T/o4b/dot" | grep tmp)" ]

# 4c. Two job files of one name on one command line (jobs/a/render.yaml, jobs/b/render.yaml) would
#     write the same OUT/<name>/: the later one is refused (exit 2, one line naming both files) and
#     the earlier one's outputs stay; it used to replace them silently, exit 0. The same file
#     given twice is one job: the second time is current and skipped.
mkdir -p "$T/two/a" "$T/two/b"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nheight: 8\nthreshold: 50\n' "$root" >"$T/two/a/render.yaml"
printf 'scene: %s/scenes/checker.yaml\nwidth: 12\nheight: 12\nthreshold: 50\n' "$root" >"$T/two/b/render.yaml"
"$WORKER" --quiet --out "$T/o4c" "$T/two/a/render.yaml" "$T/two/b/render.yaml" 2>"$T/err4c"; rc=$?
check "same name twice: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "same name twice: one line names both files" \
    grep -q "^$T/two/b/render.yaml: name \"render\" is also the name of $T/two/a/render.yaml" "$T/err4c"
check "same name twice: the first job's image kept" grep -q '"width": 8,' "$T/o4c/render/render.json"
"$WORKER" --quiet --out "$T/o4c" "$T/two/a/render.yaml" "$T/two/a/render.yaml" 2>"$T/err4c2"; rc=$?
check "same file twice: exit 0 (got $rc)" [ "$rc" -eq 0 ]

# 5. A writer killed half-way leaves its temporary file (".big.png.tmp.XXXXXX"); the next render
#    of the job removes it, and nobody else's files.
"$WORKER" --quiet --out "$T/o5" "$T/big.yaml" 2>/dev/null
: >"$T/o5/big/.big.png.tmp.Ab3xYz"; : >"$T/o5/big/.big.json.tmp.Qw9Er1"; : >"$T/o5/big/.notes.txt.tmp.Ab3xYz"
: >"$T/o5/big/.big.png.tmp.St4g3d"; : >"$T/o5/big/..big.json.tmp.St4g3d.tmp.Zx8Cv7" # killed while staging
"$WORKER" --quiet --force --out "$T/o5" "$T/big.yaml" 2>/dev/null; rc=$?
check "dead writer's temporaries: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "dead writer's temporaries: removed" [ -z "$(ls -A "$T/o5/big" | grep '^\.big\..*\.tmp\.')" ]
check "dead writer's temporaries: another file's kept" [ -e "$T/o5/big/.notes.txt.tmp.Ab3xYz" ]

# 6. Writers of one folder take turns (flock on it), so an image and its sidecar always come from
#    one render: while another holds the folder's lock, the render waits with nothing written.
if command -v flock >/dev/null; then
    printf 'scene: %s/scenes/checker.yaml\nname: big\nwidth: 16\nheight: 12\nthreshold: 50\n' "$root" >"$T/small.yaml"
    mkdir -p "$T/o6/big"
    flock "$T/o6/big" sh -c "echo locked >'$T/held'; while [ ! -e '$T/release' ]; do sleep 0.05; done" &
    holder=$!
    while [ ! -e "$T/held" ]; do sleep 0.05; done
    "$WORKER" --quiet --out "$T/o6" "$T/small.yaml" 2>/dev/null & wpid=$!
    sleep 1 # a 16x12 render takes milliseconds: by now it waits for the lock
    check "folder lock: nothing written while another holds it" [ -z "$(ls -A "$T/o6/big")" ]
    : >"$T/release"; wait "$holder"; wait "$wpid"; rc=$?
    check "folder lock: exit 0 once it is free (got $rc)" [ "$rc" -eq 0 ]
    check "folder lock: written once it is free" [ -s "$T/o6/big/big.png" ]
else
    skip "folder lock: no flock(1) here"
fi
# 7. output: [a list]: one render, each image in its format, the same bytes as a job writing that
#    image alone; the sidecar named for the first; the summary line names them all.
printf 'scene: %s/scenes/checker.yaml\nname: l\nwidth: 16\nheight: 12\nthreshold: 50\nprocesses: 1\n' "$root" >"$T/l0"
{ cat "$T/l0"; echo "output: [pic.png, pic.exr, pic.pfm]"; } >"$T/list.yaml"
{ cat "$T/l0"; echo "output: pic.png"; } >"$T/png.yaml"
{ cat "$T/l0"; echo "output: pic.exr"; } >"$T/exr.yaml"
{ cat "$T/l0"; echo "output: pic.pfm"; } >"$T/pfm.yaml"
"$WORKER" --out "$T/o7" "$T/list.yaml" 2>"$T/err7"; rc=$?
check "output list: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "output list: the summary names every image: $(cat "$T/err7")" grep -q 'l/pic.png, pic.exr, pic.pfm$' "$T/err7"
check "output list: one sidecar, named for the first" sh -c "[ -s '$T/o7/l/pic.json' ] && [ \$(ls '$T/o7/l' | wc -l) -eq 4 ]"
for f in png exr pfm; do
    "$WORKER" --quiet --out "$T/o7$f" "$T/$f.yaml"
    check "output list: pic.$f is the bytes a job writing it alone writes" cmp -s "$T/o7/l/pic.$f" "$T/o7$f/l/pic.$f"
done
"$WORKER" --out "$T/o7" "$T/list.yaml" 2>"$T/err7b"
check "output list: current when all are there" grep -q 'up to date' "$T/err7b"
rm "$T/o7/l/pic.pfm"
"$WORKER" --out "$T/o7" "$T/list.yaml" 2>"$T/err7c"
check "output list: one missing renders again" sh -c "! grep -q 'up to date' '$T/err7c' && [ -s '$T/o7/l/pic.pfm' ]"
finish
