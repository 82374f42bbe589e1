# lib.sh: helpers for end-to-end tests; source it, call ok/no, end with `finish`.
set -u
WORKER=${WORKER:-$(pwd)/bin/worker}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0; fail=0
ok() { pass=$((pass + 1)); }
no() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
check() { # check "description" command...
    d=$1; shift
    if "$@"; then ok; else no "$d"; fi
}
finish() { echo "$pass passed, $fail failed"; [ "$fail" -eq 0 ]; }
render_child() { # render_child PID: print the pid of a render process of worker PID (wait up to 10 s)
    for _ in $(seq 1 500); do
        c=$(pgrep -P "$1" | head -n 1)
        [ -n "$c" ] && { echo "$c"; return 0; }
        sleep 0.02
    done
    return 1
}
