#!/bin/sh
# Golden images: every scene in scenes/ re-rendered small (64x64, seed 1) with each pixel
# sampler must stay within a measured RMSE of tests/golden/<scene>-<sampler>.png, and renders
# of deliberately broken scenes (a wall removed, a light turned around) must be rejected.
# GOLDEN_UPDATE=1 rewrites the goldens (`make golden`; GOLDEN_SAMPLERS="sobol" limits a run to
# some samplers, and then SEGMENTS holds only theirs: merge the other lines back by hand); GOLDEN_MEASURE=1 prints the RMSE
# between seeds 1, 2 and 3 that the tolerances in tests/golden/TOLERANCE are derived from.
. tests/lib.sh
root=$(pwd)
G=$root/tests/golden
samplers=${GOLDEN_SAMPLERS:-"uniform jitter random poisson sobol"} # GOLDEN_SAMPLERS: a subset (make golden writes all)
BLOCK=8 # compare 8x8 block means: noise averages out, a wrong wall or light does not
# Under ASan the suite runs every scene with one sampler only (same images, same bounds).
[ "${ASAN_FAST:-0}" = 1 ] && [ "${GOLDEN_UPDATE:-0}" != 1 ] && samplers="jitter"

render() { # render NAME SCENE-FILE SAMPLER THRESHOLD LIGHT-THRESHOLD SEED -> $T/out/NAME/NAME.png
    printf 'name: %s\nscene: %s\nwidth: 64\nheight: 64\nsampler: %s\nthreshold: %s\nlight_threshold: %s\nseed: %s\nprocesses: 2\n' \
        "$1" "$2" "$3" "$4" "$5" "$6" >"$T/$1.yaml"
    "$WORKER" --quiet --out "$T/out" "$T/$1.yaml" 2>"$T/$1.err"
}
rmse() { "$WORKER" diff "$1" "$2" --block "$BLOCK" | sed -n 's/^rmse //p'; }
SEG_TOL=0.006 # > 2x the largest spread between seeds 1, 2 and 3 (tests/golden/README.md)
segs() { # segments per camera sample of NAME's render
    awk '/"samples"/ { s = 1 } s && /"total"/ { st = $2; s = 0 } /"rays"/ { r = 1 } r && /"total"/ { rt = $2; r = 0 }
         END { gsub(",", "", st); gsub(",", "", rt); if (st > 0) printf "%.5f\n", rt / st }' "$T/out/$1/$1.json"
}
seg_golden() { awk -v s="$1" '$1 == s { print $2 }' "$G/SEGMENTS"; }
seg_within() { awk -v a="$1" -v b="$2" -v t="$SEG_TOL" 'BEGIN { d = (a - b) / b; exit !(b > 0 && d <= t && d >= -t) }'; }
[ "${GOLDEN_UPDATE:-0}" = 1 ] && printf '%s\n' "# Path segments per camera sample (rays.total / samples.total) of each golden's render: seed 1," \
    "# as tests/e2e_golden.sh renders it. Written by \`make golden\`; see README.md here." >"$G/SEGMENTS.new"

while read -r scene thr lthr tol; do
    case "$scene" in '#'*|'') continue ;; esac
    for s in $samplers; do
        n=$scene-$s
        render "$n" "$root/scenes/$scene.yaml" "$s" "$thr" "$lthr" 1; rc=$?
        check "$n: renders (exit $rc)" [ "$rc" -eq 0 ]
        if [ "${GOLDEN_UPDATE:-0}" = 1 ]; then
            cp "$T/out/$n/$n.png" "$G/$n.png" && echo "golden: wrote tests/golden/$n.png"
            echo "$n $(segs "$n")" >>"$G/SEGMENTS.new"
        elif [ "${GOLDEN_MEASURE:-0}" = 1 ]; then
            render "$n-s2" "$root/scenes/$scene.yaml" "$s" "$thr" "$lthr" 2
            render "$n-s3" "$root/scenes/$scene.yaml" "$s" "$thr" "$lthr" 3
            echo "measure: $n seed1-seed2 $(rmse "$T/out/$n/$n.png" "$T/out/$n-s2/$n-s2.png")" \
                "seed1-seed3 $(rmse "$T/out/$n/$n.png" "$T/out/$n-s3/$n-s3.png")" \
                "seed2-seed3 $(rmse "$T/out/$n-s2/$n-s2.png" "$T/out/$n-s3/$n-s3.png")" \
                "golden-seed1 $(rmse "$G/$n.png" "$T/out/$n/$n.png")"
            echo "measure: $n segments seed1 $(segs "$n") seed2 $(segs "$n-s2") seed3 $(segs "$n-s3")" \
                "golden $(seg_golden "$n")"
        else
            got=$(rmse "$G/$n.png" "$T/out/$n/$n.png")
            "$WORKER" diff "$G/$n.png" "$T/out/$n/$n.png" --block "$BLOCK" --max-rmse "$tol" >/dev/null 2>&1; rc=$?
            check "$n: rmse $got within $tol of the golden (exit $rc)" [ "$rc" -eq 0 ]
            got=$(segs "$n"); want=$(seg_golden "$n")
            check "$n: $got segments per sample within $SEG_TOL of the golden's ${want:-(none)}" \
                seg_within "${got:-0}" "${want:-0}"
        fi
    done
done <"$G/TOLERANCE"
[ "${GOLDEN_UPDATE:-0}" = 1 ] && { [ "$fail" -eq 0 ] && mv "$G/SEGMENTS.new" "$G/SEGMENTS"; rm -f "$G/SEGMENTS.new"; finish; exit; }

# Perturbed scenes must fail the same check: the golden bound is not vacuous.
tol_of() { awk -v s="$1" '$1 == s { print $4 }' "$G/TOLERANCE"; }
thr_of() { awk -v s="$1" '$1 == s { print $2, $3 }' "$G/TOLERANCE"; }
perturbed() { # perturbed NAME SCENE SED-EXPR: render the edited scene with jitter, expect rejection
    mkdir -p "$T/scenes"
    sed "$3" "$root/scenes/$2.yaml" >"$T/scenes/$1.yaml"
    cp -r "$root/scenes/textures" "$T/scenes/" 2>/dev/null
    check "$1: the edit changed the scene" sh -c "! cmp -s '$root/scenes/$2.yaml' '$T/scenes/$1.yaml'"
    set -- "$1" "$2" $(thr_of "$2") "$(tol_of "$2")"
    render "$1" "$T/scenes/$1.yaml" jitter "$3" "$4" 1
    got=$(rmse "$G/$2-jitter.png" "$T/out/$1/$1.png")
    "$WORKER" diff "$G/$2-jitter.png" "$T/out/$1/$1.png" --block "$BLOCK" --max-rmse "$5" >/dev/null 2>&1; rc=$?
    [ "${GOLDEN_MEASURE:-0}" = 1 ] && echo "measure: perturbed $1 rmse $got (tolerance $5)"
    check "$1: perturbed render rejected (rmse $got over $5, exit $rc)" [ "$rc" -eq 1 ]
}
perturbed book3-no-green-wall cornell-book3 '/at: 555, material: green/d'
perturbed book3-light-up cornell-book3 '/material: lamp/s/flip: true, //'
perturbed cornell-disk-turned cornell '/center: \[278, 554, 279\]/s/toward: \[278, 0, 279\]/toward: [278, 1000, 279]/'
perturbed cornell-no-sphere cornell '/material: earth }/d'
finish
