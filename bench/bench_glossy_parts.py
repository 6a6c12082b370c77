"""docs/results/glossy.md's split of the default bake's difference on glossy materials (issue 30): how much of it Cycles makes
of the world's own light split by ray visibility, with no lamps at all. The scene is bench_glossy.py's (Blender's
default Principled BSDF at roughness 0.2, 0.5 and 1.0, render_scene.glossy_spheres); for each probe it renders
  full  the world lit by every ray;                 noise  the same with another seed;
  D     the world seen by the camera and diffuse and volume rays (glossy and transmission off);
  G     the world seen by glossy and transmission rays only;
  split the add-on's default bake, LAMPS lamps (64 unless given; Lamps take: All of the light: lamps for diffuse
        light, the world's visibility left to reflections);
  L     the same lamps with the world hidden from every ray but the camera's: the lamps alone;
  Dm    the world and the default bake again with every material a plain diffuse BSDF (0.8): the bound diffuse
        materials give in this scene, which issue 30 holds glossy ones to;
and prints, each a third of the picture against its reference (render_scene.block_difference, %): noise; D + G
against full (what Cycles' own split of the world costs); the default bake against full; L + G against full (the
lamps and the world's reflections rendered apart); L against D (the lamps against the world's diffuse light); the
diffuse materials' default bake against their world.

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_glossy_parts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [NAME,NAME,... [SAMPLES [LAMPS]]]

(256 Cycles samples by default, 192x96 pixels, 4 bounces; NAME: probe file names without their extension, or "all")
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
harness.install_addon(zip_path)
SAMPLES = int(rest[1]) if len(rest) > 1 else 256
LAMPS = int(rest[2]) if len(rest) > 2 else 64
PROBES = harness.named_probes(harness.bench_probes(shared, studio_lights=False), rest[0] if rest else "")
RAYS = ("camera", "diffuse", "glossy", "transmission", "scatter")


def visible_to(world, *rays):
    for ray in RAYS:
        setattr(world.cycles_visibility, ray, ray in rays)


def with_materials(mats):
    """Gives every mesh the materials `mats` (object name -> material); returns the ones they had."""
    kept = {}
    for o in bpy.data.objects:
        if o.type == "MESH":
            kept[o.name] = o.data.materials[0]
            o.data.materials[0] = mats[o.name]
    return kept


def added(a, b):
    out = a.copy()
    out[..., :3] = a[..., :3] + b[..., :3]
    return out


print("| probe | noise (seed 2) | world split by visibility, D + G | default bake, %d lamps | lamps alone + G | "
      "lamps alone against D | diffuse materials, default bake |" % LAMPS)
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.glossy_probe_scene(probe, SAMPLES)
    world = scene.world
    full = render_scene.render()
    scene.cycles.seed = 2
    noise = render_scene.render()
    scene.cycles.seed = 1
    diffuse = render_scene.diffuse_material(0.8)
    principled = with_materials({o.name: diffuse for o in bpy.data.objects if o.type == "MESH"})
    full_diffuse = render_scene.render()
    with_materials(principled)
    visible_to(world, "camera", "diffuse", "scatter")
    d = render_scene.render()
    visible_to(world, "glossy", "transmission")
    g = render_scene.render()
    visible_to(world, *RAYS)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=LAMPS, lamps_take="ALL") == {"FINISHED"}
    split = render_scene.render()
    kept = {ray: getattr(world.cycles_visibility, ray) for ray in RAYS}
    visible_to(world, *[ray for ray in RAYS if kept[ray] and ray not in ("glossy", "transmission")])
    lamps = render_scene.render()
    visible_to(world, *[ray for ray in RAYS if kept[ray]])
    with_materials({name: diffuse for name in principled})
    split_diffuse = render_scene.render()
    with_materials(principled)
    diff = render_scene.thirds_difference
    print("| %s | %s | %s | %s | %s | %s | %s |" % (
        os.path.basename(probe), diff(full, noise), diff(full, added(d, g)), diff(full, split),
        diff(full, added(lamps, g)), diff(d, lamps), diff(full_diffuse, split_diffuse)),
        flush=True)
print("Blender %s, %d Cycles samples; each cell: roughness %s, %% from its reference" % (
    bpy.app.version_string, SAMPLES, " / ".join("%g" % r for r in render_scene.ROUGHNESS)))
sys.stdout.flush()
os._exit(0)  # as the other benches: bpy's teardown is not needed
