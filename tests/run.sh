#!/bin/sh
# Runs every unit test binary and every end-to-end script, sums their "N passed, N failed" lines.
set -u
dir=$(cd "$(dirname "$0")" && pwd)
passed=0; failed=0; broken=""
tally() { # $1 = name, $2 = log file, $3 = exit code
    line=$(grep -E '[0-9]+ passed, [0-9]+ failed' "$2" | tail -n 1)
    p=$(echo "$line" | awk '{for (i = 1; i < NF; i++) if ($(i + 1) == "passed,") print $i}')
    f=$(echo "$line" | awk '{for (i = 1; i < NF; i++) if ($(i + 1) ~ /^failed/) print $i}')
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
