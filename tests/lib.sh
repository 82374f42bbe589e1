# lib.sh: helpers for end-to-end tests; source it, call ok/no (or skip), end with `finish`.
set -u
WORKER=${WORKER:-$(pwd)/bin/worker}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0; fail=0; skipped=0
ok() { pass=$((pass + 1)); }
no() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
skip() { skipped=$((skipped + 1)); echo "SKIP: $*"; } # a check this machine cannot make: counted apart
check() { # check "description" command...
    d=$1; shift
    if "$@"; then ok; else no "$d"; fi
}
# the closing line tests/run.sh sums: "N passed, N failed" and, when any, ", K skipped"
finish() {
    if [ "$skipped" -gt 0 ]; then echo "$pass passed, $fail failed, $skipped skipped"; else echo "$pass passed, $fail failed"; fi
    [ "$fail" -eq 0 ]
}
render_child() { # render_child PID: print the pid of a render process of worker PID (wait up to 10 s)
    for _ in $(seq 1 500); do
        c=$(pgrep -P "$1" | head -n 1)
        [ -n "$c" ] && { echo "$c"; return 0; }
        sleep 0.02
    done
    return 1
}
