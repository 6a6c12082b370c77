"""The render tests' cache (harness/render_cache.py) must never hand back a render of another scene: every change
that can change a picture changes the key, and the same scene built twice has the same key. No Cycles render is made;
EEVEE renders 32 x 24 pixels twice.

    tests/blender/run.sh blender tests/blender/test_render_cache.py build/probe_lights-0.1.0-linux_x64.zip ../shared
"""

import math
import os
import sys
import tempfile

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402
import render_cache  # noqa: E402
import render_scene  # noqa: E402

ARGS = harness.args()
harness.install_addon(ARGS.zip)
render_cache.FOLDER = tempfile.mkdtemp()


def scene_of_the_tests():
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE), rotation=(0.0, 0.0, 0.5))
    render_scene.sphere_over_plane(64, 48, 16)
    return bpy.context.scene, world


def node(tree, idname):
    return next(n for n in tree.nodes if n.bl_idname == idname)


def changes(scene, world):
    """(what, a function that changes it, one that puts it back): each must change the key."""
    sphere = next(o for o in scene.objects if o.type == "MESH" and len(o.data.vertices) > 4)
    material = sphere.active_material
    bsdf = next(n for n in material.node_tree.nodes if "Bsdf" in n.bl_idname)
    colour = bsdf.inputs[0].default_value[:]
    image = next(i for i in bpy.data.images if i.source == "FILE")
    mapping, background = node(world.node_tree, "ShaderNodeMapping"), world.node_tree.nodes["Background"]
    lamp = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "SUN"))
    scene.collection.objects.link(lamp)

    def setter(owner, name, value):
        old = getattr(owner, name)
        old = old[:] if hasattr(old, "__len__") and not isinstance(old, str) else old
        return lambda: setattr(owner, name, value), lambda: setattr(owner, name, old)

    def pixel(value):
        def f():
            a = np.empty(len(image.pixels), np.float32)
            image.pixels.foreach_get(a)
            a[4 * 1000] = value
            image.pixels.foreach_set(a)
        return f

    first = image.pixels[4 * 1000]
    driven = lamp.data.driver_add("energy")
    driven.driver.expression = "1.0"
    return [
        ("the world's rotation", *setter(mapping.inputs["Rotation"], "default_value", (0.0, 0.0, 0.6))),
        ("the world's strength", *setter(background.inputs["Strength"], "default_value", 2.0)),
        ("a material's colour", lambda: setattr(bsdf.inputs[0], "default_value", (0.1, 0.2, 0.3, 1.0)),
         lambda: setattr(bsdf.inputs[0], "default_value", colour)),
        ("an object's place", *setter(sphere, "location", (0.0, 0.0, 0.01))),
        ("an object hidden", *setter(sphere, "hide_render", True)),
        ("the camera's lens", *setter(scene.camera.data, "lens", 36.0)),
        ("a pixel of the probe", pixel(first + 1.0), pixel(first)),
        ("the samples", *setter(scene.cycles, "samples", 17)),
        ("the seed", *setter(scene.cycles, "seed", 3)),
        ("the resolution", *setter(scene.render, "resolution_x", 65)),
        ("the film", *setter(scene.render, "film_transparent", not scene.render.film_transparent)),
        ("a lamp's angle", *setter(lamp.data, "angle", 0.3)),
        ("a lamp's direction", *setter(lamp, "rotation_euler", (0.3, 0.0, 0.0))),
        ("a lamp's rays", *setter(lamp, "visible_diffuse", False)),
        ("a driver", lambda: setattr(driven.driver, "expression", "2.0"),
         lambda: setattr(driven.driver, "expression", "1.0")),
        ("an ID property", lambda: lamp.__setitem__("probe_lights_test", 1), lambda: lamp.pop("probe_lights_test")),
    ]


def test_every_change_to_what_a_render_reads_changes_the_key():
    scene, world = scene_of_the_tests()
    for what, change, back in changes(scene, world):
        before = render_cache.key(scene)
        change()
        changed = render_cache.key(scene)
        back()
        assert changed != before, "the key missed %s" % what
        assert render_cache.key(scene) == before, "the key did not come back after %s" % what


def test_the_same_scene_built_again_has_the_same_key():
    first = render_cache.key(scene_of_the_tests()[0])
    scene = scene_of_the_tests()[0]
    second = render_cache.key(scene)
    assert first is not None and first == second
    # The add-on's settings in a file opened without it: a plain group, its timings in it.
    scene["settings_of_an_addon_not_here"] = {"count": 32, "last_ms": 145.9}
    with_settings = render_cache.key(scene)
    scene["settings_of_an_addon_not_here"]["last_ms"] = 146.7
    assert render_cache.key(scene) == with_settings, "a timing changed the key"
    scene["settings_of_an_addon_not_here"]["count"] = 16
    assert render_cache.key(scene) != with_settings, "the key missed a setting in an ID property group"
    del scene["settings_of_an_addon_not_here"]


def test_what_is_not_remembered():
    scene, _ = scene_of_the_tests()
    if render_cache._gpu() is None:  # no EEVEE render yet in this process
        scene.render.engine = harness.eevee_engine()
        assert render_cache.key(scene) is None  # the OpenGL driver is not known yet
    scene.render.engine = "CYCLES"
    image = next(i for i in bpy.data.images if i.source == "FILE")
    image.source = "SEQUENCE"
    assert render_cache.key(scene) is None  # its pixels are the frame's
    image.source = "FILE"
    folder, render_cache.FOLDER = render_cache.FOLDER, ""
    assert render_cache.key(scene) is None  # not asked for
    render_cache.FOLDER = folder


def test_a_remembered_render_of_another_scene_fails_the_verification():
    k = "f" * 64
    pixels = np.full((4, 4, 4), 0.5, np.float32)
    render_cache.store(k, pixels)
    assert np.array_equal(render_cache.lookup(k), pixels)
    render_cache.store(k, pixels, pixels + 1e-6)  # float rounding: the same render
    try:
        render_cache.store(k, pixels, pixels * 1.03)  # another seed is ~3e-2 apart
    except AssertionError as e:
        assert "misses a property" in str(e), e
    else:
        raise AssertionError("a render 3 % apart was taken for the remembered one")
    assert math.isclose(float(render_cache.lookup(k)[0, 0, 0]), 0.5)


def test_eevee_is_remembered_with_what_it_printed():
    """EEVEE renders are remembered once its OpenGL driver is known (after its first render in the process), with
    what Blender printed making them (ctest reads it: "Shadow buffer full" fails a test), and never with a light
    probe in the scene (its baked light is outside RNA). Two renders of 32 x 24 pixels are made, the third asked for
    is remembered."""
    if bpy.app.version < (4, 2, 0):
        print("  skipped: EEVEE Legacy renders only under X (Blender %s)" % bpy.app.version_string)
        return
    scene, _ = scene_of_the_tests()
    scene.render.engine = harness.eevee_engine()
    scene.render.resolution_x, scene.render.resolution_y = 32, 24
    scene.eevee.taa_render_samples = 1
    if render_cache._gpu() is None:
        render_scene.render()  # the first EEVEE render of the process: made, not remembered
    k = render_cache.key(scene)
    assert k is not None and render_cache.lookup(k) is None
    made = render_scene.render()
    with open(render_cache._printed_path(k), "rb") as f:
        printed = f.read()
    print("  %d bytes printed while EEVEE rendered, remembered" % len(printed))
    # Blender's own line for the written file (its C code's output, past sys.stdout; 5.3 prints no "Fra:" lines)
    assert b"Saved: " in printed, printed[:200]
    assert np.array_equal(render_cache.lookup(k), made) and np.array_equal(render_scene.render(), made)
    probe = bpy.data.objects.new("probe", bpy.data.lightprobes.new("probe", "SPHERE"))
    scene.collection.objects.link(probe)
    assert render_cache.key(scene) is None
    data = probe.data
    bpy.data.objects.remove(probe)
    bpy.data.lightprobes.remove(data)
    assert render_cache.key(scene) == k
    scene.render.engine = "CYCLES"


harness.run([test_every_change_to_what_a_render_reads_changes_the_key,
             test_the_same_scene_built_again_has_the_same_key, test_what_is_not_remembered,
             test_a_remembered_render_of_another_scene_fails_the_verification,
             test_eevee_is_remembered_with_what_it_printed])
