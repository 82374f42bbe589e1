"""peers_cycles.py: run by Blender for `make bench-peers` (bench/peers.sh):

  blender -b --factory-startup -P bench/peers_cycles.py -- SCENE.json OUT_STEM SEED SPP WIDTH HEIGHT

builds the scene bench/peers.py converted from our scene file, renders it with Cycles on one CPU
thread with unbiased settings (box pixel filter 1 px wide, no adaptive sampling, no denoising, no
clamping, no light threshold, no glossy filter, caustics on), and writes OUT_STEM.exr (linear
float), OUT_STEM.pfm (the same values, for bench/peers.py's means) and OUT_STEM.tsv: the render's
CPU seconds and wall seconds, from the render call alone (no start-up, no scene building, no
saving)."""
import json
import math
import os
import struct
import sys
import time
from array import array

import bmesh
import bpy
from mathutils import Matrix


def checker(nt, c):
    """The books' solid checker as math nodes: odd where sin(s x) sin(s y) sin(s z) < 0, (x, y, z)
    the object coordinates (our world's: every mesh is built in world space at the origin)."""
    coords = nt.nodes.new("ShaderNodeTexCoord")
    xyz = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(coords.outputs["Object"], xyz.inputs[0])
    prod = None
    for k in range(3):
        scale = nt.nodes.new("ShaderNodeMath")
        scale.operation = "MULTIPLY"
        scale.inputs[1].default_value = c["scale"]
        nt.links.new(xyz.outputs[k], scale.inputs[0])
        sine = nt.nodes.new("ShaderNodeMath")
        sine.operation = "SINE"
        nt.links.new(scale.outputs[0], sine.inputs[0])
        if prod is None:
            prod = sine
        else:
            mul = nt.nodes.new("ShaderNodeMath")
            mul.operation = "MULTIPLY"
            nt.links.new(prod.outputs[0], mul.inputs[0])
            nt.links.new(sine.outputs[0], mul.inputs[1])
            prod = mul
    odd = nt.nodes.new("ShaderNodeMath")
    odd.operation = "LESS_THAN"
    odd.inputs[1].default_value = 0.0
    nt.links.new(prod.outputs[0], odd.inputs[0])
    mix = nt.nodes.new("ShaderNodeMixRGB")  # factor 1 (odd): Color2
    mix.inputs["Color1"].default_value = (*c["even"], 1)
    mix.inputs["Color2"].default_value = (*c["odd"], 1)
    nt.links.new(odd.outputs[0], mix.inputs["Fac"])
    return mix.outputs["Color"]


def material(name, m):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    if m["type"] == "lambertian":
        n = nt.nodes.new("ShaderNodeBsdfDiffuse")  # roughness 0: Lambert
        n.inputs["Roughness"].default_value = 0
        if "checker" in m:
            nt.links.new(checker(nt, m["checker"]), n.inputs["Color"])
        else:
            n.inputs["Color"].default_value = (*m["albedo"], 1)
        nt.links.new(n.outputs[0], out.inputs["Surface"])
    elif m["type"] == "dielectric":
        n = nt.nodes.new("ShaderNodeBsdfGlass")
        n.distribution = "SHARP"
        n.inputs["Color"].default_value = (1, 1, 1, 1)
        n.inputs["IOR"].default_value = m["ior"]
        nt.links.new(n.outputs[0], out.inputs["Surface"])
    else:  # a light: emits from its front face only, its back absorbs (as ours)
        peak = max(m["emit"])
        em = nt.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (*[c / peak for c in m["emit"]], 1)
        em.inputs["Strength"].default_value = peak
        dark = nt.nodes.new("ShaderNodeEmission")
        dark.inputs["Strength"].default_value = 0
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geo.outputs["Backfacing"], mix.inputs[0])
        nt.links.new(em.outputs[0], mix.inputs[1])
        nt.links.new(dark.outputs[0], mix.inputs[2])
        nt.links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def sphere(i, center, radius, mat):
    """A true sphere: one point of a point cloud (Cycles intersects it analytically)."""
    me = bpy.data.meshes.new("sphere%d" % i)
    me.from_pydata([center], [], [])
    ob = bpy.data.objects.new("sphere%d" % i, me)
    ng = bpy.data.node_groups.new("points%d" % i, "GeometryNodeTree")
    ng.inputs.new("NodeSocketGeometry", "Geometry")
    ng.outputs.new("NodeSocketGeometry", "Geometry")
    gin, gout = ng.nodes.new("NodeGroupInput"), ng.nodes.new("NodeGroupOutput")
    pts = ng.nodes.new("GeometryNodeMeshToPoints")
    pts.inputs["Radius"].default_value = radius
    setm = ng.nodes.new("GeometryNodeSetMaterial")
    setm.inputs["Material"].default_value = mat
    ng.links.new(gin.outputs[0], pts.inputs["Mesh"])
    ng.links.new(pts.outputs[0], setm.inputs["Geometry"])
    ng.links.new(setm.outputs[0], gout.inputs[0])
    ob.modifiers.new("points", "NODES").node_group = ng
    return ob


def sphere_mesh(i, center, radius, mat, segments=512, rings=256):
    """A sphere as a closed, smooth-shaded UV-sphere mesh (a glass Cycles point-cloud
    sphere showed no light refracted through it, as if a ray inside never hit it again)."""
    me = bpy.data.meshes.new("sphere%d" % i)
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings, radius=radius)
    bmesh.ops.translate(bm, verts=bm.verts, vec=center)
    for f in bm.faces:
        f.smooth = True
    bm.to_mesh(me)
    bm.free()
    me.materials.append(mat)
    return bpy.data.objects.new("sphere%d" % i, me)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    scene_json, stem = args[0], args[1]
    seed, spp, width, height = (int(x) for x in args[2:6])
    with open(scene_json) as f:
        d = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    mats = {name: material(name, m) for name, m in d["materials"].items()}
    for i, o in enumerate(d["objects"]):
        if "sphere" in o:
            make = sphere_mesh if os.environ.get("PEERS_SPHERE", "mesh") == "mesh" else sphere
            ob = make(i, o["sphere"], o["radius"], mats[o["material"]])
        else:
            me = bpy.data.meshes.new("mesh%d" % i)
            me.from_pydata(o["mesh"], [], o["faces"])
            me.materials.append(mats[o["material"]])
            ob = bpy.data.objects.new("mesh%d" % i, me)
        sc.collection.objects.link(ob)
    c = d["camera"]
    cam = bpy.data.cameras.new("camera")
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24
    cam.lens = 0.5 * cam.sensor_height / math.tan(math.radians(c["vfov"]) / 2)
    cam.clip_start, cam.clip_end = 1e-3, 1e6
    ob = bpy.data.objects.new("camera", cam)
    u, v, w, o = c["u"], c["v"], c["w"], c["origin"]  # Blender's camera looks down its -z, y up
    ob.matrix_world = Matrix(((u[0], v[0], w[0], o[0]), (u[1], v[1], w[1], o[1]), (u[2], v[2], w[2], o[2]),
                              (0, 0, 0, 1)))
    sc.collection.objects.link(ob)
    sc.camera = ob
    world = bpy.data.worlds.new("world")
    world.use_nodes = False
    world.color = d["background"]
    sc.world = world

    r, cy = sc.render, sc.cycles
    r.engine = "CYCLES"
    cy.device = "CPU"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.threads_mode, r.threads = "FIXED", 1
    r.film_transparent = False
    cy.samples = spp
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.pixel_filter_type, cy.filter_width = "BOX", 1.0
    cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = cy.transmission_bounces = 50
    cy.transparent_max_bounces = 50
    cy.volume_bounces = 0
    cy.min_light_bounces = cy.min_transparent_bounces = 0
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0
    cy.light_sampling_threshold = 0
    cy.blur_glossy = 0
    cy.caustics_reflective = cy.caustics_refractive = True
    cy.sampling_pattern = "SOBOL"  # Sobol-Burley in 3.4
    cy.seed, cy.use_animated_seed = seed, False
    sc.view_settings.view_transform = "Standard"
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGB"

    t_cpu, t_wall = time.process_time(), time.perf_counter()
    bpy.ops.render.render()
    cpu_s, wall_s = time.process_time() - t_cpu, time.perf_counter() - t_wall
    bpy.data.images["Render Result"].save_render(stem + ".exr")

    img = bpy.data.images.load(stem + ".exr")
    px = array("f", [0.0]) * (width * height * 4)
    img.pixels.foreach_get(px)
    rgb = array("f", (px[i] for i in range(len(px)) if i % 4 != 3))
    with open(stem + ".pfm", "wb") as f:  # rows bottom to top, as Blender holds them
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(struct.pack("<%df" % len(rgb), *rgb))
    with open(stem + ".tsv", "w") as f:
        f.write("%.6f\t%.6f\n" % (cpu_s, wall_s))


main()
