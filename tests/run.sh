#!/bin/sh
# Runs every unit test binary and every end-to-end script, sums their "N passed, N failed" lines.
set -u
dir=$(cd "$(dirname "$0")" && pwd)
passed=0; failed=0; broken=""
tally() { # $1 = name, $2 = log file, $3 = exit code
    line=$(grep -E '[0-9]+ passed, [0-9]+ failed' "$2" | tail -n 1)
    # the leading group may not end in a digit, so greedy matching keeps whole numbers
    p=$(echo "$line" | sed -n 's/^\(.*[^0-9]\)\{0,1\}\([0-9][0-9]*\) passed, \([0-9][0-9]*\) failed.*/\2/p')
    f=$(echo "$line" | sed -n 's/^\(.*[^0-9]\)\{0,1\}\([0-9][0-9]*\) passed, \([0-9][0-9]*\) failed.*/\3/p')
    : "${p:=0}" "${f:=0}"
    if [ "$3" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
    passed=$((passed + p)); failed=$((failed + f))
    [ "$f" -ne 0 ] && broken="$broken $1"
    printf '%-28s %s passed, %s failed\n' "$1" "$p" "$f"
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
    done
fi
[ -n "$broken" ] && echo "failing:$broken"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
