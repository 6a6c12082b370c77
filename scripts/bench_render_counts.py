"""Render cost of many lights, per Blender version: the sphere-over-plane scene of the render test lit by
N = 4..256 baked suns at equal samples, against the world-lit render: render time and difference (8x8 block means
of the lit pixels, tests/blender/render_scene.py). Cycles 3.4 picks lamps nearly uniformly (no light tree), so
there more lamps add noise; 4.x and 5.x pick them through a light tree. Run it in each Blender the tests cover:

    tests/blender/run.sh blender scripts/bench_render_counts.py build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBE] [SAMPLES]
    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python scripts/bench_render_counts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared
"""
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "blender"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, probe, samples = harness.bench_args()

harness.install_addon(zip_path)
harness.empty_scene()
harness.env_world(bpy.data.images.load(probe))
render_scene.sphere_over_plane(128, 96, samples)


def timed_render():
    t = time.perf_counter()
    pixels = render_scene.render()
    return pixels, time.perf_counter() - t


reference, seconds = timed_render()
print("RENDER Blender %s, %s, %d spp, 128x96" % (bpy.app.version_string, os.path.basename(probe), samples))
print("RENDER world-lit: %.2f s" % seconds)
bpy.context.scene.cycles.seed = 2
again, _ = timed_render()
print("RENDER noise floor (world vs world, other seed): %.2f %%" % (
    100 * render_scene.block_difference(reference, again)[0]))
bpy.context.scene.cycles.seed = 1
for n in (4, 8, 16, 32, 64, 128, 256):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
    pixels, seconds = timed_render()
    print("RENDER %3d suns: %.2f s, difference %.2f %%" % (
        n, seconds, 100 * render_scene.block_difference(reference, pixels)[0]), flush=True)
