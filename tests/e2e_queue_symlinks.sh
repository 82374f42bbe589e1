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
    check "unrunnable: $n.yaml moved to failed/" [ ! -e "$Q/$n.yaml" ] && [ ! -L "$Q/$n.yaml" ] &&
        { [ -e "$Q/failed/$n.yaml" ] || [ -L "$Q/failed/$n.yaml" ]; }
    check "unrunnable: $n.log says why" grep -q "cannot run" "$Q/failed/$n.log"
done
check "unrunnable: one line each on stderr" [ "$(grep -c "cannot run" "$T/q4.log")" -eq 4 ]
finish
