"""Bake animation: a world that changes over time baked frame by frame into lamps that keep their identity, keyed
on every frame; each frame's lamps the core's sequence bake of that frame's probe, energy exact."""

import math
import os
import tempfile
import threading

import bpy
import numpy as np

import harness
from rgbe import write_hdr
from addon_common import _probelights, bake, expect_report, irradiance, latlong_direction, light_objects, LUM, sun_direction

FRAMES = 12
W, H = 64, 32


def _spot(f):
    """Frame f's spot pixel: it crosses the sky, rising, with its brightness changing."""
    return 4 + 4 * f, 14 - f // 2


def _write_sequence(folder):
    """FRAMES Radiance frames sky_0001.hdr... of a dim sky with a bright spot moving across it."""
    for f in range(1, FRAMES + 1):
        a = np.full((H, W, 3), 0.05, np.float32)
        a[H // 2:] = 0.02 * f  # the ground brightens
        x, y = _spot(f)
        a[y, x] = (300 + 40 * f, 250, 200)
        write_hdr(os.path.join(folder, "sky_%04d.hdr" % f), a)


def _sequence_world(folder, strength=2.0, start=1, offset=0, cyclic=False):
    image = bpy.data.images.load(os.path.join(folder, "sky_0001.hdr"))
    image.source = "SEQUENCE"
    world = harness.env_world(image, strength=strength)
    node = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    node.image_user.frame_duration, node.image_user.frame_start = FRAMES, start
    node.image_user.frame_offset, node.image_user.use_cyclic = offset, cyclic
    return world, node


def _bake_animation(**settings):
    result = bpy.ops.probe_lights.bake_animation("EXEC_DEFAULT", **settings)
    assert result == {"FINISHED"}, result
    return sorted(light_objects.baked_lights(bpy.context.scene.world), key=lambda o: o.name)


def _expect_refusal(text, **settings):
    expect_report(text, bpy.ops.probe_lights.bake_animation, **settings)


def _check_frames(lamps, frames, strength):
    """Each lamp on sampled frames is light k of the core's frame (direction, irradiance, angle), the lamps
    summing to each frame's probe. Returns the id of the lamp that carries the moving spot."""
    scene = bpy.context.scene
    spot_lamp = set()
    for f in (1, 2, 7, FRAMES):
        scene.frame_set(f)
        lights = frames[f - 1]["lights"]
        for k, lamp in enumerate(lamps):
            if lights["rgb"][k] @ LUM > 0:
                assert harness.angle_deg(sun_direction(lamp), lights["direction"][k]) < 0.01, (f, k)
            assert np.allclose(irradiance(lamp), strength * lights["rgb"][k], rtol=1e-4, atol=1e-6), (f, k)
            assert abs(lamp.data.angle - lights["angle"][k]) < 1e-5
        # The lamps sum to the probe, channel by channel, as cut and refit alike (the refit holds the energy).
        total = sum(irradiance(lamp) for lamp in lamps)
        assert abs(frames[f - 1]["energy_shift"]) < 1e-12, (f, frames[f - 1]["energy_shift"])
        assert np.allclose(total, strength * frames[f - 1]["total_rgb"], rtol=1e-4), (f, total)
        x, y = _spot(f)
        near = [k for k, lamp in enumerate(lamps) if harness.angle_deg(sun_direction(lamp),
                                                                       latlong_direction(x, y, W, H)) < 6]
        spot_lamp.add(max(near, key=lambda k: irradiance(lamps[k]) @ LUM))
    assert len(spot_lamp) == 1, spot_lamp  # one lamp carries the moving spot all along
    return spot_lamp.pop()


def test_an_image_sequence_bakes_into_keyed_lamps_that_keep_their_ids():
    harness.empty_scene()
    scene = bpy.context.scene
    animation = harness.addon_module("animation")
    with tempfile.TemporaryDirectory() as folder:
        _write_sequence(folder)
        world, node = _sequence_world(folder)
        scene.frame_start, scene.frame_end = 1, FRAMES
        for refit in (False, True):  # as cut, and finished as a single bake (the default): energy exact in both
            lamps = _bake_animation(count=6, refit=refit)
            # The core's sequence bake of the same frames with the add-on's options, read as Blender reads them.
            baker = _probelights.SequenceBaker(**animation.sequence_options(scene, scene.probe_lights, 0.1))
            read = harness.addon_module("world_image").sequence_pixels
            frames = [baker.add(read(node, f), frame=f) for f in range(1, FRAMES + 1)]
            assert len(lamps) == 6
            for lamp in lamps:  # every lamp keyed on every frame
                fcurves = animation._fcurves(lamp.animation_data)
                assert {len(c.keyframe_points) for c in fcurves} == {FRAMES}, lamp.name
                # straight between frames (sampled light: no overshoot)
                assert {p.interpolation for c in fcurves for p in c.keyframe_points} == {"LINEAR"}, lamp.name
            spot = _check_frames(lamps, frames, 2.0)
            print("  refit %s: %d lamps keyed on %d frames; the spot kept lamp %d; energy shift up to %.2f %%" % (
                refit, len(lamps), FRAMES, spot, 100 * max(abs(f["energy_shift"]) for f in frames)))
        # Exact energy off: each frame's refit trades energy as a single bake's does, as the core's frames say.
        free_lamps = _bake_animation(count=6, exact_energy=False)
        free = _probelights.SequenceBaker(**animation.sequence_options(scene, scene.probe_lights, 0.1, False))
        shifted = [free.add(read(node, f), frame=f) for f in (1, 2)]
        assert max(abs(f["energy_shift"]) for f in shifted) > 1e-4
        scene.frame_set(2)
        total = sum(irradiance(lamp) for lamp in free_lamps).sum()
        assert abs(total - 2.0 * sum(shifted[1]["total_rgb"]) * (1 + shifted[1]["energy_shift"])) < 1e-4 * total
        print("  exact energy off: frame 2's lamps carry %+.2f %% of its light, as the core's frame" % (
            100 * shifted[1]["energy_shift"]))
        lamps = _bake_animation(count=6)
    # The world's strength is still followed, on every frame.
    node.id_data.nodes["Background"].inputs["Strength"].default_value = 3.0
    scene.frame_set(7)
    assert np.allclose(irradiance(lamps[0]), 3.0 * frames[6]["lights"]["rgb"][0], rtol=1e-4, atol=1e-6)


def test_a_bake_of_an_image_sequence_reads_the_scenes_frame_and_restore_takes_the_keys():
    harness.empty_scene()
    scene = bpy.context.scene
    with tempfile.TemporaryDirectory() as folder:
        _write_sequence(folder)
        _, node = _sequence_world(folder)
        scene.frame_set(7)
        lamp = max(bake(count=4), key=lambda o: irradiance(o) @ LUM)
        assert harness.angle_deg(sun_direction(lamp), latlong_direction(*_spot(7), W, H)) < 3
        assert lamp.animation_data is None or lamp.animation_data.action is None
        lamps = _bake_animation(count=4, frame_start=2, frame_end=5)
        actions = {a.name for a in bpy.data.actions}
        assert actions and all(o.animation_data.action is not None for o in lamps)
        # A single bake after it keys nothing: the lamps it reuses lose their keys.
        lamps = bake(count=4)
        assert all(o.animation_data is None or o.animation_data.action is None for o in lamps)
        assert not bpy.data.actions, [a.name for a in bpy.data.actions]
        lamps = _bake_animation(count=4, frame_start=2, frame_end=5)
        assert bpy.ops.probe_lights.restore("EXEC_DEFAULT") == {"FINISHED"}
        assert not light_objects.baked_lights(scene.world) and not bpy.data.actions
        # A frame whose file is not there, a range backwards, a world that does not change: one line each.
        node.image_user.frame_duration = FRAMES + 5  # images past the last file
        _expect_refusal("has no file", frame_start=10, frame_end=FRAMES + 3)
        _expect_refusal("ends before it starts", frame_start=5, frame_end=4)
        # A frame the core refuses while the next one is read (frames bake on a thread beside the reading): its
        # number and the core's line, nothing changed and no thread left behind.
        node.image_user.frame_duration = FRAMES
        write_hdr(os.path.join(folder, "sky_0006.hdr"), np.full((H // 2, W // 2, 3), 0.05, np.float32))
        bake(count=4)
        before = sorted(o.name for o in bpy.data.objects)
        _expect_refusal("frame 6: frame 6 is 32x16 latlong", frame_start=1, frame_end=FRAMES)
        assert sorted(o.name for o in bpy.data.objects) == before and not bpy.data.actions
        assert not [t.name for t in threading.enumerate() if t.name.startswith("probe_lights_bake")]
    harness.empty_scene()
    harness.env_world(harness.float_image("still", np.ones((8, 16, 3))))
    _expect_refusal("does not change over time")


def test_sequence_frames_are_the_ones_cycles_renders():
    """The image of each scene frame (start frame, offset, cyclic) is the one Cycles renders at that frame."""
    harness.empty_scene()
    world_image = harness.addon_module("world_image")
    with tempfile.TemporaryDirectory() as folder:
        _write_sequence(folder)
        for start, offset, cyclic, frames in ((3, 1, True, (2, 15, 30)), (1, 0, False, (2, 30))):
            world, node = _sequence_world(folder, start=start, offset=offset, cyclic=cyclic)
            node.image_user.frame_duration = FRAMES - 2
            render = world_image.WorldRender(world, W, samples=4)
            try:
                for frame in frames:
                    read = world_image.sequence_pixels(node, frame)
                    rendered = render.render(frame)
                    at = [np.unravel_index(np.argmax(p[..., 1]), p.shape[:2]) for p in (read, rendered)]
                    assert at[0] == at[1], (start, offset, cyclic, frame, at)
            finally:
                render.close()


def test_an_animated_sky_is_rendered_frame_by_frame():
    harness.empty_scene()
    scene = bpy.context.scene
    world = harness.sky_world(elevation_deg=10.0)
    sky = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky")
    for frame, elevation in ((1, 10.0), (3, 50.0)):
        sky.sun_elevation = math.radians(elevation)
        sky.keyframe_insert("sun_elevation", frame=frame)
    scene.frame_start, scene.frame_end = 1, 3
    animation = harness.addon_module("animation")
    animation.RENDER_WIDTH, width = 512, animation.RENDER_WIDTH  # half the add-on's: enough to find the sun
    settings = scene.probe_lights
    try:
        lamps = _bake_animation(count=8)
        # The Tradeoff times Bake animation's frame too: here the world's render beside the bake.
        settings.count = 8
        assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    finally:
        animation.RENDER_WIDTH = width
    assert settings.tradeoff_frames == 3 and settings.tradeoff_frames_rendered
    assert settings.tradeoff_frame_read_ms > 0 and settings.tradeoff_frame_bake_ms > 0
    assert "(the world rendered in " in harness.addon_module("ui").animation_cost(settings)
    print("  " + harness.addon_module("ui").animation_cost(settings))
    elevations = []
    for f in (1, 2, 3):
        scene.frame_set(f)
        sun = max(lamps, key=lambda o: irradiance(o) @ LUM)
        elevations.append(math.degrees(math.asin(sun_direction(sun)[2])))
    # Keyed 10 and 50 degrees at frames 1 and 3: 30 at frame 2, between Bezier keys.
    assert all(abs(e - want) < 3 for e, want in zip(elevations, (10, 30, 50))), elevations
    print("  the sky's sun at %s degrees" % ", ".join("%.1f" % e for e in elevations))


def test_the_tradeoff_says_what_bake_animation_costs():
    """On a world that changes over time the Tradeoff adds Bake animation's cost at the panel's count: the current
    frame read (or rendered) beside its bake, over the scene's frames. It keys nothing; a still world gets no line."""
    harness.empty_scene()
    scene, settings = bpy.context.scene, bpy.context.scene.probe_lights
    ui = harness.addon_module("ui")
    with tempfile.TemporaryDirectory() as folder:
        _write_sequence(folder)
        world, _ = _sequence_world(folder)
        scene.frame_start, scene.frame_end = 1, FRAMES
        settings.count = 6
        before = harness.tree_snapshot(world)
        assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
        assert (settings.tradeoff_frames, settings.tradeoff_frame_lights) == (FRAMES, 6)
        assert settings.tradeoff_frame_read_ms > 0 and settings.tradeoff_frame_bake_ms > 0
        assert not settings.tradeoff_frames_rendered
        line = ui.animation_cost(settings)
        assert line.startswith("Bake animation, %d frames of 6 lights: about " % FRAMES), line
        assert "(the world read in " in line, line
        assert harness.tree_snapshot(world) == before and not light_objects.baked_lights(world)
        assert world.node_tree.animation_data is None or not world.node_tree.animation_data.action
        print("  " + line)
    harness.env_world(harness.float_image("still", np.full((32, 64, 3), 0.5, np.float32)))
    assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    assert settings.tradeoff_frames == 0
