#!/bin/sh
# The bad-input corpus (tests/bad/EXPECT): every case exits 2 with "file:line:col: message" and
# writes nothing under --out.
. tests/lib.sh
cases=0
while IFS="$(printf '\t')" read -r file expect; do
    case "$file" in '#'*|'') continue ;; esac
    cases=$((cases + 1))
    path=tests/bad/$file
    run=$path
    case "$file" in
    scene-*)
        run=$T/job-for-$file
        printf 'scene: %s\nwidth: 8\n' "$(pwd)/$path" >"$run"
        path=$(pwd)/$path
        ;;
    esac
    rm -rf "$T/out"
    "$WORKER" --quiet --out "$T/out" "$run" 2>"$T/err"; rc=$?
    check "$file: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    if grep -Fq "$path:" "$T/err" && grep -Eq "^.*$file:$expect" "$T/err"; then ok; else
        no "$file: expected '$path:$expect', got: $(head -n 1 "$T/err")"
    fi
    check "$file: one-line error" [ "$(grep -c . "$T/err")" -eq 1 ]
    check "$file: nothing written under --out" [ ! -e "$T/out" ]
done <tests/bad/EXPECT
echo "bad-input corpus: $cases cases"
check "corpus has at least 40 cases" [ "$cases" -ge 40 ]
finish
