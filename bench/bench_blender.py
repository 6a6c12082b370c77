"""One-click bake time in Blender: 64 suns from the bundled probe at 1K and resized to 2K, 4K and 8K, in any Blender
the tests cover (the add-on installed from the zip as the tests do), with the click's stages (read the image's
pixels, bake with the estimate, make the lamps); PROBELIGHTS_BENCH_REFIT=1 times the clicks with Refit on:

  oiiotool assets/noon_grass_1k.hdr --resize 2048x1024 -o /tmp/noon_2k.exr
  oiiotool assets/noon_grass_1k.hdr --resize 4096x2048 -o /tmp/noon_4k.exr
  oiiotool assets/noon_grass_1k.hdr --resize 8192x4096 -d half -o /tmp/noon_8k.exr
  tests/blender/run.sh blender bench/bench_blender.py build/probe_lights-0.1.0-linux_x64.zip ../shared
  tests/blender/run.sh ~/.cache/probelights/bpy-5.2.3/bin/python bench/bench_blender.py build/probe_lights-0.1.0-linux_x64.zip ../shared

PROBELIGHTS_BENCH_PROBES=/tmp/noon_8k.exr times those probes alone (paths joined by ':'), so the first click is a
session's first: nothing baked before it in the process. Each image is loaded, then left a second before its first
click, as a user's is: Blender's own work on a probe it has just read (measured: up to 0.3 s of an 8K click that
follows at once) is not the bake's.
"""
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
import harness  # noqa: E402

harness.install_addon(harness.args().zip)
harness.empty_scene()
bake = harness.addon_module("bake")
probes = os.environ.get("PROBELIGHTS_BENCH_PROBES")
probes = probes.split(":") if probes else (harness.BUNDLED_PROBE, "/tmp/noon_2k.exr", "/tmp/noon_4k.exr",
                                           "/tmp/noon_8k.exr")
for path in (p for p in probes if os.path.exists(p)):
    img = bpy.data.images.load(path)
    img.pixels[0]  # load the file (reading it is not part of a bake)
    harness.env_world(img)
    time.sleep(1.0)
    times, stages = [], []
    settings = bpy.context.scene.probe_lights
    settings.count = 64
    settings.refit = bool(os.environ.get("PROBELIGHTS_BENCH_REFIT"))
    for i in range(3):
        t = time.perf_counter()
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64, refit=settings.refit)
        times.append(1000 * (time.perf_counter() - t))
    for i in range(3):
        stages.append(bake.bake_world(bpy.context, settings)["timings"])
    print("TIMING Blender %s, %s %dx%d: one click, 64 suns%s incl. estimate: %s ms; stages (read / bake+estimate / "
          "lamps): %s ms" % (bpy.app.version_string, os.path.basename(path), img.size[0], img.size[1],
                             " with Refit" if settings.refit else "",
                             " / ".join("%.0f" % t for t in times),
                             ", ".join("%.0f / %.0f / %.0f" % (s["probe"], s["bake"], s["lamps"]) for s in stages)))
