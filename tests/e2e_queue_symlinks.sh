#!/bin/sh
# End to end: a job's outputs are never written through a symbolic link: not at DIR/done (or
# running/, failed/), not at DIR/done/<name>, not at --out's <name> folder. Entries named *.yaml
# that can never run (a FIFO, a directory, a dangling or looping link) are filed in failed/ with a
# log, once, instead of lying in DIR for ever.
. tests/lib.sh
root=$(pwd)
tiny() {
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; } >"$1"
}

# 1. DIR/done is a link to elsewhere: the queue is refused, nothing lands there
Q=$T/q1; mkdir -p "$Q" "$T/elsewhere1"; ln -s "$T/elsewhere1" "$Q/done"
tiny "$Q/a.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/q1.log"; rc=$?
check "done/ a link: refused with exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "done/ a link: says so" grep -q "symbolic link" "$T/q1.log"
check "done/ a link: nothing written through it" [ -z "$(ls -A "$T/elsewhere1")" ]

# 2. DIR/done/<name> is a link: the job is filed in failed/, nothing lands there
Q=$T/q2; mkdir -p "$Q/done" "$T/elsewhere2"; ln -s "$T/elsewhere2" "$Q/done/b"
tiny "$Q/b.yaml"; tiny "$Q/c.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/q2.log"; rc=$?
check "done/<name> a link: exit 1 or 2 (got $rc)" [ "$rc" -ge 1 ]
check "done/<name> a link: nothing written through it" [ -z "$(ls -A "$T/elsewhere2")" ]
check "done/<name> a link: the job in failed/" [ -f "$Q/failed/b.yaml" ]
check "done/<name> a link: its log says why" grep -q "symbolic link" "$Q/failed/b.log"
check "done/<name> a link: the other job done" [ -f "$Q/done/c/c.png" ]

# 3. --out's <name> folder is a link: refused
mkdir -p "$T/out3" "$T/elsewhere3"; ln -s "$T/elsewhere3" "$T/out3/d"; tiny "$T/d.yaml"
"$WORKER" --quiet --out "$T/out3" "$T/d.yaml" 2>"$T/d.log"; rc=$?
check "--out <name> a link: refused (got $rc)" [ "$rc" -ne 0 ]
check "--out <name> a link: nothing written through it" [ -z "$(ls -A "$T/elsewhere3")" ]

# 4. entries that can never run go to failed/ with a log; the queue drains the rest
Q=$T/q4; mkdir -p "$Q"
mkfifo "$Q/fifo.yaml"; mkdir "$Q/dir.yaml"; ln -s "$T/nothing.yaml" "$Q/dangling.yaml"
ln -s loop.yaml "$Q/loop.yaml"; tiny "$Q/e.yaml"
timeout 30 "$WORKER" --queue "$Q" --once --quiet 2>"$T/q4.log"; rc=$?
check "unrunnable: the worker ends (exit 2; got $rc)" [ "$rc" -eq 2 ]
check "unrunnable: the good job done" [ -f "$Q/done/e.yaml" ]
for n in fifo dir dangling loop; do
    check "unrunnable: $n.yaml moved to failed/" eval '[ ! -e "$Q/$n.yaml" ] && [ ! -L "$Q/$n.yaml" ] &&
        { [ -e "$Q/failed/$n.yaml" ] || [ -L "$Q/failed/$n.yaml" ]; }'
    check "unrunnable: $n.log says why" grep -q "cannot run" "$Q/failed/$n.log"
done
check "unrunnable: one line each on stderr" [ "$(grep -c "cannot run" "$T/q4.log")" -eq 4 ]

# 5. input side: a scene or reference inside the queue that a link leads out of it is not read,
#    and nothing of the file it points to reaches the world-readable failed/*.log; the same files
#    named by their own path (outside the queue, on purpose) are read as ever
Q=$T/q5; mkdir -p "$Q/in" "$T/secret"
printf 'root: x:0:0:SECRET-LINE\n' >"$T/secret/passwd.yaml"
ln -s "$T/secret/passwd.yaml" "$Q/in/scene.yaml"
{ echo "scene: in/scene.yaml"; echo "width: 8"; } >"$Q/f.yaml"
tiny "$T/r.yaml"; "$WORKER" --quiet --out "$T/o5" "$T/r.yaml"; cp "$T/o5/r/r.png" "$T/secret/ref.png"
ln -s "$T/secret/ref.png" "$Q/in/ref.png"
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 8"; echo "reference: in/ref.png"; } >"$Q/g.yaml"
{ echo "scene: $T/secret/passwd.yaml"; echo "width: 8"; } >"$Q/h.yaml"
timeout 60 "$WORKER" --queue "$Q" --once --quiet 2>"$T/q5.log"; rc=$?
check "input link: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "input link: the scene's job in failed/" [ -f "$Q/failed/f.yaml" ]
check "input link: its log names the key and the link" grep -q "f.yaml:1:8: scene: .*leaves the queue through a symbolic link" "$Q/failed/f.log"
check "input link: nothing of the file in the log" sh -c "! grep -q -e SECRET-LINE -e 'root: unknown' '$Q/failed/f.log'"
check "input link: the reference's job in failed/" grep -q "g.yaml:3:12: reference: .*leaves the queue" "$Q/failed/g.log"
check "input named outside on purpose: read (its error is about its content)" grep -q "root: unknown key" "$Q/failed/h.log"

# 6. a scene or reference that is not a regular file (a FIFO) is refused at once, in or out of a queue
mkfifo "$T/fifo-scene.yaml" "$T/fifo-ref.png"
{ echo "scene: $T/fifo-scene.yaml"; echo "width: 8"; } >"$T/fs.yaml"
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 8"; echo "reference: $T/fifo-ref.png"; } >"$T/fr.yaml"
for j in fs fr; do
    timeout 20 "$WORKER" --quiet --out "$T/o6" "$T/$j.yaml" 2>"$T/$j.log"; rc=$?
    check "FIFO input ($j): exit 2 at once (got $rc): $(cat "$T/$j.log")" [ "$rc" -eq 2 ]
done

# 7. each names what the file is (a FIFO, a character device, a directory), never "no scene file" or
#    "a symbolic link to nothing" for a file that is there
mkdir -p "$T/adir"
{ echo "scene: $T/fifo-scene.yaml"; echo "width: 8"; } >"$T/k1.yaml"
{ echo "scene: /dev/zero"; echo "width: 8"; } >"$T/k2.yaml"
{ echo "scene: $T/adir"; echo "width: 8"; } >"$T/k3.yaml"
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 8"; echo "reference: $T/fifo-ref.png"; } >"$T/k4.yaml"
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 8"; echo "reference: /dev/null"; } >"$T/k5.yaml"
(cd "$T" && printf 'scene: fifo-scene.yaml\nwidth: 8\n' >k6.yaml)
for k in "k1:is a FIFO, not a scene file" "k2:/dev/zero is a character device, not a scene file" \
    "k3:is a directory, not a scene file" "k4:is a FIFO, not an image file" \
    "k5:/dev/null is a character device, not an image file" "k6:fifo-scene.yaml is a FIFO"; do
    j=${k%%:*}; want=${k#*:}
    timeout 20 "$WORKER" --quiet --out "$T/o7" "$T/$j.yaml" 2>"$T/$j.log"; rc=$?
    check "special input ($j): exit 2 saying \"$want\" (got $rc): $(cat "$T/$j.log")" \
        sh -c "[ $rc -eq 2 ] && grep -q '$want' '$T/$j.log' && ! grep -q 'did you mean' '$T/$j.log'"
done
Q=$T/q7; mkdir -p "$Q"
ln -s /dev/zero "$Q/z.yaml"; ln -s "$T/fifo-scene.yaml" "$Q/f.yaml"
timeout 60 "$WORKER" --queue "$Q" --once --quiet 2>"$T/q7.log"
check "a link to /dev/zero in a queue: named so" grep -q 'z.yaml: cannot run: a symbolic link to a character device' "$Q/failed/z.log"
check "a link to a FIFO in a queue: named so" grep -q 'f.yaml: cannot run: a symbolic link to a FIFO' "$Q/failed/f.log"
finish
