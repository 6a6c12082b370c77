"""The lamps a bake makes: re-baked in place, split by effect, following the world's turn and strength, kept per
world, drawn under one rig, adopted from older bakes, thousands made in one batch."""

import math

import bpy
import numpy as np

import harness
from addon_common import bake, bright_spot_world, irradiance, lamp_state, light_objects, LUM, sun_direction, world_mix


def test_rebake_replaces_only_its_own_lights():
    harness.empty_scene()
    bright_spot_world((10, 30))
    scene = bpy.context.scene
    user_light = bpy.data.objects.new("user key light", bpy.data.lights.new("key", "AREA"))
    scene.collection.objects.link(user_light)
    lights = bake(count=16)
    collection = light_objects.world_collection(scene.world)
    stray = bpy.data.objects.new("user empty", None)
    collection.objects.link(stray)
    assert len(lights) == 16
    lights = bake(count=5)
    assert len(lights) == 5
    assert stray.name in collection.objects and user_light.name in scene.objects
    assert len([c for c in bpy.data.collections if c.get(light_objects.COLLECTION_TAG)]) == 1
    assert len([n for n in scene.world.node_tree.nodes if n.get(world_mix.NODE_TAG)]) > 0
    nodes = scene.world.node_tree.nodes
    assert len([n for n in nodes if n.get(world_mix.MIX_TAG)]) == 1, "a re-bake replaces the mix, never stacks one"
    assert len([n for n in nodes if n.get(world_mix.EEVEE_OUTPUT_TAG)]) == 1  # the EEVEE-only output, once


def test_lamps_light_the_effects_of_their_split_and_sample_by_importance_only_with_reflections():
    """Which effects the lamps light (Cycles' ray visibility; in EEVEE every effect) and whether Cycles reaches them
    by multiple importance sampling: off unless they light reflections, where Cycles has a light tree (3.5+;
    docs/results/glossy.md)."""
    harness.empty_scene()
    tree = hasattr(bpy.context.scene.cycles, "use_light_tree")
    bright_spot_world((64, 32))
    default = {"replace_reflections": False, "lamps_take": "ALL"}
    for settings, glossy in ((default, False), ({"replace_reflections": True, "lamps_take": "ALL"}, True),
                             ({"replace_reflections": False, "lamps_take": "SOURCES"}, True), (default, False)):
        lamps = bake(count=4, **settings)
        assert lamps, settings
        for obj in lamps:
            flags = (obj.visible_diffuse, obj.visible_glossy, obj.visible_transmission,
                     obj.data.cycles.use_multiple_importance_sampling)
            assert flags == (True, glossy, glossy, glossy or not tree), (settings, obj.name, flags)
            if hasattr(obj.data, "specular_factor"):  # EEVEE's world lights nothing: there the lamps light all
                assert (obj.data.diffuse_factor, obj.data.specular_factor) == (1.0, 1.0), (settings, obj.name)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}


def test_point_lights_give_the_same_irradiance_at_the_origin():
    harness.empty_scene()
    bright_spot_world((30, 20))
    # One cut for both (auto may keep another cut for points, whose shadows are hard, than for fitted suns).
    suns = bake(count=8, refit=False, method="variance")
    sun_e = sorted(float(irradiance(o) @ LUM) for o in suns)
    points = bake(count=8, light_type="POINT", distance=7.0, refit=False, method="variance")
    for o in points:
        assert abs(o.location.length - 7.0) < 1e-4
    # Point power P at distance D gives P / (4 pi D^2) (measured: tests/blender/test_render.py checks it in Cycles).
    point_e = sorted(float((np.array(o.data.color) * o.data.energy) @ LUM / (4 * math.pi * 49.0)) for o in points)
    assert np.allclose(sun_e, point_e, rtol=1e-6), (sun_e, point_e)


def test_lamps_follow_the_worlds_rotation_and_strength():
    """The rig turns with the world's Mapping and the lamps' strengths follow the Background's (drivers): after a
    change they equal a fresh bake's."""
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE), strength=1.0, rotation=(0.2, -0.1, 0.5))
    bake(count=16)
    nt = world.node_tree
    mapping = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeMapping")
    for vector_type in ("POINT", "TEXTURE"):
        mapping.vector_type = vector_type
        bake(count=16)
        before = lamp_state(world)
        mapping.inputs["Rotation"].default_value = (0.7, 0.3, -1.9)
        nt.nodes["Background"].inputs["Strength"].default_value = 2.5
        followed = lamp_state(world)
        # The rig turned as the world now turns the probe (read independently from the changed world).
        expected = np.array(harness.addon_module("world_graph").find_probe(world, bpy.app.version).world_from_probe)
        turned = np.array(light_objects.rig(world).matrix_world.to_3x3())
        assert np.abs(turned - expected).max() < 1e-5, (vector_type, turned, expected)
        assert abs(followed[1].sum() / before[1].sum() - 2.5) < 1e-5
        bake(count=16)
        fresh = lamp_state(world)
        assert np.abs(followed[0] - fresh[0]).max() < 1e-4, (vector_type, np.abs(followed[0] - fresh[0]).max())
        assert np.abs(followed[1] / fresh[1] - 1).max() < 1e-4, vector_type
        print("  %s mapping: rotated and 2.5x stronger world, lamps vs a fresh bake: direction %.1e, energy %.1e" % (
            vector_type, np.abs(followed[0] - fresh[0]).max(), np.abs(followed[1] / fresh[1] - 1).max()))
        mapping.inputs["Rotation"].default_value = (0.2, -0.1, 0.5)
        nt.nodes["Background"].inputs["Strength"].default_value = 1.0
    # A changed image is not followed: the panel asks for a re-bake.
    bake_module = harness.addon_module("bake")
    assert bake_module.image_changed(world) == ""
    env = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    env.image = harness.float_image("other", np.ones((8, 16, 3), np.float32))
    assert bake_module.image_changed(world) == "other"


def test_suns_on_a_dome_around_the_scene_under_one_rig():
    harness.empty_scene()
    scene = bpy.context.scene
    bright_spot_world((40, 20))
    for location in ((5, 0, 0), (9, 2, 1)):
        mesh = bpy.data.objects.new("block", bpy.data.meshes.new("block"))
        mesh.data.from_pydata([(-1, -1, -1), (1, 1, 1)], [], [])
        mesh.location = location
        scene.collection.objects.link(mesh)
    bpy.context.view_layer.update()
    lamps = bake(count=8)
    centre, radius = light_objects.scene_bounds(scene)
    assert np.allclose(centre, (7, 1, 0.5)) and abs(radius - math.sqrt(61) / 2) < 1e-9, (centre, radius)
    holder = light_objects.rig(scene.world)
    assert holder is not None and all(o.parent == holder for o in lamps)
    assert abs(holder.empty_display_size - 1.5 * radius) < 1e-6
    for o in lamps:
        offset = np.array(o.matrix_world.translation) - centre
        assert abs(np.linalg.norm(offset) - 1.5 * radius) < 1e-4
        # A sun sits where it shines from: its light comes from the offset's direction.
        assert harness.angle_deg(offset, sun_direction(o)) < 1e-3


def test_worlds_keep_their_own_lamps_and_mix():
    harness.empty_scene()
    scene = bpy.context.scene
    world_a = bright_spot_world((40, 20), name="A")
    before_a = harness.tree_snapshot(world_a)
    bake(count=8)
    world_b = bright_spot_world((90, 40), name="B")
    before_b = harness.tree_snapshot(world_b)
    bake(count=5)
    assert len(light_objects.baked_lights(world_a)) == 8 and len(light_objects.baked_lights(world_b)) == 5
    assert world_mix.has_mix(world_a) and world_mix.has_mix(world_b)

    def excluded(world):
        c = light_objects.world_collection(world)
        return bpy.context.view_layer.layer_collection.children[c.name].exclude

    assert excluded(world_a) and not excluded(world_b)  # only the scene's world lights it
    scene.world = world_a
    bpy.context.view_layer.update()  # the depsgraph handler switches the lamps with the world
    assert not excluded(world_a) and excluded(world_b)
    assert [w.name for w in light_objects.baked_worlds()] == ["A", "B"]
    # Restore B while A is the scene's world: B comes back exactly, its collection goes, A is untouched.
    assert bpy.ops.probe_lights.restore(world="B") == {"FINISHED"}
    assert harness.tree_snapshot(world_b) == before_b and light_objects.world_collection(world_b) is None
    assert len(light_objects.baked_lights(world_a)) == 8 and world_mix.has_mix(world_a)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert harness.tree_snapshot(world_a) == before_a
    assert not [c for c in bpy.data.collections if c.get(light_objects.COLLECTION_TAG)]


def test_a_bake_by_version_0_1_is_adopted():
    """Version 0.1 kept one untied "Probe Lights" collection per scene: a re-bake replaces its lamps (the scene is
    never lit by both), Restore removes them."""
    harness.empty_scene()
    scene = bpy.context.scene
    world = bright_spot_world((40, 20))
    bake(count=6)
    c = light_objects.world_collection(world)
    del c[light_objects.WORLD_KEY]  # as 0.1 left it
    for o in [o for o in c.objects if o.get(light_objects.RIG_TAG)]:
        bpy.data.objects.remove(o)
    assert light_objects.world_collection(world) == c and len(light_objects.baked_lights(world)) == 6
    bake(count=4)
    assert len([o for o in scene.objects if o.get(light_objects.OBJECT_TAG)]) == 4
    assert light_objects.world_collection(world).get(light_objects.WORLD_KEY) == world
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert not [o for o in scene.objects if o.get(light_objects.OBJECT_TAG)]


def test_lamps_of_an_earlier_bake_light_every_effect_in_eevee():
    """Lamps baked before their ray visibility followed the engine (no split kept, EEVEE's specular factor 0) are
    adopted as they are found: their visibility is their Cycles split, EEVEE gets every effect."""
    harness.empty_scene()
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    bright_spot_world((40, 20))
    lamps = bake(count=4, replace_reflections=False)
    for o in lamps:  # as the add-on left them until 2026-12-05 (until 2026-12-06 their rays had no drivers)
        del o[light_objects.RAYS_KEY]
        for ray in light_objects.LAMP_RAYS:
            o.driver_remove("visible_" + ray)
        if hasattr(o.data, "specular_factor"):
            o.data.specular_factor = 0.0
    rays = ("visible_diffuse", "visible_glossy", "visible_transmission", "visible_volume_scatter")
    scene.render.engine = harness.eevee_engine()
    light_objects.follow_engine(scene)
    for o in lamps:
        assert [getattr(o, r) for r in rays] == [True] * 4, o.name
        assert not hasattr(o.data, "specular_factor") or o.data.specular_factor == 1.0
    scene.render.engine = "CYCLES"
    light_objects.follow_engine(scene)
    assert {tuple(getattr(o, r) for r in rays) for o in lamps} == {(True, False, False, True)}
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}


def test_the_bakes_nodes_are_framed_beside_the_users():
    harness.empty_scene()
    world = bright_spot_world((40, 20), rotation=(0.1, 0.2, 0.3))
    bake(count=4, replace_reflections=False)
    nodes = world.node_tree.nodes
    ours = [n for n in nodes if n.get(world_mix.NODE_TAG)]
    frames = [n for n in ours if n.bl_idname == "NodeFrame"]
    assert len(frames) == 1 and "Probe Lights" in frames[0].label
    users = [n for n in nodes if not n.get(world_mix.NODE_TAG)]
    lowest_user = min(n.location.y for n in users)
    for n in ours:
        if n is not frames[0]:
            assert n.parent == frames[0], n.name
            y = n.location.y + (frames[0].location.y if bpy.app.version >= (4, 4, 0) else 0)
            assert y < lowest_user, (n.name, y, lowest_user)


def test_thousands_of_lamps_go_in_one_batch():
    """A re-bake reuses its lamps and removes only the surplus, in batches (one by one, 4096 lamps took 5 s)."""
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    import time
    times = []
    for count in (4096, 4096, 64):
        start = time.perf_counter()
        lamps = bake(count=count, resolution="512")
        times.append(time.perf_counter() - start)
        assert len(lamps) == count
    start = time.perf_counter()
    removed = light_objects.remove_lights(world)
    print("  4096 lamps: bake %.2f s, re-bake %.2f s, re-bake to 64 %.2f s; removing 64: %.3f s" % (
        *times, time.perf_counter() - start))
    assert removed == 64 and not light_objects.baked_lights(world)
    assert not [l for l in bpy.data.lights if l.name.startswith("Probe Light")]
