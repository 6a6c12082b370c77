"""Render cost of many lights (Blender background benchmark): the sphere-over-plane scene of the render test lit
by N = 4..256 baked suns at equal samples, against the world-lit render: render time and difference (8x8 block
means of the lit pixels, tests/blender/render_scene.py). Cycles 3.4 has no light tree, so more lamps add noise.

    BLENDER_USER_SCRIPTS=$(mktemp -d) blender -b --factory-startup -noaudio --python scripts/bench_render_counts.py \\
        -- [PROBE] [SAMPLES]
"""
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "blender"))
import render_scene  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
probe = argv[0] if argv else os.path.join(HERE, "..", "assets", "noon_grass_1k.hdr")
samples = int(argv[1]) if len(argv) > 1 else 256

bpy.ops.preferences.addon_install(filepath=os.path.join(HERE, "..", "build", "probe_lights.zip"), overwrite=True)
bpy.ops.preferences.addon_enable(module="probe_lights")
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
world = bpy.context.scene.world
env = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
env.image = bpy.data.images.load(probe)
world.node_tree.links.new(env.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
render_scene.sphere_over_plane(128, 96, samples)


def timed_render():
    t = time.perf_counter()
    pixels = render_scene.render()
    return pixels, time.perf_counter() - t


reference, ms = timed_render()
print("RENDER %s, %d spp, 128x96" % (os.path.basename(probe), samples))
print("RENDER world-lit: %.2f s" % ms)
bpy.context.scene.cycles.seed = 2
again, _ = timed_render()
print("RENDER noise floor (world vs world, other seed): %.2f %%" % (100 * render_scene.block_difference(reference, again)[0]))
bpy.context.scene.cycles.seed = 1
for n in (4, 8, 16, 32, 64, 128, 256):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
    pixels, seconds = timed_render()
    print("RENDER %3d suns: %.2f s, difference %.2f %%" % (n, seconds, 100 * render_scene.block_difference(reference, pixels)[0]))
