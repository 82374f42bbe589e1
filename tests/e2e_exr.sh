#!/bin/sh
# End to end: float images. format: exr / pfm (and their extensions) write the linear framebuffer,
# the same bytes for any process count or part split, read by OpenEXR's own tools when present;
# the PFM's floats are the EXR's; a float reference scores in linear radiance (relmse checked
# against python3 reading the two PFMs), an 8-bit one with a warning; worker diff reads all four
# formats, --json, --map.
. tests/lib.sh
root=$(pwd)

job() { # job FILE NAME [yaml lines...]: cornell (a light and its reflections clip in 8 bits), 24x20
    f=$1; n=$2; shift 2
    { echo "name: $n"; echo "scene: $root/scenes/cornell.yaml"; echo "width: 24"; echo "height: 20"
      echo "light_threshold: 50"; for l in "$@"; do echo "$l"; done; } >"$f"
}

# 1. format: exr and format: pfm, the same render as format: png
job "$T/e.yaml" e "threshold: 25" "format: exr"
job "$T/p.yaml" p "threshold: 25" "format: pfm"
job "$T/g.yaml" g "threshold: 25"
"$WORKER" --quiet --out "$T/o" "$T/e.yaml" "$T/p.yaml" "$T/g.yaml" 2>"$T/e1"; rc=$?
check "exr, pfm, png jobs: exit 0 (got $rc: $(cat "$T/e1"))" [ "$rc" -eq 0 ]
check "format: exr writes e.exr and its sidecar" eval '[ -s "$T/o/e/e.exr" ] && [ -s "$T/o/e/e.json" ]'
check "format: pfm writes p.pfm" [ -s "$T/o/p/p.pfm" ]
check "the EXR starts with OpenEXR's magic number" [ "$(head -c 4 "$T/o/e/e.exr" | od -An -tx1 | tr -d ' ')" = "762f3101" ]
check "the PFM's header: PF, 24 20, -1.0 (little-endian)" [ "$(head -c 14 "$T/o/p/p.pfm" | tr '\n' ' ')" = "PF 24 20 -1.0 " ]
check "the PFM holds 24 x 20 x 3 floats" [ "$(wc -c <"$T/o/p/p.pfm")" -eq $((14 + 24 * 20 * 12)) ]
if command -v exrheader >/dev/null; then
    exrheader "$T/o/e/e.exr" >"$T/hdr" 2>&1; rc=$?
    check "exrheader reads it (exit $rc)" [ "$rc" -eq 0 ]
    check "exrheader: zip, float R G B, 24x20, the job's name and sampler" sh -c "
        grep -q 'compression.*zip' '$T/hdr' && [ \$(grep -c '32-bit floating-point' '$T/hdr') -eq 3 ] &&
        grep -q 'dataWindow.*(0 0) - (23 19)' '$T/hdr' && grep -q 'job (type string): \"e\"' '$T/hdr' &&
        grep -q 'sampler (type string): \"random t=25\"' '$T/hdr'"
else
    echo "exrheader not installed (Debian: openexr): OpenEXR's own reading of the file not checked"
fi
if command -v exrcheck >/dev/null; then
    exrcheck "$T/o/e/e.exr" >"$T/chk" 2>&1; rc=$?
    check "exrcheck passes (exit $rc: $(tail -n 1 "$T/chk"))" [ "$rc" -eq 0 ]
fi
"$WORKER" diff "$T/o/e/e.exr" "$T/o/p/p.pfm" --json >"$T/d1" 2>&1
check "the PFM's floats are the EXR's ($(cat "$T/d1"))" grep -q '"mse": 0, "rmse": 0, "relmse": 0, .*"domain": "linear"' "$T/d1"
"$WORKER" diff "$T/o/g/g.png" "$T/o/e/e.exr" --json >"$T/d2" 2>"$T/d2.err"
check "the PNG is the EXR's floats in 8 bits ($(cat "$T/d2"))" grep -q '"mse": 0, .*"domain": "8-bit"' "$T/d2"
check "diff PNG against EXR warns in one line that it measures 8-bit values" \
    sh -c "[ \$(wc -l <'$T/d2.err') -eq 1 ] && grep -q '8-bit display values' '$T/d2.err'"

# 2. the bytes do not depend on the process count, nor on a --part split merged (EXR and PFM)
for f in e p; do
    ext=$([ $f = e ] && echo exr || echo pfm)
    "$WORKER" --quiet --force --out "$T/o1" --processes 1 "$T/$f.yaml" 2>/dev/null
    "$WORKER" --quiet --force --out "$T/o3" --processes 3 "$T/$f.yaml" 2>/dev/null
    check "$ext: one process and three write the same bytes" cmp -s "$T/o1/$f/$f.$ext" "$T/o3/$f/$f.$ext"
    check "$ext: and the first render's" cmp -s "$T/o1/$f/$f.$ext" "$T/o/$f/$f.$ext"
    for i in 0 1; do "$WORKER" --quiet --out "$T/parts" --part "$i/2" "$T/$f.yaml" 2>/dev/null; done
    "$WORKER" merge --out "$T/parts" "$T/$f.yaml" 2>/dev/null; rc=$?
    check "$ext: merge of two parts (exit $rc) gives the same bytes" cmp -s "$T/parts/$f/$f.$ext" "$T/o/$f/$f.$ext"
done
job "$T/x.yaml" x "threshold: 50" "output: x.exr"
"$WORKER" --quiet --out "$T/o" "$T/x.yaml" 2>/dev/null
check "output: x.exr without format: is an EXR" [ "$(head -c 4 "$T/o/x/x.exr" | od -An -tx1 | tr -d ' ')" = "762f3101" ]
job "$T/bad.yaml" bad "threshold: 50" "format: exr" "output: bad.pfm"
"$WORKER" --quiet --out "$T/o" "$T/bad.yaml" 2>"$T/e2"; rc=$?
check "format: exr against output: bad.pfm: exit 2, at format: ($(cat "$T/e2"))" \
    sh -c "[ $rc -eq 2 ] && grep -q '^$T/bad.yaml:7:9: format: exr contradicts' '$T/e2'"

# 3. a float reference: the sidecar's error is in linear radiance, and equals relMSE computed
#    here from the two PFMs (python3 reading them by hand)
job "$T/ref.yaml" ref "threshold: 5" "format: pfm" "seed: 7"
"$WORKER" --quiet --out "$T/o" "$T/ref.yaml" 2>/dev/null
cp "$T/o/ref/ref.pfm" "$T/ref.pfm"
job "$T/s.yaml" s "threshold: 25" "format: pfm" "reference: $T/ref.pfm"
"$WORKER" --quiet --out "$T/o" "$T/s.yaml" 2>"$T/e3"; rc=$?
check "scored against a PFM: exit 0, no warning (got $rc: $(cat "$T/e3"))" sh -c "[ $rc -eq 0 ] && [ \$(wc -l <'$T/e3') -eq 1 ]"
check "its sidecar: domain linear, relmse_robust" sh -c "grep -q '\"domain\": \"linear\"' '$T/o/s/s.json' && grep -q '\"relmse_robust\": [0-9]' '$T/o/s/s.json'"
if command -v python3 >/dev/null; then
    python3 - "$T/ref.pfm" "$T/o/s/s.pfm" "$T/o/s/s.json" >"$T/py" 2>&1 <<'PY'
import json, struct, sys
def pfm(path):
    d = open(path, 'rb').read()
    head = d.split(b'\n', 3)
    w, h = map(int, head[1].split())
    assert head[0] == b'PF' and float(head[2]) < 0
    return struct.unpack('<%df' % (w * h * 3), head[3])
r, v = pfm(sys.argv[1]), pfm(sys.argv[2])
terms = [(b - a) ** 2 / (a * a + 0.01) for a, b in zip(r, v)]
rel = sum(terms) / len(terms)
mse = sum((b - a) ** 2 for a, b in zip(r, v)) / len(r)
err = json.load(open(sys.argv[3]))['error']
ok = abs(err['relmse'] - rel) <= 1e-6 * rel and abs(err['mse'] - mse) <= 1e-6 * mse
print('relmse %.10g here, %.10g in the sidecar; mse %.10g, %.10g' % (rel, err['relmse'], mse, err['mse']))
sys.exit(0 if ok and err['domain'] == 'linear' else 1)
PY
    rc=$?
    check "sidecar relmse and mse = python3's from the two PFMs to 1e-6 relative ($(cat "$T/py"))" [ "$rc" -eq 0 ]
else
    echo "python3 not installed: the independent relMSE not computed"
fi

# 4. worker diff ref.exr img.exr --json: one JSON object with the figures and the domain
job "$T/re.yaml" re "threshold: 5" "format: exr" "seed: 7"
"$WORKER" --quiet --out "$T/o" "$T/re.yaml" 2>/dev/null
"$WORKER" diff "$T/o/re/re.exr" "$T/o/e/e.exr" --json >"$T/d4" 2>"$T/d4.err"; rc=$?
check "diff --json of two EXRs: exit 0, nothing on stderr (got $rc)" sh -c "[ $rc -eq 0 ] && [ ! -s '$T/d4.err' ]"
check "diff --json: one line" [ "$(wc -l <"$T/d4")" -eq 1 ]
for k in mse rmse relmse relmse_robust psnr; do
    check "diff --json has $k" grep -q "\"$k\": [0-9]" "$T/d4"
done
check "diff --json: domain linear" grep -q '"domain": "linear"' "$T/d4"
if command -v python3 >/dev/null; then
    check "diff --json parses as JSON, relmse_robust <= relmse" python3 -c "
import json, sys
d = json.load(open('$T/d4'))
sys.exit(0 if d['relmse_robust'] <= d['relmse'] and d['domain'] == 'linear' else 1)"
fi
"$WORKER" diff "$T/o/re/re.exr" "$T/o/e/e.exr" >"$T/d5"
check "diff prints the domain it measured in" grep -qx 'domain linear' "$T/d5"
"$WORKER" diff "$T/o/re/re.exr" "$T/o/e/e.exr" --map "$T/map.png" >/dev/null 2>&1; rc=$?
check "diff --map: exit 0, a PNG (got $rc)" sh -c "[ $rc -eq 0 ] && [ \"\$(head -c 4 '$T/map.png' | tail -c 3)\" = PNG ]"
check "diff --map: its scale in a tEXt chunk" grep -q 'worker:scale' "$T/map.png"
check "diff --map: a PNG worker reads, the image's size" sh -c "'$WORKER' diff '$T/map.png' '$T/map.png' >/dev/null"

# 5. an 8-bit reference: a one-line warning, the error named 8-bit
cp "$T/o/g/g.png" "$T/ref8.png"
job "$T/s8.yaml" s8 "threshold: 25" "reference: $T/ref8.png"
"$WORKER" --out "$T/o" "$T/s8.yaml" 2>"$T/e5"; rc=$?
check "PNG reference: exit 0, the warning and the summary line ($(cat "$T/e5"))" \
    sh -c "[ $rc -eq 0 ] && [ \$(wc -l <'$T/e5') -eq 2 ] && grep -q '^s8: warning: .*8-bit display values' '$T/e5'"
check "PNG reference: the sidecar's domain is 8-bit" grep -q '"domain": "8-bit"' "$T/o/s8/s8.json"

# 6. malformed float files are refused: exit 2, one line naming the file, nothing written
printf 'v/1\001garbage' >"$T/broken.exr"
printf 'PF\n2 2\n-1.0\n\000\000' >"$T/short.pfm"
for bad in broken.exr short.pfm; do
    job "$T/m.yaml" m "threshold: 50" "reference: $T/$bad"
    rm -rf "$T/om"
    "$WORKER" --quiet --out "$T/om" "$T/m.yaml" 2>"$T/e6"; rc=$?
    check "reference $bad: exit 2, one line at reference: ($(cat "$T/e6"))" \
        sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/e6') -eq 1 ] && grep -q '^$T/m.yaml:7:12: reference: ' '$T/e6'"
    check "reference $bad: nothing written" [ ! -e "$T/om" ]
    "$WORKER" diff "$T/$bad" "$T/o/e/e.exr" >/dev/null 2>"$T/e6"; rc=$?
    check "diff $bad: exit 2, one line naming it" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/e6') -eq 1 ] && grep -q '$bad' '$T/e6'"
done

# 7. a float reference of the right size holding a NaN is refused before rendering, at its key
python3 -c "
import sys
b = open(sys.argv[1], 'rb').read()
k = 0
for _ in range(3):
    k = b.index(b'\\n', k) + 1
open(sys.argv[2], 'wb').write(b[:k] + bytes.fromhex('0000c07f') + b[k + 4:])
" "$T/ref.pfm" "$T/nan.pfm"
job "$T/n.yaml" n "threshold: 25" "format: pfm" "reference: $T/nan.pfm"
rm -rf "$T/on"
"$WORKER" --quiet --out "$T/on" "$T/n.yaml" 2>"$T/e7"; rc=$?
check "NaN reference: exit 2, one line at reference: ($(cat "$T/e7"))" \
    sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/e7') -eq 1 ] && grep -q '^$T/n.yaml:8:12: reference: .*1 of its .* values are NaN or infinite' '$T/e7'"
check "NaN reference: nothing written" [ ! -e "$T/on" ]
finish
