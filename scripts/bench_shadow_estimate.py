"""Does the estimate predict the render? The evaluator's shadow scene (a plane under a unit sphere, direct light;
render_scene.ground_under_sphere) rendered by Cycles lit by the world and by N baked suns, for each sun-angle
choice (points, spread, fit): the rendered relative RMS difference beside the add-on's estimate of it.

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python scripts/bench_shadow_estimate.py \\
        build/probe_lights.zip ../shared [PROBE] [SAMPLES]
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "blender"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, probe, samples = harness.bench_args(samples=1024)
harness.install_addon(zip_path)
harness.empty_scene()
harness.env_world(bpy.data.images.load(probe))
render_scene.ground_under_sphere(samples)
world = render_scene.render()
bpy.context.scene.cycles.seed = 2
floor = render_scene.relative_rms(world, render_scene.render())
bpy.context.scene.cycles.seed = 1
print("ESTIMATE Blender %s, %s, %d spp: noise floor %.2f %%" % (
    bpy.app.version_string, os.path.basename(probe), samples, 100 * floor))
settings = bpy.context.scene.probe_lights
for n in (8, 16, 64):
    for shadows in ("HARD", "SPREAD", "FIT"):
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n, shadows=shadows)
        lit = render_scene.render()
        rendered = render_scene.relative_rms(world, lit)
        bpy.context.scene.cycles.seed = 2
        noise = render_scene.relative_rms(lit, render_scene.render())  # two seeds: sqrt(2) x one render's noise
        bpy.context.scene.cycles.seed = 1
        print("ESTIMATE %3d suns %-6s: estimate %.2f %%, rendered %.2f %% (lamps' noise %.2f %%)" % (
            n, shadows, settings.last_shadow_error, 100 * rendered, 100 * noise), flush=True)
