"""One-click bake time in Blender: 64 suns from the bundled probe at 1K and resized to 2K and 4K.

  oiiotool assets/noon_grass_1k.hdr --resize 2048x1024 -o /tmp/noon_2k.exr
  oiiotool assets/noon_grass_1k.hdr --resize 4096x2048 -o /tmp/noon_4k.exr
  BLENDER_USER_SCRIPTS=$(mktemp -d) blender -b --factory-startup -noaudio --python scripts/bench_blender.py
"""
import os
import time

import bpy

bpy.ops.preferences.addon_install(filepath=os.path.join(os.path.dirname(__file__), "..", "build", "probe_lights.zip"), overwrite=True)
bpy.ops.preferences.addon_enable(module="probe_lights")
for path in (p for p in (os.path.join(os.path.dirname(__file__), "..", "assets", "noon_grass_1k.hdr"), "/tmp/noon_2k.exr", "/tmp/noon_4k.exr") if os.path.exists(p)):
    img = bpy.data.images.load(path)
    img.pixels[0]  # load the file (reading it is not part of a bake)
    w = bpy.context.scene.world; nt = w.node_tree
    env = nt.nodes.get("env") or nt.nodes.new("ShaderNodeTexEnvironment"); env.name = "env"; env.image = img
    nt.links.new(env.outputs["Color"], nt.nodes["Background"].inputs["Color"])
    for i in range(3):
        t = time.perf_counter()
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64)
        print("TIMING %s %dx%d: bake 64 suns %.0f ms (add-on says %.0f ms)" % (os.path.basename(path), img.size[0], img.size[1], 1000 * (time.perf_counter() - t), bpy.context.scene.probe_lights.last_ms))
