"""Does the estimate predict the render? The evaluator's shadow scene (a plane under a unit sphere, direct light;
render_scene.ground_under_sphere) rendered by Cycles lit by the world and by 16 and 64 baked suns, for each
shadow choice (Hard: points; Region spread: the angle before issue 9; Fitted; Fitted with the refit): the rendered
relative RMS difference beside the add-on's estimate of it, the renders' noise, and the difference with both
renders' noise taken out (docs/results/shadows.md; for every probe: bench/bench_shadow_table.sh).

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_shadow_estimate.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBE] [SAMPLES]

PROBELIGHTS_METHOD=both bakes with that method (default: the panel's default, auto).
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, probe, samples = harness.bench_args(samples=4096 if bpy.app.version >= (4, 0, 0) else 16384)
harness.install_addon(zip_path)
harness.empty_scene()
world_data = harness.env_world(bpy.data.images.load(probe))
world_data.node_tree.nodes["Environment Texture"].interpolation = "Closest"  # the truth: the probe's pixels
render_scene.ground_under_sphere(samples)
world = render_scene.render()
bpy.context.scene.cycles.seed = 2
floor = render_scene.relative_rms(world, render_scene.render()) / 2 ** 0.5
bpy.context.scene.cycles.seed = 1
print("ESTIMATE Blender %s, %s, %d spp: world noise %.2f %%" % (
    bpy.app.version_string, os.path.basename(probe), samples, 100 * floor))
settings = bpy.context.scene.probe_lights
# PROBELIGHTS_SHADOW_CHOICES="FIT,FIT+refit" renders only those choices (default: all four).
CHOICES = (("HARD", False), ("SPREAD", False), ("FIT", False), ("FIT", True))
wanted = os.environ.get("PROBELIGHTS_SHADOW_CHOICES")
if wanted:
    CHOICES = [c for c in CHOICES if c[0] + ("+refit" if c[1] else "") in wanted.split(",")]
for n in (16, 64):
    for shadows, refit in CHOICES:
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n, shadows=shadows, refit=refit,
                                  method=os.environ.get("PROBELIGHTS_METHOD", "auto"))
        lit = render_scene.render()
        rendered = render_scene.relative_rms(world, lit)
        bpy.context.scene.cycles.seed = 2
        noise = render_scene.relative_rms(lit, render_scene.render()) / 2 ** 0.5
        bpy.context.scene.cycles.seed = 1
        # Both renders' noise taken out (independent noise adds in squares): what the lights alone differ by.
        clean = max(0.0, rendered ** 2 - floor ** 2 - noise ** 2) ** 0.5
        print("ESTIMATE %3d suns %-6s%s: estimate %.2f %%, rendered %.2f %% (lamps' noise %.2f %%; less both "
              "noises %.2f %%)" % (n, shadows, " refit" if refit else "      ", settings.last_shadow_error,
                                   100 * rendered, 100 * noise, 100 * clean), flush=True)
