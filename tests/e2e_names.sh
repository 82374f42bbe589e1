#!/bin/sh
# Names with terminal escapes, control bytes and bytes that are no UTF-8 (issue 36): every name a
# terminal shows goes through the one sanitiser (as \xNN), chart.svg stays well-formed XML,
# report.html holds no raw control byte, summary.csv keeps the name's bytes (quoted), verdict.json
# stays JSON: a compare run, `worker verdict` (also on a forged summary.csv) and `worker status`.
. tests/lib.sh
root=$(pwd)
ln -s "$root/scenes" "$T/scenes"
# a scene file named with ESC, BEL, ^A, the C1 CSI U+009B and XML's < &
stem=$(printf 'a\033[31mr<&\007\001\302\233z')
cp scenes/checker.yaml "$T/$stem.yaml"
cat >"$T/esc.yaml" <<'YAML'
name: esc
scenes: ["a\e[31mr<&\a\x01\u009bz.yaml"]
width: 4
reference: { sampler: jitter, threshold: 10 }
seeds: [1, 2]
sweep: { threshold: [25, 20] }
variants:
  - { label: jit, sampler: jitter }
  - { label: rnd, sampler: random }
YAML
raw() { # raw FILE: 0 when FILE holds a control byte other than tab, LF, CR (ESC, BEL, ^A, DEL, C1)
    python3 - "$1" <<'PY'
import sys
d = open(sys.argv[1], 'rb').read()
bad = [b for b in d if (b < 32 and b not in (9, 10, 13)) or b == 127]
bad += [1 for i in range(len(d) - 1) if d[i] == 0xc2 and 0x80 <= d[i + 1] <= 0x9f]
sys.exit(0 if bad else 1)
PY
}
(cd "$T" && "$WORKER" --out out esc.yaml >run.out 2>run.err); rc=$?
check "a scene named with escapes: exit 0 (got $rc: $(tail -n 1 "$T/run.err"))" [ "$rc" -eq 0 ]
check "the run's terminal output holds no control byte: $(grep -a 'at equal CPU' "$T/run.err")" eval '! raw "$T/run.err" && ! raw "$T/run.out"'
check "... and shows the name escaped" grep -q 'esc: a\\x1b\[31mr<&\\x07\\x01\\xc2\\x9bz inconclusive' "$T/run.err"
check "chart.svg is well-formed XML" python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])' "$T/out/esc/chart.svg"
check "report.html holds no raw control byte and is UTF-8" eval '! raw "$T/out/esc/report.html" &&
    python3 -c "open(\"$T/out/esc/report.html\", \"rb\").read().decode(\"utf-8\")"'
check "report.html shows the name escaped" grep -q 'a\\x1b\[31mr&lt;&amp;\\x07\\x01\\xc2\\x9bz' "$T/out/esc/report.html"
check "summary.csv keeps the scene's name whole (its bytes)" python3 - "$T/out/esc/summary.csv" "$stem" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline='', encoding='utf-8')))
assert all(r[0] == sys.argv[2] for r in rows[1:]), rows[1]
PY
check "verdict.json is JSON with the name" python3 - "$T/out/esc/verdict.json" "$stem" <<'PY'
import json, sys
assert json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]['scene'] == sys.argv[2]
PY
"$WORKER" verdict "$T/out/esc" >"$T/v.out" 2>"$T/v.err"; rc=$?
check "worker verdict: exit 0 (got $rc), no control byte shown" eval '[ "$rc" -eq 0 ] && ! raw "$T/v.out" && ! raw "$T/v.err"'
check "worker verdict: the name escaped" grep -q '^esc: a\\x1b\[31mr<&\\x07\\x01\\xc2\\x9bz: ' "$T/v.out"

# a forged summary.csv: variants named with ESC, OSC and a byte that is no UTF-8
cp -r "$T/out/esc" "$T/forged"
python3 - "$T/forged/summary.csv" <<'PY'
import sys
p = sys.argv[1]
d = open(p, 'rb').read()
d = d.replace(b',jit,', b',j\x1b]0;pwn\x07it,').replace(b',rnd,', b',r\xffn\x1b[2Jd,')
open(p, 'wb').write(d)
PY
"$WORKER" verdict "$T/forged" >"$T/f.out" 2>"$T/f.err"; rc=$?
check "forged names: exit 0 (got $rc: $(tail -n 1 "$T/f.err")), no control byte shown" eval \
    '[ "$rc" -eq 0 ] && ! raw "$T/f.out" && ! raw "$T/f.err"'
check "forged names: shown escaped" eval 'grep -q "r\\\\xffn\\\\x1b\\[2Jd" "$T/f.out" "$T/f.err"'
"$WORKER" verdict "$T/forged" --json >"$T/f.json" 2>/dev/null
check "forged names: --json is JSON" python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$T/f.json"

# worker status: job files and study folders named with escapes, in every list
Q=$T/q
mkdir -p "$Q/done" "$Q/failed" "$Q/spread/$(printf 's\033]0;x\007')"
touch "$Q/spread/$(printf 's\033]0;x\007')/study.job" "$Q/done/$(printf 'd\033[2J\377\001').yaml" \
    "$Q/failed/$(printf 'f\033[1m').yaml"
echo "scene: checker" >"$Q/$(printf 'w\033[5m').yaml"
"$WORKER" status "$Q" >"$T/s.out" 2>"$T/s.err"; rc=$?
check "status: exit 0 (got $rc: $(cat "$T/s.err"))" [ "$rc" -eq 0 ]
check "status: no control byte shown: $(tr -d '\033\007' <"$T/s.out" | tr '\n' '|')" eval '! raw "$T/s.out" && ! raw "$T/s.err"'
check "status: done:, studies:, failed: and waiting show the names escaped" eval \
    'grep -q "d\\\\x1b\\[2J\\\\xff\\\\x01.yaml" "$T/s.out" && grep -q "study s\\\\x1b\\]0;x\\\\x07" "$T/s.out" &&
     grep -q "f\\\\x1b\\[1m.yaml" "$T/s.out" && grep -q "w\\\\x1b\\[5m.yaml" "$T/s.out"'
finish
