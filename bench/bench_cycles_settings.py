"""What Cycles' default settings do to baked lamps, per Blender version: the sphere-over-plane scene of the render
test (bounce light included, 4 bounces) lit by the world (unclamped: the reference) and by N baked suns, with
Cycles' default indirect clamp and with the settings the add-on offers (clamp 0, light tree where there is one).
Prints the mean brightness of the lit pixels relative to the world's and the 8x8-block difference:

    tests/blender/run.sh blender bench/bench_cycles_settings.py build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBE] [SAMPLES]

With PROBELIGHTS_BENCH_WRITE=addon/probe_lights/cycles_clamp.json it also puts this version's and probe's darkening
under the default clamp at 64 suns into that file (written whole: a temporary file renamed over it), the data the
add-on's advice on Cycles' settings reads (cycles_settings.py).
"""
import datetime
import json
import os
import re
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, probe, samples = harness.bench_args()

harness.install_addon(zip_path)
harness.empty_scene()
harness.env_world(bpy.data.images.load(probe))
render_scene.sphere_over_plane(128, 96, samples)
scene = bpy.context.scene
default_clamp = scene.cycles.bl_rna.properties["sample_clamp_indirect"].default


def brightness(reference, pixels):
    lit = (reference[..., 3] > 0.999) & (reference[..., :3] @ render_scene.LUM > 0)
    return float((pixels[lit, :3] @ render_scene.LUM).mean() / (reference[lit, :3] @ render_scene.LUM).mean())


reference = render_scene.render()
print("CYCLES Blender %s, %s, %d spp, 128x96, default indirect clamp %g" % (
    bpy.app.version_string, os.path.basename(probe), samples, default_clamp))
scene.cycles.sample_clamp_indirect = default_clamp
world_default = render_scene.render()
print("CYCLES world, default clamp: brightness %.4f, difference %.2f %%" % (
    brightness(reference, world_default), 100 * render_scene.block_difference(reference, world_default)[0]))
for n in (16, 64):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
    scene.cycles.sample_clamp_indirect = default_clamp
    if hasattr(scene.cycles, "use_light_tree"):
        scene.cycles.use_light_tree = scene.cycles.bl_rna.properties["use_light_tree"].default
    plain = render_scene.render()
    if n == 64:
        darkening = max(0.0, 100 * (1 - brightness(reference, plain)))
    assert bpy.ops.probe_lights.cycles_settings() == {"FINISHED"}
    offered = render_scene.render()
    for name, pixels in (("default settings", plain), ("offered settings", offered)):
        print("CYCLES %3d suns, %s: brightness %.4f, difference %.2f %%" % (
            n, name, brightness(reference, pixels), 100 * render_scene.block_difference(reference, pixels)[0]),
            flush=True)
    bpy.ops.probe_lights.restore()

# Noise at a low sample count: the difference between two renders that differ only in their seed, over sqrt(2).
scene.cycles.samples = 64
for n in (0, 16, 64):
    if n:
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
        bpy.ops.probe_lights.cycles_settings()
    scene.cycles.seed = 1
    a = render_scene.render()
    scene.cycles.seed = 2
    b = render_scene.render()
    print("CYCLES noise at 64 spp, %s: %.1f %%" % ("%d suns" % n if n else "world", 100 * render_scene.block_difference(a, b)[0] / 2 ** 0.5), flush=True)
    if n:
        bpy.ops.probe_lights.restore()
if hasattr(scene.cycles, "use_light_tree"):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64)
    bpy.ops.probe_lights.cycles_settings()
    scene.cycles.use_light_tree = False
    scene.cycles.seed = 1
    a = render_scene.render()
    scene.cycles.seed = 2
    b = render_scene.render()
    print("CYCLES noise at 64 spp, 64 suns, light tree off: %.1f %%" % (
        100 * render_scene.block_difference(a, b)[0] / 2 ** 0.5), flush=True)

target = os.environ.get("PROBELIGHTS_BENCH_WRITE")
if target:
    with open(target, encoding="utf-8") as f:
        data = json.load(f)
    name = re.sub(r"_\d+k$", "", os.path.splitext(os.path.basename(probe))[0])
    version = "%d.%d.%d" % bpy.app.version
    data["versions"].setdefault(version, {})[name] = {
        "darkening": round(darkening, 1), "measured": "%s, %d samples" % (datetime.date.today(), samples)}
    partial = target + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(json.dumps(data, indent=1) + "\n")
    os.replace(partial, target)
    print("CYCLES wrote Blender %s, %s into %s" % (version, name, target))
