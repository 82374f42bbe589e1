#!/usr/bin/env python3
"""peers.py: the halves of `make bench-peers` (bench/peers.sh) that are not Blender's.

  peers.py scene SCENE.yaml OUT.json   our scene file as plain geometry for bench/peers_cycles.py:
                                       the camera's frame, each rect, box and disk as a mesh in
                                       world space, spheres, materials (the solid checker too);
                                       refuses what it cannot convert
  peers.py table RESULTS.tsv          the comparison table from the renders' figures

RESULTS.tsv: one line per render, "renderer<TAB>seed<TAB>cpu_s<TAB>image<TAB>samples", and one per
renderer and seed pair, "mse<TAB>renderer<TAB>mse" (worker diff's, in linear radiance).
"""
import json
import math
import struct
import sys

import yaml


def fail(msg):
    sys.stderr.write("peers.py: %s\n" % msg)
    sys.exit(2)


def vec(v, n=3):
    if not isinstance(v, list) or len(v) != n:
        fail("expected a list of %d numbers, got %r" % (n, v))
    return [float(x) for x in v]


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


# A rect's plane: the normal axis, then the in-plane axes its min/max run along (docs/scene-format.md).
PLANES = {"yz": (0, 1, 2), "xz": (1, 0, 2), "xy": (2, 0, 1)}


def rect_mesh(o):
    axis, ea, eb = PLANES[o["plane"]]
    (a0, b0), (a1, b1), k = vec(o["min"], 2), vec(o["max"], 2), float(o["at"])
    verts = []
    for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1)):
        p = [0.0, 0.0, 0.0]
        p[axis], p[ea], p[eb] = k, a, b
        verts.append(p)
    want = [0.0, 0.0, 0.0]
    want[axis] = -1.0 if o.get("flip") else 1.0  # the rect's front, where a light emits
    n = cross(sub(verts[1], verts[0]), sub(verts[2], verts[0]))
    face = [0, 1, 2, 3] if sum(x * y for x, y in zip(n, want)) > 0 else [3, 2, 1, 0]
    return verts, [face]


def transform(o, p):
    """rotate_y (degrees) then translate, as the renderer places an object (common/geom/shape_inline.h)."""
    t = math.radians(float(o.get("rotate_y", 0)))
    c, s = math.cos(t), math.sin(t)
    off = vec(o.get("translate", [0, 0, 0]))
    return [c * p[0] + s * p[2] + off[0], p[1] + off[1], -s * p[0] + c * p[2] + off[2]]


def box_mesh(o):
    lo, hi = vec(o["min"]), vec(o["max"])
    verts = [transform(o, [hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]])
             for i in range(8)]
    faces = [[0, 2, 6, 4], [1, 5, 7, 3], [0, 4, 5, 1], [2, 3, 7, 6], [0, 1, 3, 2], [4, 6, 7, 5]]
    return verts, faces


def disk_mesh(o, segments=256):
    """A disk as a polygon facing `toward`, its circumradius grown so that its area is the disk's
    (a light's power then matches)."""
    c, toward, r = vec(o["center"]), vec(o["toward"]), float(o["radius"])
    n = unit(sub(toward, c))
    a = unit(cross(n, [0.0, 1.0, 0.0] if abs(n[1]) < 0.9 else [1.0, 0.0, 0.0]))
    b = cross(n, a)  # (a, b, n) right-handed: counter-clockwise seen from the front
    step = 2 * math.pi / segments
    r *= math.sqrt(math.pi / (0.5 * segments * math.sin(step)))
    verts = [[c[k] + r * (math.cos(i * step) * a[k] + math.sin(i * step) * b[k]) for k in range(3)]
             for i in range(segments)]
    return verts, [list(range(segments))]


def scene(path, out):
    with open(path) as f:
        sc = yaml.safe_load(f)
    cam = sc["camera"]
    lookfrom, lookat, vup = vec(cam["lookfrom"]), vec(cam["lookat"]), vec(cam.get("vup", [0, 1, 0]))
    if float(cam.get("aperture", 0)) != 0:
        fail("camera: a thin lens (aperture > 0) is not converted")
    w = unit(sub(lookfrom, lookat))  # the renderer's frame (common/geom/camera.c): image right = u
    u = unit(cross(vup, w))
    v = cross(w, u)
    textures = {}
    for name, tx in (sc.get("textures") or {}).items():
        if tx.get("type") != "checker":
            fail("texture %s: %s is not converted" % (name, tx.get("type")))
        # the books' solid checker (common/geom/texture.c): odd where sin(s x) sin(s y) sin(s z) < 0
        textures[name] = {"odd": vec(tx["odd"]), "even": vec(tx["even"]), "scale": float(tx.get("scale", 10))}
    mats = {}
    for name, m in sc.get("materials", {}).items():
        t = m["type"]
        if t == "lambertian" and "albedo" in m:
            mats[name] = {"type": t, "albedo": vec(m["albedo"])}
        elif t == "lambertian" and m.get("texture") in textures:
            mats[name] = {"type": t, "checker": textures[m["texture"]]}
        elif t == "dielectric":
            mats[name] = {"type": t, "ior": float(m["ior"])}
        elif t == "light":
            mats[name] = {"type": t, "emit": vec(m["emit"])}
        else:
            fail("material %s: %s is not converted" % (name, t))
    objects = []
    for o in sc["objects"]:
        t = o["type"]
        if t == "rect" and not o.get("rotate_y") and not o.get("translate"):
            verts, faces = rect_mesh(o)
            objects.append({"mesh": verts, "faces": faces, "material": o["material"]})
        elif t == "box":
            verts, faces = box_mesh(o)
            objects.append({"mesh": verts, "faces": faces, "material": o["material"]})
        elif t == "disk":
            verts, faces = disk_mesh(o)
            objects.append({"mesh": verts, "faces": faces, "material": o["material"]})
        elif t == "sphere":
            objects.append({"sphere": transform(o, vec(o["center"])), "radius": float(o["radius"]),
                            "material": o["material"]})
        else:
            fail("object type %s is not converted" % t)
    doc = {"camera": {"origin": lookfrom, "u": u, "v": v, "w": w, "vfov": float(cam["vfov"])},
           "background": vec(sc.get("background", [0, 0, 0])), "materials": mats, "objects": objects}
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)


def pfm_mean(path):
    """The mean of an RGB PFM's values (linear radiance)."""
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    if parts[0].strip() != b"PF":
        fail("%s: not an RGB PFM" % path)
    w, h = (int(x) for x in parts[1].split())
    endian = "<" if float(parts[2]) < 0 else ">"
    vals = struct.unpack(endian + "%df" % (w * h * 3), parts[3][: w * h * 12])
    return math.fsum(vals) / len(vals)


def table(path):
    runs, mse = {}, {}
    order = []
    with open(path) as f:
        for line in f:
            p = line.rstrip("\n").split("\t")
            if p[0] == "mse":
                mse.setdefault(p[1], []).append(float(p[2]))
                continue
            name, seed, cpu_s, image, samples = p[0], p[1], float(p[2]), p[3], int(p[4])
            if name not in runs:
                runs[name] = []
                order.append(name)
            runs[name].append((seed, cpu_s, pfm_mean(image), samples))
    base = order[0]

    def figures(name):
        r = runs[name]
        s = sum(x[1] for x in r) / len(r)
        m = sum(mse[name]) / len(mse[name])
        return s, m, 1 / (m * s), sum(x[2] for x in r) / len(r)

    b_s, b_mse, b_eff, b_mean = figures(base)
    second_ns = 1e9 * figures(order[1])[0] / runs[order[1]][0][3] if len(order) > 1 else 0
    print("%-24s %7s %7s %11s %10s %8s %8s %8s %8s" % ("renderer", "ns/smp", "vs 2nd", "s/image", "MSE pairs", "mean",
                                                        "vs 1st", "eff", "eff/1st"))
    ok = True
    for name in order:
        s, m, eff, mean = figures(name)
        r = runs[name]
        ns = 1e9 * s / r[0][3]
        seeds = "%.2f-%.2f" % (min(x[1] for x in r), max(x[1] for x in r))
        dev = mean / b_mean - 1
        ok = ok and abs(dev) <= 0.03
        print("%-24s %7.0f %6.2fx %11s %10.3e %8.5f %+7.2f%% %8.1f %7.2fx" % (
            name, ns, ns / second_ns if second_ns else 0, seeds, m, mean, 100 * dev, eff, eff / b_eff))
    print("ns/smp: CPU seconds per image x 1e9 / camera samples (mean of the seeds); vs 2nd: against %s's;"
          % order[1] if len(order) > 1 else "")
    print("s/image: least-most CPU seconds of a seed's render; MSE pairs: mean over the seed pairs (1,2), (3,4), ...")
    print("of worker diff's mse between a pair's images (linear), each pair's in results.tsv; eff = 1 / (MSE pairs")
    print("x mean s/image); eff/1st: against %s's" % base)
    print("means within 3%% of %s's: %s" % (base, "yes" if ok else "NO"))
    return 0 if ok else 1


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "scene":
        scene(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "table":
        sys.exit(table(sys.argv[2]))
    else:
        fail("usage: peers.py scene SCENE.yaml OUT.json | peers.py table RESULTS.tsv")
