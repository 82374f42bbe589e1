#!/bin/sh
# e2e_runner: tests/run.sh counts a skipped check as skipped (its closing line "N passed, N failed,
# K skipped", which CI parses), and fails a script that asserted nothing (no closing line, or one of
# zeros) instead of counting it as passed. Run on a copy of run.sh beside made-up scripts.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
suite() { # suite NAME: a folder with run.sh, lib.sh and an empty unit-test folder
    mkdir -p "$T/$1/tests" "$T/$1/bin"
    cp "$root/tests/run.sh" "$root/tests/lib.sh" "$T/$1/tests/"
}
runs() { # runs NAME: run its suite; its output into $T/NAME.out, exit status echoed
    (cd "$T/$1" && TEST_BIN_DIR="$T/$1/bin" sh tests/run.sh) >"$T/$1.out" 2>&1
    echo $?
}
suite a
printf '. tests/lib.sh\nok\nok\nskip "no such tool here"\nfinish\n' >"$T/a/tests/e2e_one.sh"
printf '. tests/lib.sh\nok\nfinish\n' >"$T/a/tests/e2e_two.sh"
rc=$(runs a)
check "a skip: exit 0 (got $rc: $(cat "$T/a.out"))" [ "$rc" -eq 0 ]
check "a skip: counted in the closing line" [ "$(tail -n 1 "$T/a.out")" = "3 passed, 0 failed, 1 skipped" ]
check "a skip: its script's line says so" grep -q '^e2e_one  *2 passed, 0 failed, 1 skipped$' "$T/a.out"
check "a skip: its reason shown" grep -q '^e2e_one: SKIP: no such tool here$' "$T/a.out"

suite b
printf '. tests/lib.sh\nok\nfinish\n' >"$T/b/tests/e2e_one.sh"
rc=$(runs b)
check "no skip: the closing line as before" [ "$(tail -n 1 "$T/b.out")" = "1 passed, 0 failed" ]

suite c
printf '. tests/lib.sh\nfinish\n' >"$T/c/tests/e2e_empty.sh"
printf 'echo checked nothing\n' >"$T/c/tests/e2e_silent.sh"
printf '. tests/lib.sh\nok\nfinish\n' >"$T/c/tests/e2e_fine.sh"
rc=$(runs c)
check "nothing asserted: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "nothing asserted: both scripts failed" [ "$(tail -n 1 "$T/c.out")" = "1 passed, 2 failed" ]
check "nothing asserted: named" grep -q '^failing: e2e_empty e2e_silent$' "$T/c.out"

suite d
printf '. tests/lib.sh\nskip "all of it"\nfinish\n' >"$T/d/tests/e2e_skipped.sh"
rc=$(runs d)
check "all skipped: not a failure (got $rc)" [ "$rc" -eq 0 ]
check "all skipped: counted" [ "$(tail -n 1 "$T/d.out")" = "0 passed, 0 failed, 1 skipped" ]
finish
