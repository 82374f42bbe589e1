#!/usr/bin/env python3
"""check_layers: the file-level call graph of the built objects, from `nm` (a file calls another
when it leaves undefined a symbol the other defines). Fails, naming files and symbols, on any cycle
between .c files, any cycle between folders (each folder a layer), any circle of modules read from
includes and calls (a module is a header and its source, x.h + x.c: render.c including a header
that includes render.h back is a circle that nm cannot see), and any call against the
layering cli -> study/farm -> job -> common/*, and inside worker/study/ run -> present -> judge ->
load.

Usage: check_layers.py BUILD_DIR [SOURCE_DIR]   (objects under BUILD_DIR/common and BUILD_DIR/worker;
an object whose source is no longer in SOURCE_DIR, default ".", is a stale one: passed over)
"""
import os
import re
import subprocess
import sys

# (caller folder prefix, callee folder prefixes it may not call, why)
FORBIDDEN = [
    ("worker/job/", ("worker/farm/", "worker/study/", "worker/cli/"), "one job knows no farm, study or command line"),
    ("worker/farm/", ("worker/cli/",), "the farm is called by the command line, never calls it"),
    ("worker/study/", ("worker/cli/",), "the study is called by the command line, never calls it"),
    # worker/study/'s stages, bottom up: load (the model and its reading) < judge (the verdict) <
    # present (report, charts, verdict.json) < run (renders, and drives the others)
    ("worker/study/load/", ("worker/study/judge/", "worker/study/present/", "worker/study/run/"),
     "the loader builds the model: it calls nothing above it"),
    ("worker/study/judge/", ("worker/study/present/", "worker/study/run/"),
     "the judge reads a study's figures: it neither presents nor runs"),
    ("worker/study/present/", ("worker/study/run/",), "the presentation shows a study: it never runs one"),
    ("common/", ("worker/",), "common/ is a library: it knows nothing of the program"),
]


def objects(build, source):
    for top in ("common", "worker"):
        for root, _, files in os.walk(os.path.join(build, top)):
            for f in sorted(files):
                if f.endswith(".o"):
                    path = os.path.join(root, f)
                    src = os.path.relpath(path, build)[: -len(".o")] + ".c"
                    if os.path.exists(os.path.join(source, src)):
                        yield src, path


def symbols(path):
    """(defined, undefined) external symbols of one object."""
    out = subprocess.run(["nm", "-P", path], check=True, capture_output=True, text=True).stdout
    defined, undefined = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        name, kind = parts[0], parts[1]
        if kind == "U":
            undefined.add(name)
        elif kind.isupper() and kind not in ("W", "V"):
            defined.add(name)
    return defined, undefined


def graph(build, source="."):
    files = dict(objects(build, source))
    if not files:
        sys.exit(f"check_layers: no objects under {build}/common or {build}/worker: build first")
    syms = {src: symbols(obj) for src, obj in files.items()}
    owner = {}
    for src, (defined, _) in syms.items():
        for s in defined:
            owner[s] = src
    edges = {src: {} for src in files}  # caller -> callee -> symbols
    for src, (_, undefined) in syms.items():
        for s in undefined:
            to = owner.get(s)
            if to and to != src:
                edges[src].setdefault(to, set()).add(s)
    return edges


def module(path):
    return os.path.splitext(path)[0]


def includes(source):
    """module -> module -> "file includes x.h" for every #include "..." of common/ and worker/ that
    resolves beside the file or under common/ or worker/ (-Icommon -Iworker)."""
    out = {}
    for top in ("common", "worker"):
        for root, _, files in os.walk(os.path.join(source, top)):
            for f in sorted(files):
                if not f.endswith((".c", ".h")):
                    continue
                path = os.path.join(root, f)
                rel = os.path.relpath(path, source)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    for line in fh:
                        m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                        if not m:
                            continue
                        for base in (os.path.dirname(rel), "common", "worker"):
                            target = os.path.normpath(os.path.join(base, m.group(1)))
                            if os.path.exists(os.path.join(source, target)):
                                a, b = module(rel), module(target)
                                if a != b:
                                    out.setdefault(a, {}).setdefault(b, set()).add(f"{rel} includes {target}")
                                break
    return out


def module_graph(edges, source):
    """Modules joined by includes and by calls (a file's calls are its module's)."""
    graph = includes(source)
    for a in edges:
        for b in edges[a]:
            if module(a) != module(b):
                why = f"{a} calls {b} ({', '.join(sorted(edges[a][b])[:2])})"
                graph.setdefault(module(a), {}).setdefault(module(b), set()).add(why)
    for a in list(graph):
        for b in graph[a]:
            graph.setdefault(b, {})
    return graph


def cycles(edges):
    """Strongly connected components of more than one file (Tarjan, iterative)."""
    index, low, on, stack, out, n = {}, {}, set(), [], [], 0
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = n
        n += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = n
                    n += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    edges = graph(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else ".")
    bad = 0
    for comp in cycles(edges):
        bad += 1
        print("cycle: " + " <-> ".join(comp))
        for a in comp:
            for b in comp:
                if b in edges[a]:
                    print(f"  {a} -> {b}: {', '.join(sorted(edges[a][b]))}")
    mods = module_graph(edges, sys.argv[2] if len(sys.argv) == 3 else ".")
    for comp in cycles(mods):
        if any(set(comp) <= set(map(module, x)) for x in cycles(edges)):
            continue  # a cycle of .c files, named above
        bad += 1
        print("module cycle: " + " <-> ".join(comp))
        for a in comp:
            for b in comp:
                for why in sorted(mods[a].get(b, ()))[:2]:
                    print(f"  {why}")
    folders = {}
    for a in edges:
        for b in edges[a]:
            if os.path.dirname(a) != os.path.dirname(b):
                folders.setdefault(os.path.dirname(a), {}).setdefault(os.path.dirname(b), set()).add(f"{a} -> {b}")
    for comp in cycles({f: folders.get(f, {}) for f in {os.path.dirname(a) for a in edges}}):
        bad += 1
        print("folder cycle: " + " <-> ".join(comp))
        for a in comp:
            for b in comp:
                calls = sorted(folders.get(a, {}).get(b, ()))
                if calls:  # the few calls against the grain are the ones to read
                    more = f" and {len(calls) - 3} more" if len(calls) > 3 else ""
                    print(f"  {a} -> {b}: {', '.join(calls[:3])}{more}")
    for a in sorted(edges):
        for b in sorted(edges[a]):
            for caller, callees, why in FORBIDDEN:
                if a.startswith(caller) and b.startswith(callees):
                    bad += 1
                    print(f"layer: {a} -> {b} ({', '.join(sorted(edges[a][b]))}): {why}")
    calls = sum(len(v) for v in edges.values())
    print(f"check_layers: {len(edges)} files, {calls} file-to-file calls, {bad} problem(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
