"""Render cost of many lights, per Blender version: the sphere-over-plane scene of the render test lit by
N = 4..256 baked suns at equal samples, against the world-lit render: render time and difference (8x8 block means
of the lit pixels, harness/render_scene.py). Cycles 3.4 picks lamps nearly uniformly (no light tree), so
there more lamps add noise; 4.x and 5.x pick them through a light tree. Run it in each Blender the tests cover:

    tests/blender/run.sh blender bench/bench_render_counts.py build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBE] [SAMPLES]
    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_render_counts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared

With PROBELIGHTS_BENCH_WRITE=addon/probe_lights/render_cost.json it also puts this version's and probe's figures
into that file (written whole: a temporary file renamed over it), the data the add-on's render-cost advice reads.
"""
import datetime
import json
import os
import re
import subprocess
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
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


reference, seconds_world = timed_render()
print("RENDER Blender %s, %s, %d spp, 128x96" % (bpy.app.version_string, os.path.basename(probe), samples))
print("RENDER world-lit: %.2f s" % seconds_world)
bpy.context.scene.cycles.seed = 2
again, _ = timed_render()
print("RENDER noise floor (world vs world, other seed): %.2f %%" % (
    100 * render_scene.block_difference(reference, again)[0]))
bpy.context.scene.cycles.seed = 1
suns = {}
for n in (4, 8, 16, 32, 64, 128, 256):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
    pixels, seconds = timed_render()
    difference = 100 * render_scene.block_difference(reference, pixels)[0]
    suns[str(n)] = {"seconds": round(seconds, 2), "difference": round(difference, 2)}
    print("RENDER %3d suns: %.2f s, difference %.2f %%" % (n, seconds, difference), flush=True)

target = os.environ.get("PROBELIGHTS_BENCH_WRITE")
if target:
    with open(target, encoding="utf-8") as f:
        data = json.load(f)
    commit = subprocess.run(["git", "-C", HERE, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    name = re.sub(r"_\d+k$", "", os.path.splitext(os.path.basename(probe))[0])
    version = "%d.%d.%d" % bpy.app.version
    data["versions"].setdefault(version, {})[name] = {"world_seconds": round(seconds_world, 2), "suns": suns,
                                                      "measured": "%s, build %s, %d samples" % (
                                                          datetime.date.today(), commit, samples)}
    partial = target + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(json.dumps(data, indent=1) + "\n")
    os.replace(partial, target)
    print("RENDER wrote Blender %s, %s into %s" % (version, name, target))
