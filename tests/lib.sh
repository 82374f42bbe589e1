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
lease_text() { # lease_text PID [N]: the lease a worker of this host with pid PID writes (token ending :N, 1)
    printf 'host %s\npid %s\nstart %s\ntoken %s:%s:%s\n' "$(hostname)" "$1" "$(date +%s)" "$(hostname)" "$1" "${2:-1}"
}
preload_shim() { # preload_shim NAME: tests/shim/NAME.c built as $T/NAME.so for LD_PRELOAD (under ASan, whose
    # runtime the shim then precedes, with the link-order check off); 1 when it does not build ($T/cc.log)
    ${CC:-cc} -shared -fPIC -o "$T/$1.so" "tests/shim/$1.c" -ldl 2>"$T/cc.log" || return 1
    export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
}
need_shim() { # need_shim NAME: preload_shim NAME, or the script ends here, its checks skipped
    preload_shim "$1" && return 0
    cat "$T/cc.log"
    skip "no C compiler for the shim tests/shim/$1.c: race tests"
    finish
    exit $?
}
render_child() { # render_child PID: print the pid of a render process of worker PID (wait up to 10 s)
    for _ in $(seq 1 500); do
        c=$(pgrep -P "$1" | head -n 1)
        [ -n "$c" ] && { echo "$c"; return 0; }
        sleep 0.02
    done
    return 1
}
