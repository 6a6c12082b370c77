"""Flicker in Cycles renders: the sphere over a plane lit by an animated world, by its Bake animation lamps (Refit
on with every frame's energy exact, the default; Refit on with Exact energy off; Refit off), by each frame's own
single bake, and by each frame baked alone with its energy exact (Bake animation of that one frame), frame by
frame (docs/results/sequences.md, "Renders"):

  tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_animation_renders.py \\
      build/probe_lights-0.1.0-linux_x64.zip ../shared

The world is bench_sequence.py's day made from the bundled probe in 24 frames (a 2-degree sun crossing it, its
strength and the exposure changing), as the world's image sequence; with PROBELIGHTS_BENCH_WORLD=sky, a physical
Sky Texture whose sun rises, culminates at 60 degrees and sets over the 24 frames (rendered each frame by the
add-on, as single bakes render it too). For each way of lighting, on the 8x8 blocks
of lit object pixels (render_scene.block_difference's rule, from the world-lit first frame):
  error    the mean over frames of block_difference against that frame's world-lit render;
  change   the frame-to-frame change, sum |L(f+1) - L(f)|, over the world-lit renders' own;
  jitter   the second difference, sum |L(f+1) - 2 L(f) + L(f-1)|, over the world-lit renders' own: what is not
           smooth in time (a lamp that jumps), 1 when the lamps change as smoothly as the world.
Cycles at 128 x 96, 128 samples, seed fixed (its noise correlated from frame to frame), 4 bounces. 16 lamps;
PROBELIGHTS_BENCH_LIGHTS=64 for 64. The sphere over a plane; PROBELIGHTS_BENCH_SCENE=still_life for the still life
(render_scene.still_life: a metal sphere, a glossy box, a rough vase and a thin rod on a floor).
"""
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
import render_scene  # noqa: E402
from bench_sequence import make_day  # noqa: E402
from rgbe import read_hdr, write_hdr  # noqa: E402

FRAMES, LIGHTS = 24, int(os.environ.get("PROBELIGHTS_BENCH_LIGHTS", "16"))
harness.install_addon(harness.args().zip)


def render_frames():
    out = []
    for f in range(1, FRAMES + 1):
        bpy.context.scene.frame_set(f)
        out.append(render_scene.render())
    return out


def measure(world_lit, lit, frames):
    y = np.array([render_scene.block_luminance(p)[lit] for p in frames])
    w = np.array([render_scene.block_luminance(p)[lit] for p in world_lit])
    error = np.mean([render_scene.block_difference(a, b)[0] for a, b in zip(world_lit, frames)])
    change = np.abs(np.diff(y, axis=0)).sum() / np.abs(np.diff(w, axis=0)).sum()
    jitter = np.abs(np.diff(y, 2, axis=0)).sum() / np.abs(np.diff(w, 2, axis=0)).sum()
    return error, change, jitter


def sky_day():
    """A physical Sky Texture whose sun rises in the east, culminates at 60 degrees in the south and sets in the
    west over the frames (keys at the first, middle and last frame: Blender's Bezier between them)."""
    world = harness.sky_world(elevation_deg=2.0, rotation_deg=-90.0)
    sky = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky")
    for frame, elevation, rotation in ((1, 2.0, -90.0), ((FRAMES + 1) // 2, 60.0, 0.0), (FRAMES, 2.0, 90.0)):
        sky.sun_elevation, sky.sun_rotation = np.radians(elevation), np.radians(rotation)
        sky.keyframe_insert("sun_elevation", frame=frame)
        sky.keyframe_insert("sun_rotation", frame=frame)
    return world


SKY = os.environ.get("PROBELIGHTS_BENCH_WORLD") == "sky"
STILL_LIFE = os.environ.get("PROBELIGHTS_BENCH_SCENE") == "still_life"
with tempfile.TemporaryDirectory() as tmp:
    folder = pathlib.Path(tmp)
    harness.empty_scene()
    if SKY:
        world = sky_day()
    else:
        make_day(read_hdr(harness.BUNDLED_PROBE).astype(np.float32), folder, FRAMES, write=write_hdr, ext="hdr")
        image = bpy.data.images.load(str(folder / "day_0001.hdr"))
        image.source = "SEQUENCE"
        world = harness.env_world(image)
        env = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
        env.image_user.frame_duration = FRAMES
    (render_scene.still_life if STILL_LIFE else render_scene.sphere_over_plane)(128, 96, 128)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, FRAMES
    t = time.perf_counter()
    world_lit = render_frames()
    lit = render_scene.lit_blocks(world_lit[0])
    rows = []
    for name, settings in (("Refit on (default)", {}), ("Refit on, Exact energy off", {"exact_energy": False}),
                           ("Refit off", {"refit": False})):
        assert bpy.ops.probe_lights.bake_animation("EXEC_DEFAULT", count=LIGHTS, **settings) == {"FINISHED"}
        rows.append(("Bake animation, " + name, measure(world_lit, lit, render_frames())))
    single = []
    for f in range(1, FRAMES + 1):
        scene.frame_set(f)
        assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=LIGHTS) == {"FINISHED"}
        single.append(render_scene.render())
    rows.append(("each frame its own bake (Bake probe to lights)", measure(world_lit, lit, single)))
    # Each frame baked alone with its energy exact, as Bake animation finishes a frame: what exactness costs
    # without the frames' coherence (a single bake's refit trades energy).
    alone = []
    for f in range(1, FRAMES + 1):
        assert bpy.ops.probe_lights.bake_animation("EXEC_DEFAULT", count=LIGHTS, frame_start=f,
                                                   frame_end=f) == {"FINISHED"}
        scene.frame_set(f)
        alone.append(render_scene.render())
    rows.append(("each frame alone, energy exact (Bake animation of that frame)", measure(world_lit, lit, alone)))
    print("Blender %s, %s, %s, %d frames, %d lamps, %d lit blocks, %.0f s" % (
        bpy.app.version_string, "Sky Texture day" if SKY else "day sequence",
        "still life" if STILL_LIFE else "sphere over a plane", FRAMES, LIGHTS, lit.sum(),
        time.perf_counter() - t))
    print("| lamps | error | change | jitter |\n|---|---:|---:|---:|")
    for name, (error, change, jitter) in rows:
        print("| %s | %.2f %% | %.2f | %.2f |" % (name, 100 * error, change, jitter))
