"""Bake animation in Blender: the time of the add-on's whole click for an image sequence of 48 1K frames (the
bundled probe with a sun crossing it, bench_sequence.py's "day", written as Radiance frames), at 16 and 64 lights,
with Refit (each frame finished as a single bake: fitted angles, colours and directions refit) and without, with
its stages (reading the frames through Blender, the core's sequence bake, making and keying the lamps); and
the cost a frame of an animated Sky Texture, which is rendered (Cycles, a panorama of animation.RENDER_WIDTH):

  tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_addon_animation.py \\
      build/probe_lights-0.1.0-linux_x64.zip ../shared

Written up in docs/results/sequences.md ("In Blender").
"""
import math
import os
import pathlib
import sys
import tempfile
import time

import bpy
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "harness"))
sys.path.insert(0, str(HERE.parent / "tests" / "python"))
sys.path.insert(0, str(HERE))
import harness  # noqa: E402
from bench_sequence import make_day  # noqa: E402
from rgbe import read_hdr, write_hdr  # noqa: E402

FRAMES = 48
harness.install_addon(harness.args().zip)
light_objects = harness.addon_module("light_objects")


def timed_click(**settings):
    t = time.perf_counter()
    assert bpy.ops.probe_lights.bake_animation("EXEC_DEFAULT", **settings) == {"FINISHED"}
    return time.perf_counter() - t, bpy.context.scene.probe_lights.last_report


with tempfile.TemporaryDirectory() as tmp:
    folder = pathlib.Path(tmp)
    make_day(read_hdr(harness.BUNDLED_PROBE).astype(np.float32), folder, FRAMES, write=write_hdr, ext="hdr")
    harness.empty_scene()
    image = bpy.data.images.load(str(folder / "day_0001.hdr"))
    image.source = "SEQUENCE"
    world = harness.env_world(image)
    node = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    node.image_user.frame_duration = FRAMES
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, FRAMES
    for lights in (16, 64):
        for refit in (True, False):
            runs = [timed_click(count=lights, refit=refit) for _ in range(3)]
            print("TIMING Blender %s, %d frames of %dx%d, %d lights, Refit %s: %s s; the add-on's report: %s" % (
                bpy.app.version_string, FRAMES, 1024, 512, lights, "on" if refit else "off",
                " / ".join("%.2f" % r[0] for r in runs), runs[-1][1]))

harness.empty_scene()
world = harness.sky_world(elevation_deg=2.0)
sky = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky")
for frame, elevation in ((1, 2.0), (12, 60.0)):
    sky.sun_elevation = math.radians(elevation)
    sky.keyframe_insert("sun_elevation", frame=frame)
scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, 12
seconds, report = timed_click(count=16)
print("TIMING Blender %s, animated Sky Texture, 12 frames rendered at %d wide, 16 lights: %.1f s (%.2f s a frame); "
      "the add-on's report: %s" % (bpy.app.version_string, harness.addon_module("animation").RENDER_WIDTH, seconds,
                                   seconds / 12, report))
