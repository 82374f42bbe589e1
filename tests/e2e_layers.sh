#!/bin/sh
# e2e_layers: no two .c files call each other in a circle, no two modules (x.h + x.c) include or
# call each other in one, no folder does, and calls run down the
# layers cli -> study/farm -> job -> common/*, and inside study/ run -> present -> judge -> load
# (tests/check_layers.py over the built objects). The checker is shown to fail on a small bad tree
# first, so a pass means something.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${TEST_BIN_DIR:-$root/build/tests}/.." && pwd)
if ! command -v python3 >/dev/null 2>&1 || ! command -v nm >/dev/null 2>&1; then
    no "python3 and nm are needed (ci/run installs python3; nm comes with binutils)"
    finish
    exit
fi

# 1. a bad tree: job/a.c and farm/b.c call each other (a cycle, and job calling the farm), and
# common/base/c.c calls the program; a stale object (its source gone) is passed over
mkdir -p "$T/src/worker/job" "$T/src/worker/farm" "$T/src/common/base" "$T/b/worker/job" "$T/b/worker/farm" \
    "$T/b/common/base"
printf 'int farm_b(void);\nint job_a(void) { return farm_b(); }\n' >"$T/src/worker/job/a.c"
printf 'int job_a(void);\nint farm_b(void) { return job_a() + 1; }\n' >"$T/src/worker/farm/b.c"
printf 'int job_a(void);\nint base_c(void) { return job_a(); }\n' >"$T/src/common/base/c.c"
# and a study's judge calling its runner, which calls the judge back: a stage out of order, and a
# cycle between two stage folders
mkdir -p "$T/src/worker/study/judge" "$T/src/worker/study/run" "$T/b/worker/study/judge" "$T/b/worker/study/run"
printf 'int run_r(void);\nint judge_j(void) { return run_r(); }\n' >"$T/src/worker/study/judge/j.c"
printf 'int judge_j(void);\nint run_r(void) { return judge_j() + 1; }\n' >"$T/src/worker/study/run/r.c"
# and a circle only includes show: common/x/m.c calls n.c's function (through n.h), and n.h includes
# m.h back for a type; no two objects call each other, so nm alone sees no cycle
mkdir -p "$T/src/common/x" "$T/b/common/x"
printf '#ifndef M_H\n#define M_H\nstruct m_point { int x; };\nint m_f(void);\n#endif\n' >"$T/src/common/x/m.h"
printf '#ifndef N_H\n#define N_H\n#include "m.h"\nint n_g(struct m_point p);\n#endif\n' >"$T/src/common/x/n.h"
printf '#include "m.h"\n#include "n.h"\nint m_f(void) { struct m_point p = {1}; return n_g(p); }\n' >"$T/src/common/x/m.c"
printf '#include "n.h"\nint n_g(struct m_point p) { return p.x; }\n' >"$T/src/common/x/n.c"
# and two headers alone that include each other (no source, no call), under names whose circle the
# check once tolerated: any circle of modules fails, none is excused
mkdir -p "$T/src/common/geom"
printf '#ifndef SCENE_H\n#define SCENE_H\n#include "shape.h"\nstruct scene { int n; };\n#endif\n' >"$T/src/common/geom/scene.h"
printf '#ifndef SHAPE_H\n#define SHAPE_H\n#include "scene.h"\nstruct hit { int t; };\n#endif\n' >"$T/src/common/geom/shape.h"
for f in worker/job/a worker/farm/b common/base/c worker/study/judge/j worker/study/run/r common/x/m common/x/n; do
    ${CC:-cc} -c "$T/src/$f.c" -o "$T/b/$f.o" || no "cannot compile $f.c"
done
cp "$T/b/worker/job/a.o" "$T/b/worker/job/gone.o"
python3 "$root/tests/check_layers.py" "$T/b" "$T/src" >"$T/bad.out" 2>&1; rc=$?
check "a bad tree fails (got $rc)" [ "$rc" -eq 1 ]
check "a bad tree: the cycle named" grep -q '^cycle: worker/farm/b.c <-> worker/job/a.c' "$T/bad.out"
check "a bad tree: the symbols of the cycle named" grep -q 'worker/job/a.c -> worker/farm/b.c: farm_b' "$T/bad.out"
check "a bad tree: job calling the farm named" grep -q '^layer: worker/job/a.c -> worker/farm/b.c' "$T/bad.out"
check "a bad tree: common calling the program named" grep -q '^layer: common/base/c.c -> worker/job/a.c' "$T/bad.out"
check "a bad tree: the folders' cycle named" grep -q '^folder cycle: worker/farm <-> worker/job' "$T/bad.out"
check "a bad tree: the judge calling the runner named" grep -q '^layer: worker/study/judge/j.c -> worker/study/run/r.c' "$T/bad.out"
check "a bad tree: the stage folders' cycle named" grep -q '^folder cycle: worker/study/judge <-> worker/study/run' "$T/bad.out"
check "a bad tree: the include circle named" grep -q '^module cycle: common/x/m <-> common/x/n' "$T/bad.out"
check "a bad tree: the include that closes it named" grep -q 'common/x/n.h includes common/x/m.h' "$T/bad.out"
check "a bad tree: a circle of two headers named" grep -q '^module cycle: common/geom/scene <-> common/geom/shape' "$T/bad.out"
check "a bad tree: that header circle's includes named" grep -q 'common/geom/shape.h includes common/geom/scene.h' "$T/bad.out"
check "a bad tree: a stale object passed over" grep -q '7 files' "$T/bad.out"

# 2. the real build
python3 "$root/tests/check_layers.py" "$build" "$root" >"$T/real.out" 2>&1; rc=$?
check "the build has no cycles and keeps its layers (got $rc)" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || cat "$T/real.out" >&2
finish
