#!/bin/sh
# e2e_queue_copy: files a copier or an editor writes beside a job (dotfiles, *.tmp, *.part,
# *.yaml~, #x.yaml#, .#x.yaml, swap files) are never claimed; an empty X.yaml just created (a copy
# about to be written) is left for a later scan; a claimed file that does not parse (a copy cut
# short, an empty file left for good) is filed in failed/ with its file:line:col in the log.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
Q=$T/q; mkdir -p "$Q"
for n in .a.yaml a.yaml.tmp a.yaml.part a.yaml~ '#a.yaml#' '.#a.yaml' a.yaml.swp .a.yaml.swp .a.yaml.XYZ123 a.yaml.filepart; do
    printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$root" >"$Q/$n"
done
: >"$Q/fresh.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log"; rc=$?
check "nothing to claim: exit 0 (got $rc: $(cat "$T/log"))" [ "$rc" -eq 0 ]
check "no copier's file claimed" [ -z "$(find "$Q/running" "$Q/done" "$Q/failed" -mindepth 1)" ]
check "the empty file just created is left where it is" [ -f "$Q/fresh.yaml" ]
# a copy cut short, and an empty file left for good (older than the grace)
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: [50' "$root" >"$Q/cut.yaml"
touch -d '1 minute ago' "$Q/fresh.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log"; rc=$?
check "invalid jobs: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "the cut copy is in failed/" [ -f "$Q/failed/cut.yaml" ]
check "its log gives file:line:col: $(cat "$Q/failed/cut.log" 2>/dev/null)" grep -q "^error: $Q/cut.yaml:[0-9]*:[0-9]*: " "$Q/failed/cut.log"
check "the old empty file is in failed/" [ -f "$Q/failed/fresh.yaml" ]
check "its log says it is empty" grep -q "fresh.yaml:1:1: empty file" "$Q/failed/fresh.log"
check "the copier's files are still not claimed" [ "$(ls -A "$Q" | grep -c .)" -eq 13 ]
finish
