"""docs/results/glossy.md's table: glossy materials lit by the add-on's lamps against the world, in Cycles, on the bundled
probe and every ../shared probe. The scene is render_scene.glossy_spheres: Blender's default Principled BSDF at
roughness 0.2, 0.5 and 1.0, one sphere over its own ground each, side by side; each third of the picture is
compared with the world's render (render_scene.block_difference: 8x8 blocks of lit pixels, mean
|lamps - world| / world of their luminance). Rows: the world against itself with another seed (the renders'
noise), the default split (Lamps take: All of the light; the world keeps reflections) at 16 and 64 lamps, the same
64 lamps with the world's reflections routed as the add-on did before (a mix on Light Path's Is Glossy Ray and Is
Camera Ray, the world's ray visibility left on), and the lamps of the bright sources with the residual world at
16 and 64.

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_glossy.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [SAMPLES]

(256 Cycles samples by default, 192x96 pixels, 4 bounces)
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
samples = int(rest[0]) if rest else 256
harness.install_addon(zip_path)
PROBES = harness.bench_probes(shared, studio_lights=False)
ROWS = (("ALL", 16), ("ALL", 64), ("BEFORE", 64), ("SOURCES", 16), ("SOURCES", 64))


def route_by_light_path(world):
    """The default bake's world as the add-on made it before: the mix shows the original to camera and glossy rays
    and the black Background to the others; the ray visibility is not used."""
    tree = world.node_tree
    mix = next(n for n in tree.nodes if n.get("probe_lights_mix"))
    path = tree.nodes.new("ShaderNodeLightPath")
    top = tree.nodes.new("ShaderNodeMath")
    top.operation = "MAXIMUM"
    tree.links.new(path.outputs["Is Camera Ray"], top.inputs[0])
    tree.links.new(path.outputs["Is Glossy Ray"], top.inputs[1])
    tree.links.new(top.outputs[0], mix.inputs["Fac"])
    for ray in ("diffuse", "transmission", "scatter"):
        setattr(world.cycles_visibility, ray, True)


print("| probe | noise (seed 2) | all of the light, 16 | all, 64 | all, 64, Is Glossy Ray (before) | "
      "bright sources + residual, 16 | sources, 64 |")
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.glossy_probe_scene(probe, samples)
    reference = render_scene.render()
    scene.cycles.seed = 2
    cells = [render_scene.thirds_difference(reference, render_scene.render())]
    scene.cycles.seed = 1
    for take, n in ROWS:
        assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n, lamps_take=take.replace("BEFORE", "ALL")) == {
            "FINISHED"}
        if take == "BEFORE":
            route_by_light_path(scene.world)
        cells.append(render_scene.thirds_difference(reference, render_scene.render()))
    print("| %s | %s |" % (os.path.basename(probe), " | ".join(cells)), flush=True)
print("Blender %s, %d Cycles samples; each cell: roughness %s, %% from the world's render" % (
    bpy.app.version_string, samples, " / ".join("%g" % r for r in render_scene.ROUGHNESS)))
sys.stdout.flush()
os._exit(0)  # as the other benches: bpy's teardown is not needed
