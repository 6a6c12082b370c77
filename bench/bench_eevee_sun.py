"""docs/results/eevee.md's table of one sun lamp in EEVEE against Cycles, by its elevation and angle: a sun of strength 1
over the diffuse sphere and plane (harness/render_scene.py, 160x120, a black world, direct light only; EEVEE 64
samples, Cycles 256), and each cell the EEVEE render's light over the Cycles render's (the sum over the object
pixels). With "noplane" the plane is hidden; with "noshadow" the sun casts none.

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_sun.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [noplane] [noshadow]
"""
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

ELEVATIONS = (80, 45, 10)
ANGLES = (0, 20, 30, 45, 60, 90, 120, 150, 180)

_, _, rest = harness.bench_argv()
harness.empty_scene()
world = bpy.data.worlds.new("black")
bpy.context.scene.world = world
harness.use_nodes(world)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
render_scene.sphere_over_plane(160, 120, 256)
scene = bpy.context.scene
scene.cycles.max_bounces = 0
scene.eevee.taa_render_samples = 64
if "noplane" in rest:
    bpy.data.objects["Plane"].hide_render = True
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
scene.collection.objects.link(sun)
sun.data.energy = 1.0
if "noshadow" in rest:
    sun.data.use_shadow = False
    if hasattr(sun.data, "cycles") and hasattr(sun.data.cycles, "cast_shadow"):
        sun.data.cycles.cast_shadow = False
eevee = harness.eevee_engine()

print("| sun's elevation | " + " | ".join("angle %d" % a for a in ANGLES) + " |")
print("|---" * (len(ANGLES) + 1) + "|")
for elevation in ELEVATIONS:
    sun.rotation_euler = (math.radians(90 - elevation), 0, math.radians(30))
    cells = []
    for angle in ANGLES:
        sun.data.angle = math.radians(angle)
        light = {}
        for engine in ("CYCLES", eevee):
            scene.render.engine = engine
            light[engine] = float((render_scene.render()[..., :3] @ render_scene.LUM).sum())
        cells.append("%.3f" % (light[eevee] / light["CYCLES"]))
    print("| %d degrees | %s |" % (elevation, " | ".join(cells)), flush=True)
print("Blender %s, EEVEE / Cycles light of one sun%s" % (
    bpy.app.version_string, "".join(", " + r for r in rest)))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
