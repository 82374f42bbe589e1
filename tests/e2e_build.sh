#!/bin/sh
# e2e_build: the Makefile's flags suit more than one compiler: a file builds with clang (skipped
# when there is none), whose -Werror refuses warning options it does not know.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)

if command -v clang >/dev/null; then
    MAKEFLAGS= make -s -C "$root" CC=clang BUILD="$T/clang" "$T/clang/common/base/err.o" >"$T/clang.log" 2>&1; rc=$?
    check "clang builds common/base/err.c with the Makefile's flags (got $rc: $(head -c 300 "$T/clang.log"))" \
        [ "$rc" -eq 0 ]
    check "clang: the object is there" [ -s "$T/clang/common/base/err.o" ]
else
    echo "no clang: the clang build check skipped"
fi

finish
