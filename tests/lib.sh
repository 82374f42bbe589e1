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
