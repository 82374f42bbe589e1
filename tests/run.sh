#!/bin/sh
# Runs every unit test binary and every end-to-end script, sums their "N passed, N failed[, K skipped]"
# lines. A script that asserted nothing (no check passed, failed or was skipped) fails: it checked nothing.
set -u
dir=$(cd "$(dirname "$0")" && pwd)
passed=0; failed=0; skipped=0; broken=""
count() { # count WORD LINE: the number before WORD ("passed,", "failed", "skipped") in LINE
    echo "$2" | awk -v w="$1" '{for (i = 1; i < NF; i++) { t = $(i + 1); sub(/,$/, "", t); if (t == w) print $i }}'
}
tally() { # $1 = name, $2 = log file, $3 = exit code
    line=$(grep -E '[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)?$' "$2" | tail -n 1)
    p=$(count passed "$line"); f=$(count failed "$line"); k=$(count skipped "$line")
    : "${p:=0}" "${f:=0}" "${k:=0}"
    if [ "$3" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$k" -eq 0 ]; then
        echo "$1: asserted nothing (no \"N passed, N failed\" line, or all zero): counted as failed"
        f=1
    fi
    passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + k))
    [ "$f" -ne 0 ] && broken="$broken $1"
    if [ "$k" -gt 0 ]; then
        printf '%-28s %s passed, %s failed, %s skipped\n' "$1" "$p" "$f" "$k"
    else
        printf '%-28s %s passed, %s failed\n' "$1" "$p" "$f"
    fi
}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for t in "$TEST_BIN_DIR"/test_*; do
    [ -x "$t" ] || continue
    case "$t" in *.d|*.o) continue ;; esac
    n=$(basename "$t")
    (cd "$dir/.." && "$t") >"$tmp/$n.log" 2>&1; rc=$?
    tally "$n" "$tmp/$n.log" "$rc"
    [ "$rc" -ne 0 ] && cat "$tmp/$n.log"
done
if [ "${E2E:-1}" = 1 ]; then
    for s in "$dir"/e2e_*.sh; do
        [ -f "$s" ] || continue
        n=$(basename "$s" .sh)
        (cd "$dir/.." && sh "$s") >"$tmp/$n.log" 2>&1; rc=$?
        tally "$n" "$tmp/$n.log" "$rc"
        [ "$rc" -ne 0 ] && cat "$tmp/$n.log"
        grep '^SKIP: ' "$tmp/$n.log" | sed "s/^/$n: /"
    done
fi
[ -n "$broken" ] && echo "failing:$broken"
if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
