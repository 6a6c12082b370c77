"""The add-on as a user meets it: installed from the zip into a fresh profile, baking real probes through every
kind of world, re-baking, restoring, undoing, and refusing bad worlds with a one-line report."""

import glob
import math
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402

ARGS = harness.args()
addon = harness.install_addon(ARGS.zip)
_probelights = harness.native()
light_objects, world_mix, conversion = (harness.addon_module(n) for n in ("light_objects", "world_mix", "conversion"))

LUM = np.array([0.2126, 0.7152, 0.0722])


def bake(**settings):
    result = bpy.ops.probe_lights.bake("EXEC_DEFAULT", **settings)
    assert result == {"FINISHED"}, result
    return light_objects.baked_lights(bpy.context.scene.world)


def irradiance(obj):
    """What a baked sun gives a facing surface, per channel (W/m^2): a wide Cycles sun gives less than its
    strength (conversion.sun_normal_irradiance, checked in Cycles by test_render.py)."""
    factor = conversion.sun_normal_irradiance(obj.data.angle, bpy.app.version)
    return np.array(obj.data.color) * obj.data.energy * factor


def sun_direction(obj):
    """Where a sun shines from (unit length: the add-on draws its suns at a small scale)."""
    d = np.array(obj.matrix_world.to_3x3().col[2])
    return d / np.linalg.norm(d)


def real_probes():
    files = sorted(glob.glob(os.path.join(ARGS.shared, "hdri", "*.hdr")) + glob.glob(os.path.join(ARGS.shared, "hdri", "*.exr")))
    if not files:
        print("  skipped: ../shared not found (its probes); using the bundled probe and Blender's studio lights")
        files = [harness.BUNDLED_PROBE]
    files += sorted(glob.glob(os.path.join(harness.studiolights(ARGS), "*.exr")))
    assert len(files) > 1, "no probes found"
    return files


def test_register_unregister():
    assert hasattr(bpy.types.Scene, "probe_lights") and hasattr(bpy.ops.probe_lights, "bake")
    bpy.ops.preferences.addon_disable(module=harness.ADDON)
    assert not hasattr(bpy.types.Scene, "probe_lights")
    assert not hasattr(bpy.types, "PROBE_LIGHTS_PT_world")
    bpy.ops.preferences.addon_enable(module=harness.ADDON)
    assert hasattr(bpy.types.Scene, "probe_lights") and hasattr(bpy.types, "PROBE_LIGHTS_PT_world")


def test_real_probes_bake_with_their_energy():
    for path in real_probes():
        harness.empty_scene()
        image = bpy.data.images.load(path)
        harness.env_world(image, strength=1.5)
        lights = bake(count=16, refit=False)  # the regions' sums; the refit moves them (its note says how much)
        assert len(lights) == 16, (path, len(lights))
        # Reference: the same pixels Blender holds, through the add-on's own module.
        pixels = np.empty(image.size[0] * image.size[1] * image.channels, np.float32)
        image.pixels.foreach_get(pixels)
        pixels = pixels.reshape(image.size[1], image.size[0], image.channels)[::-1]
        reference = _probelights.bake(pixels, lights=1)["total_rgb"]
        total = sum(irradiance(o) for o in lights)
        rel = np.abs(total - 1.5 * reference) / (1.5 * reference)
        assert rel.max() < 1e-5, (path, total, reference)
        for o in lights:
            assert o.data.type == "SUN" and 0 <= o.data.angle <= math.pi and o.data.energy >= 0
        print("  %-32s 16 suns, energy matches to %.1e, brightest %.0f%%" % (
            os.path.basename(path), rel.max(), 100 * max(irradiance(o) @ LUM for o in lights) / (total @ LUM)))


def bright_spot_world(direction_pixel, size=(128, 64), projection="EQUIRECTANGULAR", **world):
    w, h = size
    a = np.full((h, w, 3), 0.01, np.float32)
    x, y = direction_pixel
    a[y, x] = 1000.0
    img = harness.float_image("spot", a)
    return harness.env_world(img, projection=projection, **world)


def latlong_direction(x, y, w, h):
    phi, el = 2 * math.pi * (0.5 - (x + 0.5) / w), math.pi / 2 - math.pi * (y + 0.5) / h
    return np.array([math.cos(el) * math.cos(phi), math.cos(el) * math.sin(phi), math.sin(el)])


def brightest(lights):
    return max(lights, key=lambda o: irradiance(o) @ LUM)


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


def test_every_method_bakes():
    harness.empty_scene()
    bright_spot_world((40, 20))
    for method in ("auto", "both", "variance", "median-cut", "sh"):
        lights = bake(count=6, method=method)
        assert len(lights) == 6, (method, len(lights))
        assert harness.angle_deg(sun_direction(brightest(lights)), latlong_direction(40, 20, 128, 64)) < 0.5, method


def test_auto_fits_both_cuts_up_to_16_lights():
    """Auto (the default) fits variance and median cut up to 16 lights and keeps the better, says which in the
    notes; above 16 it starts both and fits the better alone; Both cuts fits both at any count; a tolerance
    never does either."""
    harness.empty_scene()
    bright_spot_world((40, 20))
    settings = bpy.context.scene.probe_lights
    assert settings.bl_rna.properties["method"].default == "auto"
    for method, count, note in (("auto", 16, "both cuts fitted:"), ("auto", 17, "both cuts started:"),
                                ("both", 24, "both cuts fitted:"), ("variance", 8, None)):
        bake(count=count, method=method)
        said = [n for n in ("both cuts fitted:", "both cuts started:") if n in settings.last_notes]
        assert said == ([note] if note else []), (method, count, settings.last_notes)
        assert "both cuts" not in settings.last_warnings, settings.last_warnings
    bake(method="both", count_mode="TOLERANCE", max_error=5.0)
    assert "both cuts" not in settings.last_notes and "auto count" in settings.last_notes, settings.last_notes


def test_estimated_errors_and_count_by_tolerance():
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    settings = bpy.context.scene.probe_lights
    bake(count=16)
    assert 0 < settings.last_diffuse_error < 10 and 0 < settings.last_shadow_error < 20, (
        settings.last_diffuse_error, settings.last_shadow_error)
    lights = bake(count_mode="TOLERANCE", max_error=1.5)
    assert settings.last_diffuse_error <= 1.5 and settings.last_shadow_error <= 1.5
    assert "auto count" in settings.last_notes, settings.last_notes
    print("  1.5 %% tolerance: %d lights, diffuse %.2f %%, shadow %.2f %%" % (
        len(lights), settings.last_diffuse_error, settings.last_shadow_error))
    refit = bake(count=16, refit=True)
    assert len(refit) == 16
    # Refit is the default, and the results say where the strengths went (a wide sun gives a facing surface more
    # light than its strength, so they sum to less than the world's); a count past what it takes bakes without
    # it, saying so.
    assert bpy.context.scene.probe_lights.bl_rna.properties["refit"].default is True
    bake(count=16)
    assert 85.0 < settings.last_energy < 100.0, settings.last_energy
    many = bake(count=300)
    assert len(many) == 300, len(many)
    assert "the refit takes at most 256 lights: 300 lights baked without it" in settings.last_warnings, \
        settings.last_warnings


def test_more_suns_than_pay_off_are_reported_with_this_versions_measurements():
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    settings = bpy.context.scene.probe_lights
    render_cost = harness.addon_module("render_cost")
    best = render_cost.sweet_spot(bpy.app.version)
    bake(count=best)
    assert "no closer in Cycles" not in settings.last_notes + settings.last_warnings, settings.last_notes
    bake(count=2 * best)
    if not hasattr(bpy.context.scene.cycles, "use_light_tree"):
        # Cycles 3.x: the warning that many lamps render noisily says it, once.
        assert "no light tree" in settings.last_warnings, settings.last_warnings
        assert "More than" not in settings.last_notes, settings.last_notes
        return
    measured = render_cost.measured_version(bpy.app.version)
    assert "More than %d suns" % best in settings.last_notes, settings.last_notes
    assert "no closer in Cycles %d.%d" % measured[:2] in settings.last_notes, settings.last_notes
    assert "no closer" not in settings.last_warnings, settings.last_warnings  # a note, not a warning
    note = [n for n in settings.last_notes.split("\n") if "no closer in Cycles" in n][0]
    print("  note at %d suns: %s" % (2 * best, note))


def test_tradeoff_in_the_panel():
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    before = harness.tree_snapshot(world)
    assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    rows = bpy.context.scene.probe_lights.tradeoff
    plain = {r.lights: r.diffuse for r in rows if not r.refit}
    assert sorted(plain) == [4, 8, 16, 32, 64, 128, 256] and plain[256] < plain[4]
    for r in rows:  # a click's time counts reading the world and making the lamps, not only the bake
        assert r.click_ms > r.bake_ms > 0, (r.lights, r.click_ms, r.bake_ms)
    assert harness.tree_snapshot(world) == before and not light_objects.baked_lights(bpy.context.scene.world)
    assert bpy.ops.probe_lights.set_count(count=32) == {"FINISHED"}
    assert bpy.context.scene.probe_lights.count == 32
    print("  tradeoff: " + ", ".join("%d: %.2f %%" % (n, 100 * e) for n, e in sorted(plain.items())))


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


def test_lamps_light_the_effects_of_their_split_and_sample_by_importance_only_with_reflections():
    """Which effects the lamps light (Cycles' ray visibility; in EEVEE every effect) and whether Cycles reaches them
    by multiple importance sampling: off unless they light reflections, where Cycles has a light tree (3.5+;
    docs/glossy.md)."""
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


def expect_report(text):
    """The bake fails with one ERROR report containing `text` (from Python an operator's error report is raised)."""
    try:
        bpy.ops.probe_lights.bake("EXEC_DEFAULT")
    except RuntimeError as e:
        message = str(e).strip()
        assert text in message and "\n" not in message, message
        print("  report: " + message)
        return
    raise AssertionError("the bake did not fail")


def test_bad_worlds_are_one_line_reports():
    harness.empty_scene()
    bpy.context.scene.world = None
    expect_report("the scene has no world")
    world = harness.env_world(None)
    expect_report("has no image")
    missing = bpy.data.images.new("missing", 4, 4, float_buffer=True)
    missing.source = "FILE"
    missing.filepath = "/nonexistent/probe.exr"
    missing.reload()
    world.node_tree.nodes["Environment Texture"].image = missing
    before = harness.tree_snapshot(world)
    expect_report("is its file missing?")
    assert harness.tree_snapshot(world) == before, "a failed bake leaves the world alone"
    nan = np.ones((8, 16, 3), np.float32)
    nan[2, 3, 1] = np.nan
    world.node_tree.nodes["Environment Texture"].image = harness.float_image("nan", nan)
    expect_report("1 NaN/Inf samples, first at pixel (3, 2); to read them as 0: set NaN/Inf pixels to Zero")
    assert not light_objects.baked_lights(bpy.context.scene.world)



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


def lamp_state(world):
    """Each baked lamp's world direction (suns: where they shine from) and its strength, in bake order."""
    bpy.context.view_layer.update()
    lamps = sorted(light_objects.baked_lights(world), key=lambda o: o.name)
    return np.array([sun_direction(o) for o in lamps]), np.array([o.data.energy for o in lamps])


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
    for o in lamps:  # as the add-on left them until 2026-12-05
        del o[light_objects.RAYS_KEY]
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


def test_tolerance_never_backfires():
    """A tolerance no count meets: the count with the lowest error found, said in the report, never more lights
    than a count that did better. The probe is log-normal noise (sigma 3, 256 x 128): its shadows stay above the
    smallest tolerance (0.05 %) up to the most lights tried, 1024 (0.16 % measured); a real probe meets it."""
    harness.empty_scene()
    rng = np.random.default_rng(1)
    noise = np.exp(3 * rng.standard_normal((128, 256, 1))).repeat(3, 2)
    harness.env_world(harness.float_image("noise", noise))
    settings = bpy.context.scene.probe_lights
    lamps = bake(count_mode="TOLERANCE", max_error=0.05)
    worst = max(settings.last_diffuse_error, settings.last_shadow_error)
    assert "no count met the tolerance" in settings.last_report, settings.last_report
    assert "no count met the tolerance" in settings.last_warnings
    n = len(lamps)
    for m in (8, 16, 32, 64, 128):
        bake(count=m)
        other = max(settings.last_diffuse_error, settings.last_shadow_error)
        assert not (m < n and other < worst - 1e-6), (m, other, n, worst)
    print("  tolerance 0.05 %%: %d lights, worst error %.2f %%" % (n, worst))


def test_cycles_settings_offer_and_restore():
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.cycles.sample_clamp_indirect = 10.0
    has_tree = hasattr(scene.cycles, "use_light_tree")
    if has_tree:
        scene.cycles.use_light_tree = False
    bake(count=64)
    # The measured cost (cycles_clamp.json, render_cost.json): the clamp in 3.4 (no light tree); the light tree
    # switched off in 4.x and later, where the clamp darkens nothing measurable and is not mentioned.
    expected = "indirect clamp (10)" if not has_tree else "light tree is off"
    assert expected in scene.probe_lights.last_warnings, scene.probe_lights.last_warnings
    assert not has_tree or "indirect clamp" not in scene.probe_lights.last_warnings, scene.probe_lights.last_warnings
    assert bpy.ops.probe_lights.cycles_settings() == {"FINISHED"}
    assert scene.cycles.sample_clamp_indirect == 0.0 and (not has_tree or scene.cycles.use_light_tree)
    assert harness.addon_module("cycles_settings").advice(scene, 64) == ""
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert scene.cycles.sample_clamp_indirect == 10.0 and (not has_tree or not scene.cycles.use_light_tree)


def test_eevee_shadow_pool_follows_the_scene_and_restore():
    """EEVEE Next (4.2+) keeps shadows in a pool that about 19 suns fill: a bake in EEVEE makes room by itself,
    without ever shrinking the pool or going past 1 GB, and says so; so does a render in EEVEE of suns baked under
    Cycles; the offer in the panel does it too; Restore world puts the user's values back."""
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.render.engine = harness.eevee_engine()
    settings = scene.probe_lights
    shadows = harness.addon_module("eevee_settings")
    if bpy.app.version < (4, 2, 0):  # EEVEE Legacy has no shadow pool
        bake(count=64)
        assert "EEVEE" not in settings.last_notes and shadows.advice(scene, 64) == ""
        print("  skipped: EEVEE Legacy (Blender %s) has no shadow pool" % bpy.app.version_string)
        return
    scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale = "512", 1.0
    bake(count=16)  # 16 suns: about 1,900 pages, the default pool holds 2,048
    assert "EEVEE" not in settings.last_notes and not shadows.fitted(scene), settings.last_notes
    bake(count=30)  # about 3,500 pages: a 1 GB pool at full resolution
    assert "EEVEE: shadow pool 1024 MB" in settings.last_notes, settings.last_notes
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("1024", 1.0)
    bake(count=64)  # more than 1 GB holds at full resolution: half resolution in the pool already set
    assert shadows.advice(scene, 64) == "" and shadows.baked_suns(scene) == 64
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("1024", 0.5)
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert (scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale) == ("512", 1.0)
    # Baked under Cycles (no pool to fit), then set to EEVEE: the panel says what to do in one line, the offer
    # does it, and Restore puts it back.
    scene.render.engine = "CYCLES"
    bake(count=30)
    assert not shadows.fitted(scene) and scene.eevee.shadow_pool_size == "512"
    scene.render.engine = harness.eevee_engine()
    line = shadows.advice(scene, shadows.baked_suns(scene))
    assert line == ("EEVEE's shadow pool is too small for 30 suns and drops shadows at random: fit the shadows to "
                    "the lamps"), line
    assert bpy.ops.probe_lights.eevee_settings() == {"FINISHED"} and shadows.advice(scene, 30) == ""
    assert bpy.ops.probe_lights.restore() == {"FINISHED"} and scene.eevee.shadow_pool_size == "512"
    scene.eevee.shadow_resolution_scale = 0.75  # between two measured scales: costed as the finer one
    assert shadows._pages(2140, 0.75) == 2354
    scene.eevee.shadow_resolution_scale = 1.0
    scene.render.engine = "CYCLES"


def test_the_read_buffer_is_reused_only_when_nobody_holds_it():
    """Pixels are read into a buffer kept for the next read (an 8K read into fresh memory costs 2x more), but never
    into one whose pixels somebody still holds (a running tradeoff): that read gets a buffer of its own."""
    world_image = harness.addon_module("world_image")
    img = harness.float_image("reused", np.arange(8 * 16 * 3, dtype=np.float32).reshape(8, 16, 3))
    a = world_image.image_pixels(img)
    held = a.copy()
    b = world_image.image_pixels(img)  # a is still held: b must not overwrite it
    assert b.base is not a.base and np.array_equal(a, b) and np.array_equal(a, held)
    del a
    kept = id(world_image._kept[0])  # an id, not a reference: holding the buffer would keep it from reuse
    assert id(b.base) == kept
    del b
    c = world_image.image_pixels(img)  # nobody holds the kept buffer now: reused
    assert id(c.base) == kept and np.array_equal(c, held)
    img.pixels[0] = -7.0  # bottom-left red in Blender's rows: the last row of ours
    d = world_image.image_pixels(img)
    assert id(d.base) != kept and d[-1, 0, 0] == -7.0 and np.array_equal(c, held), (d[-1, 0, 0], c[-1, 0, 0])


def test_the_cores_table_buffers_are_given_back_a_minute_after_the_last_bake():
    """The core keeps its last tables' buffers for the next bake (no fresh memory to map: 2K, 37 ms a click) and
    the add-on gives them back KEEP_SECONDS after the last bake (a timer; in background mode the test calls it)."""
    native = harness.addon_module("native")
    harness.empty_scene()
    harness.env_world(harness.float_image("kept", np.ones((64, 128, 3), np.float32)))
    bake(count=4)
    assert bpy.app.timers.is_registered(native._release_buffers)
    assert native.KEEP_SECONDS == 60.0
    native._release_buffers()  # what the timer does
    bake(count=4)  # and bakes go on after it
    assert len(light_objects.baked_lights(bpy.context.scene.world)) == 4


def test_inputs_that_are_not_what_they_claim():
    harness.empty_scene()
    settings = bpy.context.scene.probe_lights
    harness.env_world(harness.float_image("wide", np.ones((200, 300, 3), np.float32)))
    bake(count=4)
    assert "is 300x200, not 2:1" in settings.last_warnings, settings.last_warnings
    nan = np.ones((8, 16, 3), np.float32)
    nan[2, 3, 1] = np.inf
    harness.env_world(harness.float_image("nan", nan))
    bake(count=4, non_finite="zero")
    assert "read 1 NaN/Inf samples as 0" in settings.last_warnings, settings.last_warnings


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

class RecordingLayout:
    """Stands in for a panel's layout in background mode (no window): records labels, props and operators."""

    def __init__(self, log):
        self.log, self.enabled, self.scale_y = log, True, 1.0

    def _child(self, *args, **kwargs):
        return RecordingLayout(self.log)

    column = row = box = split = _child

    def label(self, text="", icon="NONE"):
        self.log.append(("label", text))

    def prop(self, data, name, **kwargs):
        assert hasattr(data, name), name
        self.log.append(("prop", name))

    def operator(self, idname, **kwargs):
        module, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, module), name), idname
        self.log.append(("operator", idname))
        return type("Props", (), {})()


def test_another_platforms_zip_is_refused_and_the_installed_one_kept():
    """Each zip names its one platform (addon/package.cmake): Blender 4.2+ refuses another platform's zip, and the
    add-on already installed stays as it was, enabled, with its own modules."""
    if bpy.app.version < (4, 2, 0):
        print("  skipped: Blender %s installs legacy add-ons, which name no platform" % bpy.app.version_string)
        return
    here = "windows_x64" if sys.platform == "win32" else "linux_x64"
    other = "linux_x64" if here == "windows_x64" else "windows_x64"
    wrong = ARGS.zip.replace("-%s.zip" % here, "-%s.zip" % other)
    if wrong == ARGS.zip or not os.path.exists(wrong):
        print("  skipped: no %s zip beside %s" % (other, ARGS.zip))
        return
    package = os.path.dirname(harness.addon_module("native").__file__)
    modules = lambda: sorted(os.path.basename(m) for m in glob.glob(os.path.join(package, "_probelights.*")))  # noqa
    before = modules()
    bpy.ops.extensions.package_install_files(filepath=wrong, repo="user_default", enable_on_install=True)
    assert harness.ADDON in bpy.context.preferences.addons
    assert modules() == before and before, (before, modules())
    print("  %s refused by Blender %s; %s kept" % (os.path.basename(wrong), bpy.app.version_string, here))


def test_panel_draws_at_default_width_in_this_blender():
    """The panel's drawing code in this Blender (fonts, preferences, operators it names), as the World properties
    editor at its default width would call it, after a bake with warnings and a tradeoff: every line fits."""
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.cycles.sample_clamp_indirect = 10.0
    if hasattr(scene.cycles, "use_light_tree"):
        scene.cycles.use_light_tree = False
    bake(count=128)
    assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    ui = harness.addon_module("ui")
    for region_type, width in (("WINDOW", 303), ("UI", 229)):
        log = []
        region = type("Region", (), {"type": region_type, "width": width})()
        context = type("Context", (), {"scene": scene, "region": region, "preferences": bpy.context.preferences})()
        ui.draw_panel(RecordingLayout(log), context)
        labels = [text for kind, text in log if kind == "label"]
        assert ("operator", "probe_lights.bake") in log and ("operator", "probe_lights.cycles_settings") in log
        assert any("Error: diffuse" in t for t in labels) and len(labels) > 20, labels
        assert not ui.OVERFLOW, (region_type, ui.OVERFLOW)
    print("  panel drawn at 303 and 229 px: %d labels, none cut" % len(labels))


harness.run([test_register_unregister, test_real_probes_bake_with_their_energy,
             test_strength_and_rotation_carry_into_the_lights, test_every_method_bakes,
             test_auto_fits_both_cuts_up_to_16_lights,
             test_estimated_errors_and_count_by_tolerance,
             test_more_suns_than_pay_off_are_reported_with_this_versions_measurements, test_tradeoff_in_the_panel, test_node_group_and_reroute, test_mirror_ball_image,
             test_sky_texture_world_is_rendered, test_read_and_rendered_worlds_agree,
             test_plain_colour_world_and_its_restore,
             test_rebake_replaces_only_its_own_lights, test_restore_brings_the_world_back_exactly,
             test_lamps_light_the_effects_of_their_split_and_sample_by_importance_only_with_reflections,
             test_bad_worlds_are_one_line_reports,
             test_point_lights_give_the_same_irradiance_at_the_origin,
             test_lamps_follow_the_worlds_rotation_and_strength, test_suns_on_a_dome_around_the_scene_under_one_rig,
             test_worlds_keep_their_own_lamps_and_mix, test_a_bake_by_version_0_1_is_adopted,
             test_lamps_of_an_earlier_bake_light_every_effect_in_eevee,
             test_the_bakes_nodes_are_framed_beside_the_users,
             test_tolerance_never_backfires, test_cycles_settings_offer_and_restore,
             test_eevee_shadow_pool_follows_the_scene_and_restore, test_the_read_buffer_is_reused_only_when_nobody_holds_it,
             test_the_cores_table_buffers_are_given_back_a_minute_after_the_last_bake,
             test_inputs_that_are_not_what_they_claim, test_thousands_of_lamps_go_in_one_batch,
             test_panel_draws_at_default_width_in_this_blender,
             test_another_platforms_zip_is_refused_and_the_installed_one_kept])
