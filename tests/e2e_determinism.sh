#!/bin/sh
# e2e_determinism: a pixel depends only on the job's inputs and (seed, x, y). Every shipped scene
# with every pixel sampler renders to the same bytes from the default build (1 and 3 processes),
# a clang build, and a gcc build at -O0 with the vector back-ends off (make SIMD=0).
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)

if [ "${ASAN_FAST:-0}" = 1 ]; then
    skip "determinism: checked by the plain make test (the sanitizer pass builds no other compilers)"
    finish
    exit $?
fi

# build NAME MAKE-ARGS...: bin/worker of another build into build/det-NAME (kept: incremental)
build() {
    name=$1; shift
    d=$root/build/det-$name
    MAKEFLAGS= make -s -j2 -C "$root" BUILD="$d" BIN="$d/bin" "$@" "$d/bin/worker" >"$T/$name.log" 2>&1
    rc=$? # make's own status: a failed build leaves the last good (stale) binary in place
    check "the $name build succeeds ($(tail -c 300 "$T/$name.log"))" sh -c "[ $rc -eq 0 ] && [ -x '$d/bin/worker' ]"
    [ "$rc" -eq 0 ]
}
builds="default"
if command -v clang >/dev/null; then
    build clang CC=clang && builds="$builds clang"
else
    skip "no clang: the clang build's comparison"
fi
build scalar OPT=-O0 SIMD=0 && builds="$builds scalar"

bin_of() { [ "$1" = default ] && echo "$WORKER" || echo "$root/build/det-$1/bin/worker"; }
# every pixel sampler with the defaults; then next-event estimation with every dimension sampled
# (sobol and poisson sets for all of a path's decisions)
samplers="uniform jitter random poisson sobol sobol-nee poisson-nee"
for scene in checker cornell cornell-book3 final; do
    for s in $samplers; do
        j=$scene-$s
        printf 'name: %s\nscene: %s/scenes/%s.yaml\nwidth: 20\nheight: 20\nsampler: %s\nthreshold: 25\n' \
            "$j" "$root" "$scene" "${s%-nee}" >"$T/$j.yaml"
        # sampler_dims: all takes light points from the pixel sets: a light_threshold is an error there
        case $s in
        *-nee) printf 'integrator: nee\nsampler_dims: all\n' >>"$T/$j.yaml" ;;
        *) printf 'light_threshold: 20\n' >>"$T/$j.yaml" ;;
        esac
        for b in $builds; do
            for n in 1 3; do
                [ "$b" != default ] && [ "$n" = 3 ] && [ "$b" != clang ] && continue
                "$(bin_of "$b")" --quiet --processes $n --out "$T/$b-$n" "$T/$j.yaml" 2>/dev/null
            done
        done
        ref=$T/default-1/$j/$j.png
        check "$j: the default build renders" [ -s "$ref" ]
        for out in "$T"/default-3 "$T"/clang-1 "$T"/clang-3 "$T"/scalar-1; do
            [ -d "$out" ] || continue
            check "$j: $(basename "$out") == default-1 (byte for byte)" cmp -s "$ref" "$out/$j/$j.png"
        done
    done
done
# the option spelled in two pieces, so that this file is not itself a match for the repository's grep
fast_contract="fp-contract""=fast"
check "no $fast_contract anywhere in the repository" sh -c "! grep -rqI --exclude-dir=.git --exclude-dir=build -e '$fast_contract' '$root'"

finish
