#!/bin/sh
# Long (about two minutes, 2 GB of memory and disk), behind `make test-big`: a 10240x10240 job
# (1.05e8 pixels, over a decoder's 1e8 limit) rendered in 4 parts merges into one image whose
# sidecar sums the parts; --part resume sees the parts as current. 1 sample per pixel and one
# bounce keep it as cheap as such an image can be.
. tests/lib.sh
root=$(pwd)
printf 'scene: %s/scenes/checker.yaml\nwidth: 10240\nheight: 10240\nsampler: uniform\nthreshold: 100\nlight_sampler: uniform\nlight_threshold: 100\nmax_depth: 1\nprocesses: 2\n' \
    "$root" >"$T/big.yaml"
for i in 0 1 2 3; do
    "$WORKER" --quiet --out "$T/out" --part "$i/4" "$T/big.yaml" 2>"$T/part$i.log"; rc=$?
    check "part $i of 4: exit 0 (got $rc)" [ "$rc" -eq 0 ]
done
"$WORKER" --out "$T/out" --part 2/4 "$T/big.yaml" 2>"$T/resume.log"; rc=$?
check "resume: a part of over 1e8 pixels is current (got $rc)" [ "$rc" -eq 0 ] && grep -q "up to date\|skipped" "$T/resume.log"
"$WORKER" merge --out "$T/out" "$T/big.yaml" 2>"$T/merge.log"; rc=$?
cat "$T/merge.log"
check "merge: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "merge: the image is there" [ -s "$T/out/big/big.png" ]
check "merge: the sidecar says 10240x10240 from 4 parts" grep -q '"parts": 4' "$T/out/big/big.json"
check "merge: the PNG is 10240x10240" [ "$(od -An -tx1 -j16 -N8 "$T/out/big/big.png" | tr -d ' \n')" = 0000280000002800 ]
finish
