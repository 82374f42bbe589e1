#!/bin/sh
# e2e_docs: the docs stay true. (1) Every key the loaders accept, read from their C tables, is a
# row of its doc's reference table, and no row names a key they refuse; (2) every ```yaml block in
# README.md and docs/ loads and renders (tiny), or fails with its "# expect-error: TEXT"; (3) the
# pictures in docs/img/ are what `worker points` draws; (4) relative links and anchors resolve;
# README.md stays within 160 lines. Each check is also run on a broken copy, which it must refuse.
. tests/lib.sh
root=$(pwd)

# --- 1. keys: the loaders' tables, mechanically ------------------------------------------------

# "TABLE KEY" for every string in a `char *[const] NAME[] = {...}` table named *_keys or *_types
# (and compare_load.c's `extra`), and in a `#define NAME_KEYS "a", "b"` list; "TABLE @MACRO" where
# a table includes such a list.
cat >"$T/tables.awk" <<'EOF'
function emit(tab, text,   s) {
    s = text
    while (match(s, /"[^"]*"/)) { print tab, substr(s, RSTART + 1, RLENGTH - 2); s = substr(s, RSTART + RLENGTH) }
    s = text
    while (match(s, /[A-Z][A-Z_]*_KEYS/)) { print tab, "@" substr(s, RSTART, RLENGTH); s = substr(s, RSTART + RLENGTH) }
}
/^#define [A-Z][A-Z_]*_KEYS / { name = $2; sub(/^#define [A-Z_]+ /, ""); emit(name, $0); next }
intab { buf = buf " " $0; if ($0 ~ /};/) { emit(tab, buf); intab = 0 }; next }
/char \*(const )?[a-z_]+\[\] = \{/ {
    match($0, /[a-z_]+\[\] = \{/); n = substr($0, RSTART, RLENGTH); sub(/\[\].*/, "", n)
    if (n ~ /_keys$/ || n ~ /_types$/ || n == "extra") {
        rest = substr($0, RSTART + RLENGTH)
        if (rest ~ /};/) emit(n, rest); else { intab = 1; tab = n; buf = rest }
    }
}
EOF
loaders="worker/job/*.c common/scenefile/*.c worker/study/load/compare*.c"
awk -f "$T/tables.awk" $loaders >"$T/tables"
# a compare variant's extra key, the argument after "variant" in the key check's call:
# compare_keys_check(&L->d, var, "variant", "label", L->e)
grep -ho '"variant", "[a-z_]*"' $loaders | sed 's/.*, "\([a-z_]*\)"$/extra \1/' | sort -u >>"$T/tables"
# a render's keys, the rows of render_spec's table: {"width", RS_INT, ...}, (a job's own: job.c's job_keys)
sed -n 's/^ *{"\([a-z_]*\)", RS_[A-Z0-9]*,.*/job_keys \1/p' common/render/render_spec.c >>"$T/tables"
# object types and their tables: {"sphere", sphere_keys, load_sphere, 1},
sed -n 's/^ *{"\([a-z_]*\)", \([a-z_]*_keys\),.*/\1 \2/p' common/scenefile/*.c >"$T/objects"
awk '{print "object_types", $1}' "$T/objects" >>"$T/tables"

n_tables=$(cut -d' ' -f1 "$T/tables" | sort -u | wc -l)
n_keys=$(wc -l <"$T/tables")
check "the loaders' tables were found (got $n_tables tables, $n_keys entries)" \
    [ "$n_tables" -ge 20 -a "$n_keys" -ge 90 ]
for t in job_keys extra scene_keys camera_keys material_keys COMMON_KEYS object_types sphere_keys; do
    check "table $t read from the source" grep -q "^$t " "$T/tables"
done
check "a compare job's own keys read (scenes, variants, sweep, seeds; a variant's label)" \
    [ "$(grep -c '^extra ' "$T/tables")" -ge 5 ]
# every table a loader checks keys against (ymap_check's third argument) is one read above
for t in $(grep -ho 'ymap_check([^,]*, [^,]*, [a-z_]*_keys,' $loaders | sed 's/.*, \([a-z_]*_keys\),$/\1/' | sort -u); do
    check "ymap_check's table $t is read by this test" grep -q "^$t " "$T/tables"
done

# index.awk DOC...: "file S heading" for each heading, "file R heading key" for each table row
# | `key` | (heading: the nearest above), "file H ancestor name" for each heading `name` under
# every heading above it; tab-separated, code blocks skipped.
cat >"$T/index.awk" <<'EOF'
BEGIN { OFS = "\t" }
FNR == 1 { n = split(FILENAME, p, "/"); f = p[n]; depth = 0; fence = 0 }
/^```/ { fence = !fence; next }
fence { next }
/^#+ / {
    match($0, /^#+/); lvl = RLENGTH; text = substr($0, lvl + 2)
    while (depth > 0 && slvl[depth] >= lvl) depth--
    name = text
    if (text ~ /^`[^`]*`$/) name = substr(text, 2, length(text) - 2)
    for (i = 1; i <= depth; i++) print f, "H", stxt[i], name
    depth++; slvl[depth] = lvl; stxt[depth] = text
    print f, "S", text, ""
    next
}
depth && /^\| `[^`]*` \|/ { s = $0; sub(/^\| `/, "", s); sub(/`.*/, "", s); print f, "R", stxt[depth], s }
EOF

# The doc and heading each table is documented under: keys as rows | `key` | right under the
# heading; types as such rows or as headings `type` anywhere inside its section.
place() {
    case $1 in
    job_keys) echo "$1	job-format.md	Keys	keys" ;;
    extra) echo "$1	compare.md	Keys	keys" ;;
    suite_keys) echo "$1	compare.md	Suites	keys" ;;
    scene_keys) echo "$1	scene-format.md	Top level	keys" ;;
    material_keys) echo "$1	scene-format.md	Materials	keys" ;;
    material_types) echo "$1	scene-format.md	Materials	types" ;;
    COMMON_KEYS) echo "$1	scene-format.md	Every object	keys" ;;
    texture_types) echo "$1	scene-format.md	Textures	types" ;;
    object_types) echo "$1	scene-format.md	Objects	types" ;;
    *_keys) echo "$1	scene-format.md	\`${1%_keys}\`	keys" ;;
    *) echo "$1	?	?	?" ;;
    esac
}

# check.awk PLACES TABLES INDEX: one line per fault: a table with no place or heading, a key with
# no row, a row that names no key of its table (nor a material type; a compare doc may list job keys).
cat >"$T/check.awk" <<'EOF'
FILENAME == ARGV[1] { split($0, a, "\t"); pf[a[1]] = a[2]; ph[a[1]] = a[3]; pk[a[1]] = a[4]; next }
FILENAME == ARGV[2] { if ($2 !~ /^@/) { n[$1]++; key[$1, n[$1]] = $2; has[$1, $2] = 1 }; next }
{
    split($0, a, "\t")
    if (a[2] == "S") sec[a[1], a[3]] = 1
    if (a[2] == "R") { row[a[1], a[3], a[4]] = 1; nr[a[1], a[3]]++; rk[a[1], a[3], nr[a[1], a[3]]] = a[4] }
    if (a[2] == "H") head[a[1], a[3], a[4]] = 1
}
END {
    for (t in pf) {
        f = pf[t]; h = ph[t]
        if (f == "?") { print "table " t ": no doc place known (add it to place() in tests/e2e_docs.sh)"; continue }
        if (!((f, h) in sec)) { print f ": no heading \"" h "\" for " t; continue }
        for (i = 1; i <= n[t]; i++) {
            k = key[t, i]
            if (!((f, h, k) in row) && !(pk[t] == "types" && (f, h, k) in head))
                print f ": " k " (" t ") is not a row | `" k "` | under \"" h "\""
        }
        if (pk[t] != "keys") continue
        for (i = 1; i <= nr[f, h]; i++) {
            k = rk[f, h, i]
            if ((t, k) in has || (t == "material_keys" && ("material_types", k) in has) ||
                (t == "extra" && ("job_keys", k) in has)) continue
            print f ": row `" k "` under \"" h "\" is not a key the loader accepts (" t ")"
        }
    }
}
EOF

# check_keys DOCS: print one line per fault.
check_keys() {
    : >"$T/places"
    for t in $(cut -d' ' -f1 "$T/tables" | sort -u); do place "$t" >>"$T/places"; done
    awk -f "$T/index.awk" "$1"/*.md >"$T/index"
    awk -f "$T/check.awk" "$T/places" "$T/tables" "$T/index" | sort
}

check_keys "$root/docs" >"$T/keys.out"
check "every accepted key is documented, every documented key accepted: $(cat "$T/keys.out")" [ ! -s "$T/keys.out" ]
# ... and the check sees a key gone from its table and a key the loader does not have
mkdir -p "$T/bad1"
cp "$root"/docs/*.md "$T/bad1/"
sed -i '/^| `aperture` |/d; s/^| `focus_dist` |/| `focus_distance` |/' "$T/bad1/scene-format.md"
check_keys "$T/bad1" >"$T/bad1.out"
check "a key missing from scene-format.md is found" grep -q 'aperture (camera_keys)' "$T/bad1.out"
check "a documented key the loader refuses is found" grep -q 'row `focus_distance`' "$T/bad1.out"

# --- 2. every ```yaml block loads ---------------------------------------------------------------

# Blocks into DIR/NNN.yaml, with DIR/NNN.where = "file:line".
extract() { # extract DIR FILE...
    out=$1; shift
    mkdir -p "$out"
    awk -v out="$out" '
        /^```yaml[ \t]*$/ { n++; f = sprintf("%s/%03d", out, n); print FILENAME ":" FNR >(f ".where"); close(f ".where"); on = 1; next }
        on && /^```/ { on = 0; close(f ".yaml"); next }
        on { print >(f ".yaml") }
    ' "$@"
}

# one.sh BLOCK: run one block; print one line per fault. A job (scene: or scenes:) or compare job
# (variants:) runs as written but at 6x4 pixels and with one process, a suite (studies:) with
# the shipped study files it names (jobs/<path>) shrunk alike; a scene (camera:, objects:,
# materials: or textures: at the top) loads and renders through a tiny job beside it, a camera
# added when it has none. "# expect-error: TEXT" in a block: it must fail, exit 2, with TEXT on
# stderr. A block the same as an earlier one but for comments and blanks (README.md repeats a
# few) runs once.
cat >"$T/one.sh" <<'EOF_ONE'
y=$1 b=${1%.yaml}
where=$(cat "$b.where") w=$b.run
mkdir -p "$w"
ln -s "$root/scenes" "$w/scenes"
expect=$(sed -n 's/^# expect-error: //p' "$y" | head -n 1)
top=$(sed -n 's/^\([a-z_]*\):.*/\1/p' "$y")
if echo "$top" | grep -qx studies; then
    # a suite: the study files it names are the shipped ones (the block read as jobs/compare.yaml
    # is), copied beside it at 6x4 pixels
    cp "$y" "$w/job.yaml"
    for p in $(sed -n 's/^studies: *\[\(.*\)\].*/\1/p' "$y" | tr ',' ' '); do
        [ -f "$root/jobs/$p" ] || continue
        mkdir -p "$w/$(dirname "$p")"
        { grep -vE '^(width|height):' "$root/jobs/$p"; printf 'width: 6\nheight: 4\n'; } >"$w/$p"
    done
elif echo "$top" | grep -qxE 'variants|scenes?'; then
    if [ -n "$expect" ]; then cp "$y" "$w/job.yaml"; else
        grep -vE '^(width|height):' "$y" >"$w/job.yaml"
        printf 'width: 6\nheight: 4\n' >>"$w/job.yaml"
    fi
elif echo "$top" | grep -qxE 'camera|objects|materials|textures'; then
    ln -s "$root/scenes/textures" "$w/textures"
    { echo "$top" | grep -qx camera ||
        echo 'camera: { lookfrom: [0, 2, -12], lookat: [0, 1, 0], vfov: 40 }'; cat "$y"; } >"$w/scene.yaml"
    printf 'name: doc\nscene: scene.yaml\nwidth: 6\nheight: 4\nthreshold: 50\nlight_threshold: 50\n' >"$w/job.yaml"
else
    echo "$where: a yaml block that is neither a job nor a scene (top-level keys: $(echo $top))"
    exit 0
fi
(cd "$w" && "$WORKER" --quiet --processes 1 --out out job.yaml) >"$w/stdout" 2>"$w/stderr"
rc=$?
if [ -n "$expect" ]; then
    [ "$rc" -eq 2 ] && grep -qF -- "$expect" "$w/stderr" ||
        echo "$where: expected exit 2 and \"$expect\", got exit $rc: $(head -c 300 "$w/stderr")"
elif [ "$rc" -ne 0 ]; then
    echo "$where: exit $rc: $(head -c 300 "$w/stderr")"
elif [ -z "$(find "$w/out" -name '*.png' 2>/dev/null | head -n 1)" ]; then
    echo "$where: exit 0 but no image under --out"
fi
EOF_ONE
export WORKER root

# check_examples DIR: every block there, two at a time; one line per fault.
check_examples() {
    for y in "$1"/*.yaml; do
        [ -f "$y" ] || continue
        sed '/^# expect-error: /!s/ *#.*//; /^ *$/d' "$y" >"${y%.yaml}.norm"
        for o in "$1"/*.norm; do
            [ "$o" = "${y%.yaml}.norm" ] && break
            cmp -s "$o" "${y%.yaml}.norm" && { rm "$y"; break; }
        done
    done
    ls "$1"/*.yaml 2>/dev/null | xargs -r -n 1 -P 2 sh "$T/one.sh" | sort
}

extract "$T/ex" "$root/README.md" "$root"/docs/*.md
n_ex=$(ls "$T/ex"/*.yaml 2>/dev/null | wc -l)
check "yaml examples found in README.md and docs/ (got $n_ex)" [ "$n_ex" -ge 20 ]
check "expect-error examples found" [ "$(cat "$T/ex"/*.yaml | grep -c '^# expect-error: ')" -ge 3 ]
check_examples "$T/ex" >"$T/ex.out"
check "every yaml example loads, or fails as it says: $(cat "$T/ex.out")" [ ! -s "$T/ex.out" ]
# ... and the check sees a broken example, a wrong expected error and an unclassifiable block
cat >"$T/bad2.md" <<'EOF'
```yaml
materials:
  white: { type: lambertian, albedo: [0.73, 0.73, 0.73] }
objects:
  - { type: sphere, center: [0, 1, 0], radius: 1, material: whte }
```

```yaml
# expect-error: threshold: must be a number in (0, 10]
scene: checker
threshold: abc
```

```yaml
sweep: { threshold: [20, 10] }
```

```yaml
name: s
studies: [studies/none.yaml]
```
EOF
extract "$T/ex2" "$T/bad2.md"
check_examples "$T/ex2" >"$T/ex2.out"
check "a broken example is found" grep -q 'bad2.md:1: exit 2: .*material: no material named "whte"' "$T/ex2.out"
check "a wrong expected error is found" grep -q 'bad2.md:8: expected exit 2' "$T/ex2.out"
check "a block that is not a job or scene is found" grep -q 'bad2.md:14: a yaml block that is neither' "$T/ex2.out"
check "a suite naming a study file that is not there is found" grep -q 'bad2.md:18: exit 2: .*no study file at studies/none.yaml' "$T/ex2.out"

# --- 3. the pictures: docs/img/SAMPLER-tT.svg is `worker points SAMPLER T --seed 1 --svg F` ---------
n_img=0
for f in "$root"/docs/img/*-t*.svg; do
    [ -f "$f" ] || continue
    n_img=$((n_img + 1))
    s=$(basename "$f" .svg)
    "$WORKER" points "${s%-t*}" "${s##*-t}" --seed 1 --svg "$T/pic.svg" >/dev/null 2>&1
    check "docs/img/$s.svg is what worker points ${s%-t*} ${s##*-t} --seed 1 --svg draws" cmp -s "$f" "$T/pic.svg"
done
check "samplers.md has pictures (got $n_img)" [ "$n_img" -ge 4 ]

# --- 4. links and length ------------------------------------------------------------------------

# check_links FILE...: every relative link's file exists, and its #anchor is a heading there
# (GitHub's slugs: lower case, punctuation dropped, spaces to '-').
check_links() {
    for md in "$@"; do
        dir=$(dirname "$md")
        grep -o '](\([^)#]*\)\(#[^)]*\)\?)' "$md" | sed 's/^](//; s/)$//' | while read -r l; do
            case $l in http://* | https://* | mailto:*) continue ;; esac
            file=${l%%#*} anchor=
            case $l in *'#'*) anchor=${l#*#} ;; esac
            target=$md
            [ -n "$file" ] && target=$dir/$file
            [ -e "$target" ] || { echo "$md: link to $l: no such file"; continue; }
            [ -z "$anchor" ] && continue
            grep '^#' "$target" | sed 's/^#* //' | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9 _-]//g; s/ /-/g' |
                grep -qxF -- "$anchor" || echo "$md: link to $l: no heading #$anchor there"
        done
    done
}
check_links "$root/README.md" "$root"/docs/*.md >"$T/links.out"
check "links resolve: $(cat "$T/links.out")" [ ! -s "$T/links.out" ]
printf '[a](nowhere.md) [b](%s#no-such-heading)\n' "$root/docs/job-format.md" >"$T/bad3.md"
check_links "$T/bad3.md" >"$T/links3.out"
check "a broken link and a broken anchor are found" [ "$(wc -l <"$T/links3.out")" -eq 2 ]
lines=$(wc -l <"$root/README.md")
check "README.md is at most 160 lines (got $lines)" [ "$lines" -le 160 ]
# --- 5. a compare job's scene stem limit: the one docs/job-format.md states is the one refused ---
mkdir -p "$T/stems"
long=$(printf 'a%.0s' $(seq 1 64))
cp "$root/scenes/checker.yaml" "$T/stems/$long.yaml"
printf 'name: st\nscenes: [%s/stems/%s.yaml]\nwidth: 4\nheight: 4\nvariants: [{ sampler: jitter, threshold: 50 }]\n' \
    "$T" "$long" >"$T/stems.yaml"
limit=$("$WORKER" --dry-run "$T/stems.yaml" 2>&1 | sed -n 's/.*its stem is [0-9]* bytes, over the \([0-9]*\) .*/\1/p')
check "job-format.md states the scene stem limit the worker keeps ($limit bytes)" \
    grep -q "a scene file whose stem is over $limit bytes is refused" "$root/docs/job-format.md"
finish
