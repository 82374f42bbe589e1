#!/bin/sh
# End to end: `--part I/N` + `merge` give the plain render's bytes for any N; merge refuses
# missing, mismatched, damaged or mixed parts (exit 2, nothing written); parts resume.
. tests/lib.sh
root=$(pwd)

job() { # job FILE [yaml lines...]: 24x17, so the parts have unequal row counts
    f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 24"; echo "height: 17"; echo "threshold: 40"
      echo "light_threshold: 50"; for l in "$@"; do echo "$l"; done; } >"$f"
}
total_samples() { # the samples total of a sidecar
    sed -n '/"samples": {/{n;s/.*"total": \([0-9]*\).*/\1/p;}' "$1"
}

job "$T/p.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/p.yaml" 2>/dev/null
check "plain render" [ -s "$T/plain/p/p.png" ]
plain_samples=$(total_samples "$T/plain/p/p.json")

# 1. parts over N = 1, 2, 3, 5 (each part with its own process count) merge to the same bytes
for n in 1 2 3 5; do
    i=0
    while [ "$i" -lt "$n" ]; do
        "$WORKER" --quiet --out "$T/o$n" --processes $((i % 3 + 1)) --part "$i/$n" "$T/p.yaml" 2>/dev/null
        check "N=$n: part $i written" [ -s "$T/o$n/p/p.part-$i-of-$n" ]
        i=$((i + 1))
    done
    check "N=$n: no image before the merge" [ ! -e "$T/o$n/p/p.png" ]
    "$WORKER" merge --out "$T/o$n" "$T/p.yaml" 2>"$T/m$n.log"; rc=$?
    check "N=$n: merge exits 0 (got $rc)" [ "$rc" -eq 0 ]
    check "N=$n: merged image == plain render" cmp -s "$T/plain/p/p.png" "$T/o$n/p/p.png"
    check "N=$n: sidecar records $n parts" grep -q "\"parts\": $n" "$T/o$n/p/p.json"
    check "N=$n: sidecar sums the samples ($plain_samples)" [ "$(total_samples "$T/o$n/p/p.json")" = "$plain_samples" ]
    check "N=$n: merge says so" grep -q "p: merged $n parts, 24x17" "$T/m$n.log"
done
check "N=5: one per_process entry per part" [ "$(grep -c '"pixels"' "$T/o5/p/p.json")" -eq 5 ]

refuse() { # refuse NAME OUT-DIR REGEX: merge exits 2 with the message and writes no image
    rm -f "$2/p/p.png" "$2/p/p.json"
    "$WORKER" merge --out "$2" "$T/p.yaml" 2>"$T/$1.err"; rc=$?
    check "$1: merge exits 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1: message matches '$3'" grep -Eq "$3" "$T/$1.err"
    check "$1: no image written" [ ! -e "$2/p/p.png" ]
    check "$1: no sidecar written" [ ! -e "$2/p/p.json" ]
}

# 2. a missing part
mkdir -p "$T/miss"; cp -r "$T/o5/p" "$T/miss/"
rm "$T/miss/p/p.part-1-of-5" "$T/miss/p/p.part-3-of-5"
refuse missing "$T/miss" "p.yaml: cannot merge: missing parts 1, 3 of 5 in .*/miss/p"
# 3. no parts at all
refuse none "$T/nothing" "p.yaml: no part files to merge"
# 4. a part rendered from a changed job file (another seed)
mkdir -p "$T/alt" "$T/mm"; job "$T/alt/p.yaml" "seed: 2"
cp -r "$T/o3/p" "$T/mm/"
"$WORKER" --quiet --out "$T/mm" --part 1/3 "$T/alt/p.yaml" 2>/dev/null
refuse mismatch "$T/mm" "p.part-1-of-3: rendered from other inputs"
# 5. parts of two splits side by side
mkdir -p "$T/mix"; cp -r "$T/o3/p" "$T/mix/"; cp "$T/o2/p/p.part-0-of-2" "$T/mix/p/"
refuse mixed "$T/mix" "parts of two splits in .* \\(of 2 and of 3\\)"
# 6. a damaged part (cut short; then one flipped byte)
mkdir -p "$T/cut"; cp -r "$T/o2/p" "$T/cut/"
head -c 500 "$T/o2/p/p.part-1-of-2" >"$T/cut/p/p.part-1-of-2"
refuse truncated "$T/cut" "p.part-1-of-2: damaged part file: 500 bytes, expected"
cp "$T/o2/p/p.part-1-of-2" "$T/cut/p/"
printf 'X' | dd of="$T/cut/p/p.part-1-of-2" bs=1 seek=700 conv=notrunc 2>/dev/null
refuse flipped "$T/cut" "p.part-1-of-2: damaged part file: checksum mismatch"
printf 'not a part' >"$T/cut/p/p.part-1-of-2"
refuse garbage "$T/cut" "p.part-1-of-2: not a worker part file"

# 7. bad --part values
for v in 3/3 1/0 -1/2 a/b 1/2x 1/257; do
    "$WORKER" --quiet --out "$T/bad" --part "$v" "$T/p.yaml" 2>"$T/badpart.err"; rc=$?
    check "--part $v: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "--part $v: says what it wants" grep -q "must be I/N" "$T/badpart.err"
done
check "bad --part: nothing written" [ ! -e "$T/bad" ]

# 8. a part that exists from the same inputs is skipped; --force renders it again
ino() { ls -i "$1" | cut -d' ' -f1; }
before=$(ino "$T/o3/p/p.part-2-of-3")
"$WORKER" --out "$T/o3" --part 2/3 "$T/p.yaml" 2>"$T/skip.err"; rc=$?
check "part resume: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "part resume: says skipped" grep -q "p: up to date (.*p.part-2-of-3, same job hash), skipped" "$T/skip.err"
check "part resume: file untouched" [ "$(ino "$T/o3/p/p.part-2-of-3")" = "$before" ]
"$WORKER" --quiet --force --out "$T/o3" --part 2/3 "$T/p.yaml" 2>/dev/null
check "part --force: rewritten" [ "$(ino "$T/o3/p/p.part-2-of-3")" != "$before" ]
"$WORKER" merge --out "$T/o3" "$T/p.yaml" 2>/dev/null
check "part --force: still merges to the plain render" cmp -s "$T/plain/p/p.png" "$T/o3/p/p.png"
# 9. a FIFO (or a directory) in place of a part: merge fails at once, naming it, instead of
#    blocking in open() for a writer that never comes
mkdir -p "$T/fifo"; cp -r "$T/o3/p" "$T/fifo/"
rm "$T/fifo/p/p.part-1-of-3" && mkfifo "$T/fifo/p/p.part-1-of-3"
rm -f "$T/fifo/p/p.png" "$T/fifo/p/p.json"
timeout 10 "$WORKER" merge --out "$T/fifo" "$T/p.yaml" 2>"$T/fifo.err"; rc=$?
check "fifo part: merge exits 2 at once (got $rc)" [ "$rc" -eq 2 ]
check "fifo part: names the file" grep -q "p.part-1-of-3: is a FIFO, not a regular file" "$T/fifo.err"
check "fifo part: no image written" [ ! -e "$T/fifo/p/p.png" ]
rm "$T/fifo/p/p.part-1-of-3" && mkdir "$T/fifo/p/p.part-1-of-3"
timeout 10 "$WORKER" merge --out "$T/fifo" "$T/p.yaml" 2>"$T/dir.err"; rc=$?
check "directory part: merge exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "directory part: names the file" grep -q "p.part-1-of-3: is a directory, not a regular file" "$T/dir.err"
finish
