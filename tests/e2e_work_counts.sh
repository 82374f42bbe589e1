#!/bin/sh
# End to end (issue 35): every sidecar's work counts (camera samples, path segments, shadow rays,
# points and sets of the pixel, light and padded sets) are the same whatever the process count
# and split (--part + merge), and summary.csv carries each image's.
. tests/lib.sh
root=$(pwd)

job() { # job FILE SCENE [yaml lines...]: 23x17, so processes and parts get unequal row counts
    f=$1; s=$2; shift 2
    { echo "scene: $root/scenes/$s.yaml"; echo "width: 23"; echo "height: 17"; echo "seed: 7"
      for l in "$@"; do echo "$l"; done; } >"$f"
}
work() { # work SIDECAR: its "work" object, one line, keys sorted ("" when absent)
    python3 -c 'import json, sys; print(json.dumps(json.load(open(sys.argv[1])).get("work", ""), sort_keys=True))' "$1"
}

job "$T/nee.yaml" checker "threshold: 20" "light_threshold: 20" "integrator: nee" "sampler: poisson" \
    "light_sampler: jitter" "max_depth: 4"
job "$T/dims.yaml" checker "threshold: 25" "integrator: nee" "sampler_dims: all" "sampler: sobol" \
    "russian_roulette: on" "max_depth: 6"
job "$T/mix.yaml" cornell "threshold: 34" "light_threshold: 20" "light_sampler: poisson" "max_depth: 5"
for j in nee dims mix; do
    "$WORKER" --quiet --processes 1 --out "$T/p1" "$T/$j.yaml" 2>/dev/null
    "$WORKER" --quiet --processes 3 --out "$T/p3" "$T/$j.yaml" 2>/dev/null
    for i in 0 1; do
        "$WORKER" --quiet --processes $((i + 1)) --part "$i/2" --out "$T/parts" "$T/$j.yaml" 2>/dev/null
    done
    "$WORKER" merge --quiet --out "$T/parts" "$T/$j.yaml" 2>/dev/null
    one=$(work "$T/p1/$j/$j.json")
    check "$j: the sidecar has work counts ($one)" python3 -c '
import json, sys
w = json.loads(sys.argv[1])
keys = {"camera_samples", "path_segments", "shadow_rays", "pixel_points", "light_points", "padded_points",
        "pixel_sets", "light_sets", "padded_sets"}
assert set(w) == keys and w["camera_samples"] > 0 and w["path_segments"] >= w["camera_samples"]
assert w["pixel_sets"] == 23 * 17 and w["pixel_points"] == w["camera_samples"]' "$one"
    check "$j: 1 and 3 processes count alike" [ "$one" = "$(work "$T/p3/$j/$j.json")" ]
    check "$j: two parts merged count alike" [ "$one" = "$(work "$T/parts/$j/$j.json")" ]
    check "$j: same image either way" cmp -s "$T/p1/$j/$j.png" "$T/p3/$j/$j.png"
done
check "nee: shadow rays counted" python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["work"]; assert w["shadow_rays"] > 0 and w["padded_points"] == 0' "$T/p1/nee/nee.json"
check "dims: padded points and sets counted, no light points" python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["work"]; assert w["padded_points"] > 0 and w["padded_sets"] >= w["pixel_sets"] and w["light_points"] == 0' "$T/p1/dims/dims.json"
check "mix: light points in light sets, no shadow rays" python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["work"]; assert w["light_points"] > 0 and w["light_sets"] > 0 and w["shadow_rays"] == 0' "$T/p1/mix/mix.json"

# summary.csv: each image's counts as its sidecar's
cat >"$T/c.yaml" <<YAML
name: c
scenes: [$root/scenes/checker.yaml]
width: 16
height: 12
integrator: nee
seeds: [1, 2]
sweep: { threshold: [50, 25] }
variants:
  - { sampler: jitter, light_sampler: jitter }
  - { sampler: poisson, light_sampler: random }
YAML
"$WORKER" --quiet --processes 2 --out "$T/cmp" "$T/c.yaml" >/dev/null 2>&1
check "summary.csv: the work columns are the sidecars'" python3 - "$T/cmp/c" <<'PY'
import csv, json, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "summary.csv"))))
assert len(rows) == 8, len(rows)
for r in rows:
    w = json.load(open(os.path.join(d, r["image"][:-4] + ".json")))["work"]
    for k, v in w.items():
        assert int(r[k]) == v, (r["image"], k, r[k], v)
PY
cut -d, -f19-27 "$T/cmp/c/summary.csv" >"$T/first"
"$WORKER" --quiet --processes 1 --out "$T/cmp" "$T/c.yaml" >/dev/null 2>&1 # every image current: read back
check "summary.csv: images taken as current keep their counts" sh -c "cut -d, -f19-27 '$T/cmp/c/summary.csv' | cmp -s - '$T/first'"
finish
