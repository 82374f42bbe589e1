#!/bin/sh
# End to end: worker diff's flip (HDR-FLIP on float images, LDR-FLIP on 8-bit ones) is 0 for an
# image against itself and within 5% of NVIDIA's reference implementation on the pairs in
# ../shared/oracles/flip/ (skipped when that folder is absent: FLIP_ORACLES names another);
# --mask (a rectangle or a white-on-black image) and a study's mask: give the cropped images'
# figures (cropped by python3); bad masks fail naming the option or file:line:col and key; a
# resumed study with another mask scores its current images again without rendering them.
. tests/lib.sh
root=$(pwd)
oracles=${FLIP_ORACLES:-$root/../shared/oracles/flip}

job() { # job FILE NAME [yaml lines...]: cornell at 24x20, light threshold 50
    f=$1; n=$2; shift 2
    { echo "name: $n"; echo "scene: $root/scenes/cornell.yaml"; echo "width: 24"; echo "height: 20"
      echo "light_threshold: 50"; for l in "$@"; do echo "$l"; done; } >"$f"
}
field() { awk -v k="$1" '$1 == k { print $2 }' "$2"; } # field KEY FILE: the value on worker diff's KEY line

# 1. a reference and an image, each as linear PFM and 8-bit PPM
job "$T/r.yaml" r "threshold: 10" "seed: 3" "output: [r.pfm, r.ppm]"
job "$T/a.yaml" a "threshold: 25" "sampler: jitter" "seed: 1" "output: [a.pfm, a.ppm]"
"$WORKER" --quiet --out "$T/o" "$T/r.yaml" "$T/a.yaml" 2>"$T/e0"; rc=$?
check "reference and image render (exit $rc: $(cat "$T/e0"))" [ "$rc" -eq 0 ]
R=$T/o/r/r A=$T/o/a/a

# 2. flip of an image against itself is 0; against another, HDR-FLIP on floats, LDR-FLIP on 8 bits
"$WORKER" diff "$R.pfm" "$R.pfm" >"$T/same_f"
"$WORKER" diff "$R.ppm" "$R.ppm" >"$T/same_8"
"$WORKER" diff --json "$R.pfm" "$R.pfm" >"$T/same_j"
check "diff A A (float): flip 0, HDR-FLIP: $(grep flip "$T/same_f")" grep -q "^flip 0.000000 HDR-FLIP" "$T/same_f"
check "diff A A (8-bit): flip 0, LDR-FLIP: $(grep flip "$T/same_8")" grep -q "^flip 0.000000 LDR-FLIP" "$T/same_8"
check "diff --json A A: \"flip\": 0, the metric named: $(cat "$T/same_j")" \
    eval 'grep -q "\"flip\": 0, \"flip_metric\": \"HDR-FLIP\", \"flip_exposures\": {" "$T/same_j"'
"$WORKER" diff "$R.pfm" "$A.pfm" >"$T/ra_f"
"$WORKER" diff "$R.ppm" "$A.ppm" >"$T/ra_8"
check "diff R A (float): 0 < flip < 1, HDR-FLIP: $(grep flip "$T/ra_f")" \
    awk '$1 == "flip" && $2 > 0 && $2 < 1 && $3 == "HDR-FLIP" { ok = 1 } END { exit !ok }' "$T/ra_f"
check "diff R A (8-bit): 0 < flip < 1, LDR-FLIP: $(grep flip "$T/ra_8")" \
    awk '$1 == "flip" && $2 > 0 && $2 < 1 && $3 == "LDR-FLIP" { ok = 1 } END { exit !ok }' "$T/ra_8"

# 3. NVIDIA's values: the README's rows "| reference | test | metric ... | mean |"
if [ -f "$oracles/README.md" ]; then
    grep -E '^\| cb3-[^|]*\.(exr|png) \|' "$oracles/README.md" | tr -d ' ' | awk -F'|' '{ print $2, $3, substr($4, 1, 8), $5 }' >"$T/rows"
    check "the oracle README lists 5 pairs" [ "$(wc -l <"$T/rows")" -eq 5 ]
    while read -r ref test metric want; do
        "$WORKER" diff "$oracles/$ref" "$oracles/$test" >"$T/or" 2>&1
        got=$(field flip "$T/or") name=$(awk '$1 == "flip" { print $3 }' "$T/or")
        check "$ref $test: $name $got against NVIDIA's $metric $want (5%)" awk -v g="$got" -v w="$want" \
            -v n="$name" -v m="$metric" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(n == m && g != "" && d <= 0.05 * w) }'
    done <"$T/rows"
else
    skip "no FLIP oracle images at $oracles (a clone without shared/): NVIDIA's values not compared"
fi

# 4. --mask: the cropped images' figures; a white-on-black mask image gives the rectangle's
python3 - "$T" "$R" "$A" <<'PY'
import struct, sys
t, ref, img = sys.argv[1:4]
x0, y0, x1, y1 = 5, 3, 17, 15
def pfm(path):  # rows bottom to top
    d = open(path, 'rb').read(); h = d.split(b'\n', 3); w, hh = map(int, h[1].split())
    f = struct.unpack('<%df' % (w * hh * 3), h[3]); return w, hh, f
def crop_pfm(src, dst):
    w, h, f = pfm(src); rows = []
    for y in range(y0, y1):  # image row y (top down) is file row h - 1 - y
        r = h - 1 - y; rows.append(f[(r * w + x0) * 3:(r * w + x1) * 3])
    out = b''.join(struct.pack('<%df' % len(r), *r) for r in reversed(rows))
    open(dst, 'wb').write(b'PF\n%d %d\n-1.0\n' % (x1 - x0, y1 - y0) + out)
def crop_ppm(src, dst):
    d = open(src, 'rb').read(); p = d.split(None, 4); w = int(p[1]); px = p[4]
    out = b''.join(px[(y * w + x0) * 3:(y * w + x1) * 3] for y in range(y0, y1))
    open(dst, 'wb').write(b'P6\n%d %d\n255\n' % (x1 - x0, y1 - y0) + out)
for name, path in (('r', ref), ('a', img)):
    crop_pfm(path + '.pfm', '%s/%s_crop.pfm' % (t, name)); crop_ppm(path + '.ppm', '%s/%s_crop.ppm' % (t, name))
mask = b''.join(b'\xff\xff\xff' if x0 <= x < x1 and y0 <= y < y1 else b'\0\0\0' for y in range(20) for x in range(24))
open(t + '/mask.ppm', 'wb').write(b'P6\n24 20\n255\n' + mask)
open(t + '/small.ppm', 'wb').write(b'P6\n23 20\n255\n' + b'\xff' * (23 * 20 * 3))
open(t + '/black.ppm', 'wb').write(b'P6\n24 20\n255\n' + b'\0' * (24 * 20 * 3))
PY
for ext in pfm ppm; do
    "$WORKER" diff "$R.$ext" "$A.$ext" --mask 5,3,17,15 | head -n 5 >"$T/m_$ext"
    "$WORKER" diff "$R.$ext" "$A.$ext" --mask "$T/mask.ppm" | head -n 5 >"$T/mi_$ext"
    "$WORKER" diff "$T/r_crop.$ext" "$T/a_crop.$ext" | head -n 5 >"$T/c_$ext"
    check "$ext: --mask 5,3,17,15 gives the cropped images' mse, rmse, relmse, relmse_robust, psnr" \
        eval '[ -s "$T/c_$ext" ] && cmp -s "$T/m_$ext" "$T/c_$ext"'
    check "$ext: --mask with a mask image of that rectangle gives the same" cmp -s "$T/mi_$ext" "$T/c_$ext"
    check "$ext: and not the whole image's mse" [ "$(field mse "$T/m_$ext")" != "$(field mse "$T/ra_f")" ]
done
"$WORKER" diff --json "$R.pfm" "$A.pfm" --mask 5,3,17,15 >"$T/mj"
check "--json says how many pixels the mask counts" grep -q '"mask_pixels": 144' "$T/mj"
for bad in 0,0,25,20 5,3,5,15 1,2,3 "$T/small.ppm" "$T/black.ppm" "$T/none.png"; do
    "$WORKER" diff "$R.pfm" "$A.pfm" --mask "$bad" >"$T/bo" 2>"$T/be"; rc=$?
    check "--mask $bad: exit 2, one line naming --mask, no figures ($rc: $(cat "$T/be"))" \
        eval '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/be")" -eq 1 ] && grep -q -- "--mask" "$T/be" && [ ! -s "$T/bo" ]'
done

# 5. a study with a mask: its summary.csv's mse is the cropped images' (the study's image of seed 1
# is a's pixels: the same settings); with the mask left out, resumed, the whole image's
study() { # study FILE MASK-LINE
    { echo "name: s"; echo "width: 24"; echo "height: 20"; echo "light_threshold: 50"; echo "threshold: 25"
      echo "reference: $R.pfm"; echo "scenes:"; echo "  - { scene: $root/scenes/cornell.yaml$2 }"
      echo "seeds: [1]"; echo "variants: [{ sampler: jitter }]"; } >"$1"
}
study "$T/s.yaml" ", mask: { rect: [5, 3, 17, 15] }"
"$WORKER" --quiet --out "$T/so" "$T/s.yaml" 2>"$T/se"; rc=$?
check "masked study: exit 0 ($rc: $(tail -n 1 "$T/se"))" [ "$rc" -eq 0 ]
item=$T/so/s/$(awk -F, 'NR == 2 { print $NF }' "$T/so/s/summary.csv" | sed 's/\.png$//')
check "the study's image is a's pixels" [ "$(field mse "$(
    "$WORKER" diff "$A.pfm" "$item.exr" >"$T/same"; echo "$T/same")")" = 0 ]
csv_mse() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } NR == 2 { print $c["mse"], $c["flip"] }' "$1"; }
near() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 0 && d <= 1e-5 * b) }'; }
set -- $(csv_mse "$T/so/s/summary.csv")
check "masked study: mse $1 is the cropped images' $(field mse "$T/c_pfm")" near "$1" "$(field mse "$T/c_pfm")"
"$WORKER" diff "$R.pfm" "$item.exr" --mask 5,3,17,15 >"$T/sm"
check "masked study: flip $2 is diff --mask's $(field flip "$T/sm")" near "$2" "$(field flip "$T/sm")"
check "the report outlines the mask" grep -q "inside the cyan outline" "$T/so/s/report.html"
check "the report shows FLIP maps" grep -q 'alt="jitter FLIP map"' "$T/so/s/report.html"
study "$T/s.yaml" ""
"$WORKER" --quiet --out "$T/so" "$T/s.yaml" >"$T/so2" 2>&1; rc=$?
set -- $(csv_mse "$T/so/s/summary.csv")
check "resumed without the mask: current, not rendered again ($rc: $(tail -n 1 "$T/so2"))" \
    eval '[ "$rc" -eq 0 ] && grep -q "1 of them current" "$T/so2"'
check "resumed without the mask: mse $1 is the whole image's $(field mse "$T/ra_f")" near "$1" "$(field mse "$T/ra_f")"

# 6. a bad mask in a study: file:line:col and key, exit 2, nothing written
for m in "rect: [5, 3, 25, 15]" "rect: [5, 3, 5, 15]" "rect: [5, 3, 17]" "image: $T/small.ppm" "image: $T/black.ppm"; do
    study "$T/b.yaml" ", mask: { $m }"
    "$WORKER" --quiet --out "$T/bdir" "$T/b.yaml" >/dev/null 2>"$T/be"; rc=$?
    check "mask: { $m }: exit 2, $T/b.yaml:8:col: mask: ... ($rc: $(cat "$T/be"))" \
        eval '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/be")" -eq 1 ] && grep -q "b.yaml:8:[0-9]*: mask: " "$T/be" && [ ! -e "$T/bdir" ]'
done
finish
