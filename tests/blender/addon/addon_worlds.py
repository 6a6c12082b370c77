"""Every kind of world read as Blender renders it (node groups, mirror balls, sky textures, plain colours), its
strength and rotation carried into the lights, and the world restored exactly."""

import math

import bpy
import numpy as np

import harness
from addon_common import _probelights, bake, bright_spot_world, brightest, irradiance, latlong_direction, light_objects, LUM, sun_direction, world_mix


def test_strength_and_rotation_carry_into_the_lights():
    harness.empty_scene()
    bright_spot_world((40, 20), strength=2.0)
    plain = brightest(bake(count=8))
    d0, e0 = sun_direction(plain), irradiance(plain)
    assert harness.angle_deg(d0, latlong_direction(40, 20, 128, 64)) < 0.5
    harness.empty_scene()
    rot = (0.3, -0.5, 1.2)
    bright_spot_world((40, 20), strength=2.0, rotation=rot)
    turned = brightest(bake(count=8))
    # The texture looks up R @ (world direction), so the spot now shines from R^T @ d0.
    expected = np.array(harness.addon_module("world_graph").euler_xyz_matrix(*rot)).T @ d0
    assert harness.angle_deg(sun_direction(turned), expected) < 0.5, (sun_direction(turned), expected)
    assert np.allclose(irradiance(turned), e0, rtol=1e-5)


def test_node_group_and_reroute():
    harness.empty_scene()
    world = bright_spot_world((100, 10))
    nt = world.node_tree
    env = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    bg = nt.nodes["Background"]
    # Move the environment texture into a group whose output feeds a reroute into the background.
    group = bpy.data.node_groups.new("env group", "ShaderNodeTree")
    if hasattr(group, "interface"):
        group.interface.new_socket("Color", in_out="OUTPUT", socket_type="NodeSocketColor")
    else:
        group.outputs.new("NodeSocketColor", "Color")
    inner = group.nodes.new("ShaderNodeTexEnvironment")
    inner.image = env.image
    out = group.nodes.new("NodeGroupOutput")
    group.links.new(inner.outputs["Color"], out.inputs[0])
    nt.nodes.remove(env)
    gnode = nt.nodes.new("ShaderNodeGroup")
    gnode.node_tree = group
    reroute = nt.nodes.new("NodeReroute")
    nt.links.new(gnode.outputs[0], reroute.inputs[0])
    nt.links.new(reroute.outputs[0], bg.inputs["Color"])
    lights = bake(count=4)
    assert "image 'spot'" in bpy.context.scene.probe_lights.last_source, bpy.context.scene.probe_lights.last_source
    assert harness.angle_deg(sun_direction(brightest(lights)), latlong_direction(100, 10, 128, 64)) < 0.5


def test_mirror_ball_image():
    # A mirror ball whose only bright spot is where Blender's mirror-ball mapping sees direction d.
    n = 128
    d = np.array([0.6, -0.3, 0.74])
    d /= np.linalg.norm(d)
    # Cycles' direction_to_mirrorball: d.y -= 1; d /= 2 sqrt(-0.5 d.y); u = (d.x + 1)/2, v_bottom = (d.z + 1)/2.
    div = 2 * math.sqrt(0.5 * (1 - d[1]))
    u, v_top = 0.5 * (d[0] / div + 1), 1 - 0.5 * (d[2] / div + 1)
    a = np.zeros((n, n, 3), np.float32)
    a[int(v_top * n), int(u * n)] = 500.0
    harness.empty_scene()
    harness.env_world(harness.float_image("ball", a), projection="MIRROR_BALL")
    lights = bake(count=4)
    assert len(lights) == 1, len(lights)  # one lit pixel: one light, and the add-on says so
    assert harness.angle_deg(sun_direction(lights[0]), d) < 2.0, sun_direction(lights[0])
    assert "made 1 lights, not 4" in bpy.context.scene.probe_lights.last_warnings


def test_sky_texture_world_is_rendered():
    harness.empty_scene()
    harness.sky_world(elevation_deg=35, rotation_deg=60)
    lights = bake(count=16)
    assert len(lights) == 16
    assert bpy.context.scene.probe_lights.last_source.startswith("rendered world"), bpy.context.scene.probe_lights.last_source
    sun = sun_direction(brightest(lights))
    elevation = math.degrees(math.asin(sun[2]))
    assert abs(elevation - 35) < 3, elevation


def test_read_and_rendered_worlds_agree():
    """The rules that read a world (rotation chains) against Blender itself: the same world rendered by the
    panoramic camera must put the bright spot in the same direction."""
    bake_module = harness.addon_module("bake")
    harness.empty_scene()
    world = bright_spot_world((40, 20), rotation=(0.4, -0.3, 2.0))
    nt = world.node_tree
    env = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    mapping = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeMapping")
    rotate = nt.nodes.new("ShaderNodeVectorRotate")
    rotate.rotation_type = "EULER_XYZ"
    rotate.invert = True
    rotate.inputs["Rotation"].default_value = (-0.2, 0.9, 0.3)
    nt.links.new(mapping.outputs["Vector"], rotate.inputs["Vector"])
    nt.links.new(rotate.outputs["Vector"], env.inputs["Vector"])
    env.interpolation = "Closest"
    read = sun_direction(brightest(bake(count=8)))
    assert "image 'spot'" in bpy.context.scene.probe_lights.last_source
    rendered = _probelights.bake(bake_module._rendered_probe(world), lights=8)
    brightest_rendered = rendered["lights"]["direction"][np.argmax(rendered["lights"]["rgb"] @ LUM)]
    assert harness.angle_deg(read, brightest_rendered) < 2.0, (read, brightest_rendered)
    print("  read vs rendered world: %.2f degrees apart" % harness.angle_deg(read, brightest_rendered))


def test_plain_colour_world_and_its_restore():
    """A world of one colour: before 5.0 a world without nodes (World.color), from 5.0 on the default tree's
    Background colour (5.0 renders every world through its nodes). Either bakes to 4 pi x the colour, and Restore
    brings the world back as it was."""
    harness.empty_scene()
    world = bpy.data.worlds.new("plain")
    bpy.context.scene.world = world
    colour = (0.2, 0.3, 0.4)
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = False
        world.color = colour
    else:
        world.node_tree.nodes["Background"].inputs["Color"].default_value = colour + (1.0,)
        before = harness.tree_snapshot(world)
    lights = bake(count=4, refit=False)
    total = sum(irradiance(o) for o in lights)
    assert np.allclose(total, 4 * math.pi * np.array(colour), rtol=2e-3), total
    assert world_mix.has_mix(world)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert not light_objects.baked_lights(bpy.context.scene.world)
    if bpy.app.version < (5, 0, 0):
        assert not world.use_nodes
    else:
        assert harness.tree_snapshot(world) == before


def test_restore_brings_the_world_back_exactly():
    harness.empty_scene()
    world = bright_spot_world((64, 32), rotation=(0.1, 0.2, 0.3))
    before = harness.tree_snapshot(world)
    bake(count=8, replace_reflections=True)
    assert harness.tree_snapshot(world) != before
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert harness.tree_snapshot(world) == before
    assert not light_objects.baked_lights(bpy.context.scene.world)
    # The default split keeps the world for reflections by its ray visibility: a flag the user had off stays off,
    # a re-bake keeps the user's flags, and Restore sets them all back.
    vis = world.cycles_visibility
    vis.scatter = False
    before = harness.tree_snapshot(world)
    bake(count=8, replace_reflections=False)
    bake(count=8, replace_reflections=False)
    assert (vis.camera, vis.diffuse, vis.glossy, vis.transmission, vis.scatter) == (True, False, True, True, False)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert harness.tree_snapshot(world) == before and not vis.scatter and vis.diffuse
    vis.scatter = True
