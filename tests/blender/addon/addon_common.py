"""What the add-on's tests share (tests/blender/test_addon.py runs them, one subject a file here): the add-on
installed once from its zip, its modules, and the helpers that bake and read lamps."""

import glob
import math
import os

import bpy
import numpy as np

import harness

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


def expect_report(text, operator=None, **settings):
    """The bake (or `operator`, with `settings`) fails with one ERROR report containing `text` (from Python an
    operator's error report is raised)."""
    try:
        (operator or bpy.ops.probe_lights.bake)("EXEC_DEFAULT", **settings)
    except RuntimeError as e:
        message = str(e).strip()
        assert text in message and "\n" not in message, message
        print("  report: " + message)
        return
    raise AssertionError("the operator did not fail")


def lamp_state(world):
    """Each baked lamp's world direction (suns: where they shine from) and its strength, in bake order."""
    bpy.context.view_layer.update()
    lamps = sorted(light_objects.baked_lights(world), key=lambda o: o.name)
    return np.array([sun_direction(o) for o in lamps]), np.array([o.data.energy for o in lamps])
