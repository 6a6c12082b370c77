"""Which side of a rendered difference is off: the world or the lamps? On the estimate's shadow scene
(render_scene.ground_under_sphere, 16 x 16 ground points), renders the world and compares it with the probe's own
truth at the points (signed pixels, and with negatives read as 0), then bakes with the add-on's defaults and
compares the lamps' render with the sun model the estimate uses (a uniform cone in 4.0+, a disc of radius
tan(angle / 2) in 3.x; numerically integrated here, independent of the core):

  tests/blender/run.sh blender bench/render_vs_model.py build/probe_lights-0.1.0-linux_x64.zip ../shared
  PROBE=../shared/hdri/pmndrs_esplanade_dwab.exr N=16 SPP=4096 tests/blender/run.sh \\
      ~/.cache/probelights/bpy-4.5.15/bin/python bench/render_vs_model.py build/probe_lights-0.1.0-linux_x64.zip ../shared
"""
import math
import os
import sys

import bpy
import mathutils
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

SIZE = 16


def sun_model(axis, angle, p, disc, n=200):
    """Irradiance at p from a sun of strength 1 (Blender's units) along `axis`, its sphere shadow included."""
    t1 = np.cross(axis, [0, 0, 1.0]) if abs(axis[2]) < 0.9 else np.cross(axis, [1.0, 0, 0])
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(axis, t1)
    g = (np.arange(n) + 0.5) / n
    if disc:  # uniform over the disc's area: Cycles 3.x's pdf and radiance (1 / cos^3) cancel per area
        r = math.tan(angle / 2) * np.sqrt(g)[:, None]
        ph = 2 * math.pi * g[None, :]
        x, y = (r * np.cos(ph)).ravel(), (r * np.sin(ph)).ravel()
        d = axis[None] + x[:, None] * t1 + y[:, None] * t2
        d /= np.linalg.norm(d, axis=1)[:, None]
        weight = np.full(len(d), 1.0 / len(d))
    else:  # uniform in solid angle, normalized to give 1 on a facing surface
        c = np.broadcast_to(1 - g[:, None] * (1 - math.cos(angle / 2)), (n, n)).ravel()
        ph = np.broadcast_to(2 * math.pi * g[None, :], (n, n)).ravel()
        s = np.sqrt(1 - c * c)
        d = c[:, None] * axis + (s * np.cos(ph))[:, None] * t1 + (s * np.sin(ph))[:, None] * t2
        weight = np.full(len(d), 1.0 / len(d)) / np.mean(d @ axis)
    return float(np.sum(weight * np.clip(d[:, 2], 0, None) * ~render_scene.hidden_by_sphere(d, p)))


def rms(got, truth):
    return 100 * float(np.sqrt(np.mean((got - truth) ** 2) / np.mean(truth ** 2)))


harness.install_addon(harness.args().zip)
probe = os.environ.get("PROBE", harness.BUNDLED_PROBE)
harness.empty_scene()
image = bpy.data.images.load(probe)
world = harness.env_world(image)
world.node_tree.nodes["Environment Texture"].interpolation = "Closest"  # the pixels as they are
render_scene.ground_under_sphere(int(os.environ.get("SPP", "4096")))
world_render = math.pi * (render_scene.render()[..., :3] @ render_scene.LUM).ravel()
signed, clamped = (math.pi * render_scene.ground_truth(image, negatives_as_zero=z)[..., 0].ravel()
                   for z in (False, True))
print("Blender %s, %s: world render vs the probe's truth %.2f %% (means %.4f / %.4f), vs the truth with negatives "
      "as 0 %.2f %% (%.4f)" % (bpy.app.version_string, os.path.basename(probe), rms(world_render, signed),
                               world_render.mean(), signed.mean(), rms(world_render, clamped), clamped.mean()))
bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=int(os.environ.get("N", "16")), shadows="FIT")
lamps_render = math.pi * (render_scene.render()[..., :3] @ render_scene.LUM).ravel()
model = np.zeros(SIZE * SIZE)
disc = bpy.app.version < (4, 0, 0)
for o in (o for o in bpy.context.scene.objects if o.type == "LIGHT"):
    axis = np.array(o.matrix_world.to_3x3() @ mathutils.Vector((0, 0, 1)))
    axis /= np.linalg.norm(axis)  # the lamps' rig scales them
    strength = float(np.array(o.data.color) @ render_scene.LUM) * o.data.energy
    model += strength * np.array([sun_model(axis, o.data.angle, p, disc) for p in render_scene.ground_points(SIZE)])
print("lamps render vs their model %.2f %% (means %.4f / %.4f); estimate %.2f %%, lamps render vs world render "
      "%.2f %%, vs the truth %.2f %%" % (rms(lamps_render, model), lamps_render.mean(), model.mean(),
                                         bpy.context.scene.probe_lights.last_shadow_error,
                                         rms(lamps_render, world_render), rms(lamps_render, signed)))
