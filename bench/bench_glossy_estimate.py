"""Does the evaluator's glossy effect say what a renderer does with lamps that light reflections (EEVEE, where the
lamps light everything; Cycles with Lamps replace the world's Reflections; glTF and USD lights in other renderers)?
For each probe and count, bakes with the add-on (its defaults, Reflections on: the world lights nothing, the
camera still sees it) and sets side by side:
  estimate  the evaluator's glossy error of the scene's lamps (native evaluate(): normalized Phong lobes,
            exponents 8 and 64, around 256 directions, relative RMS of luminance, the two lobes' as one RMS);
  rendered  a white Glossy BSDF (GGX) ball alone, seen by an orthographic camera, in Cycles: the lamps against the
            world, relative RMS of luminance over the ball's 4x4-pixel blocks, at roughness 0.3 and 0.5 (the
            lobes' widths: a Phong lobe of exponent n about the reflected direction is about a Blinn-Phong lobe of
            4n about the normal, Beckmann's alpha = sqrt(2 / (4n + 2)) (Walter et al. 2007), Blender's
            roughness = sqrt(alpha): 0.30 for 64, 0.49 for 8), and the two as one RMS.
An orthographic view of a mirror ball sees every reflected direction with the same solid angle per pixel (4 / R^2),
as the evaluator's 256 directions are spread evenly, so the two weigh directions alike.

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_glossy_estimate.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [NAME,NAME,... [SAMPLES [COUNTS]]]

(NAME: probe file names without their extension, or "all"; 256 samples and counts 16,64 by default)
"""
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
harness.install_addon(zip_path)
SAMPLES = int(rest[1]) if len(rest) > 1 else 256
COUNTS = [int(c) for c in rest[2].split(",")] if len(rest) > 2 else [16, 64]
PROBES = harness.named_probes(harness.bench_probes(shared, studio_lights=False), rest[0] if rest else "")
ROUGHNESS = (0.30, 0.49)  # the evaluator's Phong exponents 64 and 8 (above)
SIZE = 96
LUM = np.array([0.2126, 0.7152, 0.0722])


def ball_scene(probe):
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(probe))
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1, location=(0, 0, 0), segments=128, ring_count=64)
    bpy.ops.object.shade_smooth()
    mat, glossy = render_scene.bsdf_material("glossy", "ShaderNodeBsdfGlossy", Color=(1, 1, 1, 1))
    glossy.distribution = "GGX"
    bpy.context.active_object.data.materials.append(mat)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 2.0
    cam.location = (0, -5, 0)
    cam.rotation_euler = (math.radians(90), 0, 0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    render_scene.cycles_output(scene, SIZE, SIZE, SAMPLES, bounces=1, transparent=True)
    return scene, glossy


def ball_blocks(picture):
    """Luminance of the 4x4 blocks wholly inside the ball (its rim left out: the picture's edge pixels)."""
    y = picture[..., :3] @ LUM
    yy, xx = np.mgrid[0:SIZE, 0:SIZE]
    r = np.hypot((xx + 0.5) / SIZE * 2 - 1, (yy + 0.5) / SIZE * 2 - 1)
    inside = (r < 0.97).reshape(SIZE // 4, 4, SIZE // 4, 4).all(axis=(1, 3))
    return y.reshape(SIZE // 4, 4, SIZE // 4, 4).mean(axis=(1, 3))[inside]


def renders(scene, glossy):
    out = []
    for roughness in ROUGHNESS:
        glossy.inputs["Roughness"].default_value = roughness
        out.append(ball_blocks(render_scene.render()))
    return out


def relative(truths, gots):
    """Per roughness rel. RMS, and the two as one RMS (weighted by the truth's sum of squares, as the evaluator)."""
    rels = [math.sqrt(((g - t) ** 2).sum() / (t ** 2).sum()) for t, g in zip(truths, gots)]
    tt = [(t ** 2).sum() for t in truths]
    both = math.sqrt(sum(r * r * w for r, w in zip(rels, tt)) / sum(tt))
    return rels, both


def scene_lights():
    """The scene's sun lamps as the core's lights: the direction they shine from, rgb and cone angle."""
    suns = [o for o in bpy.context.scene.objects if o.type == "LIGHT" and o.data.type == "SUN"]
    direction = np.array([list(o.matrix_world.to_3x3().col[2]) for o in suns])
    rgb = np.array([[o.data.energy * c for c in o.data.color] for o in suns])
    angle = np.array([o.data.angle for o in suns])
    return {"direction": direction, "rgb": rgb, "angle": angle}


def probe_pixels(probe):
    img = bpy.data.images.load(probe, check_existing=True)
    w, h = img.size[:]
    a = np.empty(w * h * 4, np.float32)
    img.pixels.foreach_get(a)
    return np.ascontiguousarray(a.reshape(h, w, 4)[::-1, :, :3])


native = harness.native()
print("| probe | lamps | noise (seed 2), roughness 0.3 / 0.49 | rendered, roughness 0.3 / 0.49 | rendered, both "
      "| estimate (evaluator glossy) | diffuse / shadow estimate |")
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    name = os.path.basename(probe)
    pixels = probe_pixels(probe)
    for count in COUNTS:
        scene, glossy = ball_scene(probe)
        world = renders(scene, glossy)
        scene.cycles.seed = 2
        noise, _ = relative(world, renders(scene, glossy))
        scene.cycles.seed = 1
        assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=count, lamps_take="ALL", replace_diffuse=True,
                                         replace_reflections=True) == {"FINISHED"}
        lamps = renders(scene, glossy)
        rels, both = relative(world, lamps)
        est = native.evaluate(pixels, scene_lights(), effects="diffuse,shadow,glossy")
        print("| %s | %d | %.2f / %.2f %% | %.2f / %.2f %% | %.2f %% | %.2f %% | %.2f / %.2f %% |" % (
            name, count, 100 * noise[0], 100 * noise[1], 100 * rels[0], 100 * rels[1], 100 * both,
            100 * est["glossy"], 100 * est["diffuse"], 100 * est["shadow"]), flush=True)
print("Blender %s, %d Cycles samples, %dx%d" % (bpy.app.version_string, SAMPLES, SIZE, SIZE))
sys.stdout.flush()
os._exit(0)  # as the other benches: bpy's teardown is not needed
