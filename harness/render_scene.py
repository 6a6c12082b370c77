"""The diffuse sphere-over-plane scene the render comparisons use, rendered with Cycles, and how two renders are
compared (8x8-pixel block means of the lit pixels). Shared by test_render.py and bench/bench_render_counts.py."""

import math
import os
import tempfile

import bpy
import numpy as np

import render_cache

LUM = np.array([0.2126, 0.7152, 0.0722])
BLOCK = 8


def bsdf_material(name, node_type, **inputs):
    """A material of one BSDF node (e.g. "ShaderNodeBsdfGlossy") with the given inputs set. Returns (material,
    node)."""
    mat = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):  # 5.0 always uses a material's nodes (Material.use_nodes deprecated)
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    node = nt.nodes.new(node_type)
    for socket, value in inputs.items():
        node.inputs[socket].default_value = value
    nt.links.new(node.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    return mat, node


def diffuse_material(albedo=0.8):
    return bsdf_material("diffuse", "ShaderNodeBsdfDiffuse", Color=(albedo, albedo, albedo, 1))[0]


def cycles_output(scene, width, height, samples, bounces, transparent):
    """Cycles at `samples` (not adaptive, not denoised, seed 1), `bounces`, no clamp, to a 32-bit EXR of width x
    height."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.film_transparent = transparent
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    c = scene.cycles
    c.samples, c.use_adaptive_sampling, c.use_denoising, c.seed = samples, False, False, 1
    c.max_bounces = bounces
    c.sample_clamp_indirect = 0.0  # the reference must be unbiased (Blender 3.x defaults to 10)


def sphere_over_plane(width, height, samples):
    scene = bpy.context.scene
    mat = diffuse_material()
    bpy.ops.mesh.primitive_plane_add(size=12)
    bpy.context.active_object.data.materials.append(mat)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1, location=(0, 0, 1), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(mat)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0, -7, 3.2)
    cam.rotation_euler = (math.radians(72), 0, 0)
    cam.data.lens = 35
    scene.collection.objects.link(cam)
    scene.camera = cam
    cycles_output(scene, width, height, samples, bounces=4, transparent=True)


ROUGHNESS = (0.2, 0.5, 1.0)


def principled_material(roughness, base=0.8):
    """Blender's default Principled BSDF (specular IOR level 0.5) at a grey base colour and `roughness`."""
    mat = bpy.data.materials.new("principled %.2f" % roughness)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    p = mat.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (base, base, base, 1)
    p.inputs["Roughness"].default_value = roughness
    return mat


def still_life(width, height, samples):
    """A still life on a floor, the scene users render (issue 52): a polished metal sphere, a glossy red dielectric
    box, a rough dielectric vase, a thin rod lying on the floor (contact shadows, thin objects), on a 12 m diffuse
    floor, seen from a camera like sphere_over_plane's; Cycles with 4 bounces."""
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=12)
    bpy.context.active_object.data.materials.append(diffuse_material(0.5))

    def principled(name, colour, roughness, metallic=0.0):
        mat = principled_material(roughness)
        mat.name = name
        p = mat.node_tree.nodes["Principled BSDF"]
        p.inputs["Base Color"].default_value = (*colour, 1)
        p.inputs["Metallic"].default_value = metallic
        return mat

    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, location=(-1.3, 0.3, 0.7), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(principled("metal", (0.9, 0.9, 0.9), 0.15, metallic=1.0))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.4, 0.6, 0.5), rotation=(0, 0, math.radians(30)))
    bpy.context.active_object.data.materials.append(principled("glossy", (0.6, 0.08, 0.05), 0.1))
    bpy.ops.mesh.primitive_cylinder_add(radius=0.35, depth=1.4, location=(1.6, 1.2, 0.7), vertices=48)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(principled("rough", (0.25, 0.45, 0.7), 0.7))
    bpy.ops.mesh.primitive_cylinder_add(radius=0.04, depth=2.2, location=(0.2, -0.9, 0.04), vertices=16,
                                        rotation=(0, math.radians(90), math.radians(20)))
    bpy.context.active_object.data.materials.append(principled("rod", (0.8, 0.8, 0.8), 0.4))
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (-0.15, -5.2, 2.1)
    cam.rotation_euler = (math.radians(74), 0, 0)
    cam.data.lens = 45
    scene.collection.objects.link(cam)
    scene.camera = cam
    cycles_output(scene, width, height, samples, bounces=4, transparent=True)


def glossy_spheres(width, height, samples, roughness=ROUGHNESS):
    """sphere_over_plane's set-up with one Principled sphere per roughness side by side, left to right, each over
    its own third of a plane of the same material: the picture's column thirds are the three materials (thirds())."""
    sphere_over_plane(width, height, samples)
    for o in list(bpy.data.objects):
        if o.type == "MESH":
            bpy.data.objects.remove(o)
    n = len(roughness)
    for i, r in enumerate(roughness):
        mat = principled_material(r)
        x = 2.4 * (i - (n - 1) / 2)
        bpy.ops.mesh.primitive_plane_add(size=1, location=(x, 0, 0))
        plane = bpy.context.active_object
        plane.scale = (2.4, 12, 1)
        plane.data.materials.append(mat)
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1, location=(x, 0, 1), segments=48, ring_count=24)
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(mat)
    cam = bpy.context.scene.camera
    cam.location = (0, -9.5, 3.4)
    cam.rotation_euler = (math.radians(75), 0, 0)


def thirds(image):
    """The picture's column thirds (glossy_spheres' materials, left to right)."""
    w = image.shape[1] // 3
    return [image[:, i * w:(i + 1) * w] for i in range(3)]


def glossy_probe_scene(probe, samples):
    """The glossy benches' scene: glossy_spheres at 192 x 96 lit by `probe`'s world alone (an empty scene)."""
    import harness
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(probe))
    glossy_spheres(3 * 64, 96, samples)
    return bpy.context.scene


def thirds_difference(reference, other):
    """block_difference of each third (glossy_spheres' roughnesses), in %, as "a / b / c"."""
    return " / ".join("%.2f" % (100 * block_difference(a, b)[0]) for a, b in zip(thirds(reference), thirds(other)))


def ground_under_sphere(samples, size=16):
    """The evaluator's shadow scene (native/include/probelights/evaluate.h), rendered: a white diffuse plane at z = 0
    under a unit sphere resting on it at the origin, seen straight down by an orthographic camera over
    [-2.5, 2.5]^2 at size x size pixels. With size 16 each pixel's centre is one of the evaluator's ground points and
    the pixel filter is 0.01 px wide, so a pixel is the point's irradiance / pi. Direct light only; the sphere
    casts shadows but is hidden from the camera."""
    scene = bpy.context.scene
    mat = diffuse_material(albedo=1.0)
    bpy.ops.mesh.primitive_plane_add(size=12)
    bpy.context.active_object.data.materials.append(mat)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1, location=(0, 0, 1), segments=96, ring_count=48)
    bpy.ops.object.shade_smooth()
    sphere = bpy.context.active_object
    sphere.visible_camera = False
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0, 0, 10)
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 5.0
    scene.collection.objects.link(cam)
    scene.camera = cam
    cycles_output(scene, size, size, samples, bounces=0, transparent=False)
    scene.cycles.filter_width = 0.01
    scene.cycles.sample_clamp_direct = 0.0


def ground_points(size=16):
    """The ground points ground_under_sphere's pixels look at, rows top to bottom (the camera looks down -Z, x
    right, y up)."""
    return [np.array([-2.5 + 5.0 * (c + 0.5) / size, 2.5 - 5.0 * (r + 0.5) / size, 0.0])
            for r in range(size) for c in range(size)]


def hidden_by_sphere(d, p):
    """Which unit directions d (rows) from ground point p the unit sphere resting at (0, 0, 1) hides."""
    o = p - np.array([0, 0, 1.0])
    b = d @ o
    return (b < 0) & (b * b - (o @ o - 1) > 0)


def ground_truth(image, size=16, sub=2, negatives_as_zero=False):
    """What ground_under_sphere renders, computed from a lat-long image's own pixels (each sub x sub points,
    negatives kept unless negatives_as_zero): the luminance irradiance / pi at each pixel's ground point, as a
    size x size x 3 array of grey pixels (rows top to bottom, like render())."""
    w, h = image.size
    px = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(px)
    lum = px.reshape(h, w, 4)[::-1, :, :3].astype(np.float64) @ LUM
    if negatives_as_zero:
        lum = np.maximum(lum, 0.0)
    u = (np.arange(w * sub) + 0.5) / (w * sub)
    v = (np.arange(h * sub) + 0.5) / (h * sub)
    phi, el = 2 * math.pi * (0.5 - u)[None, :], (math.pi / 2 - math.pi * v)[:, None]
    d = np.stack([np.cos(el) * np.cos(phi), np.cos(el) * np.sin(phi), np.sin(el) * np.ones_like(phi)], -1)
    d = d.reshape(-1, 3)
    omega = (np.cos(el) * (2 * math.pi / (w * sub)) * (math.pi / (h * sub)) * np.ones_like(phi)).ravel()
    radiance = np.repeat(np.repeat(lum, sub, 0), sub, 1).ravel()
    up = d[:, 2] > 0
    d, weight = d[up], (omega * radiance)[up] * d[up, 2]
    out = np.array([np.sum(weight[~hidden_by_sphere(d, p)]) / math.pi for p in ground_points(size)])
    return np.repeat(out.reshape(size, size, 1), 3, axis=2)  # grey: its luminance is the value (LUM sums to 1)


def relative_rms(truth, got):
    """rms(got - truth) / rms(truth) of the pixels' luminance: the evaluator's error measure."""
    a, b = truth[..., :3] @ LUM, got[..., :3] @ LUM
    return float(np.sqrt(np.mean((b - a) ** 2) / np.mean(a ** 2)))


def render():
    """Renders the scene; returns the linear RGBA pixels, rows top to bottom. A test's render of a scene rendered
    before is taken from the render cache (render_cache.py, opt-in)."""
    scene = bpy.context.scene
    key = render_cache.key(scene)
    remembered = render_cache.lookup(key)
    if remembered is not None and not render_cache.VERIFY:
        return remembered
    fd, path = tempfile.mkstemp(suffix=".exr")
    os.close(fd)
    scene.render.filepath = path
    printed = render_cache.printing(key, lambda: bpy.ops.render.render(write_still=True))
    img = bpy.data.images.load(path)
    w, h = img.size[:]
    a = np.empty(w * h * 4, np.float32)
    img.pixels.foreach_get(a)
    bpy.data.images.remove(img)
    os.remove(path)
    pixels = a.reshape(h, w, 4)[::-1].copy()
    render_cache.store(key, pixels, remembered, printed)
    return pixels


def blocks(a):
    """The mean of each whole 8x8 block of an image (H x W or H x W x C)."""
    h, w = a.shape[0] // BLOCK, a.shape[1] // BLOCK
    return a[: h * BLOCK, : w * BLOCK].reshape(h, BLOCK, w, BLOCK, *a.shape[2:]).mean(axis=(1, 3))


def block_luminance(picture):
    return blocks(picture[..., :3] @ LUM)


def lit_blocks(world_lit):
    """The blocks block_difference compares: made only of object pixels (alpha 1) and lit above 2 % of the
    brightest of them."""
    ya = block_luminance(world_lit)
    solid = blocks((world_lit[..., 3] > 0.999).astype(float)) == 1.0
    return solid & (ya > 0.02 * ya[solid].max())


def block_difference(world_lit, light_lit):
    """Mean over the 8x8 blocks made only of lit object pixels of |lights - world| / world (luminance)."""
    lit = lit_blocks(world_lit)
    ya, yb = block_luminance(world_lit)[lit], block_luminance(light_lit)[lit]
    rel = np.abs(yb - ya) / ya
    return float(rel.mean()), int(lit.sum())


def pixel_difference(world_lit, light_lit):
    """Sum over the pixels of the lit blocks (lit_blocks) of |lights - world| / the sum of world (luminance):
    unlike the block means it sees a shadow's edge in the wrong place, and noise. The pixels of the lit blocks, not
    those above 2 % of the brightest pixel: on the still life one sun's glint on the metal ball, 250 times the
    median pixel, left 44 of its 13,208 object pixels to compare."""
    lit = np.repeat(np.repeat(lit_blocks(world_lit), BLOCK, axis=0), BLOCK, axis=1)
    h, w = lit.shape
    ya, yb = world_lit[:h, :w, :3] @ LUM, light_lit[:h, :w, :3] @ LUM
    return float(np.abs(yb[lit] - ya[lit]).sum() / ya[lit].sum())


def flip(reference, test, picture=False):
    """The mean of HDR-FLIP (Andersson et al. 2021, NVIDIA's flip-evaluator: the error a viewer sees flipping
    between the two pictures over the exposures the reference spans) of two linear renders, or None where
    flip-evaluator is not installed (scripts/bpy-env.sh pins it beside bpy); with `picture`, its error map in
    display colours (magma) instead. Negative values are clamped to 0: it takes none."""
    try:
        import flip_evaluator
    except ImportError:
        return None

    def rgb(image):
        return np.ascontiguousarray(np.clip(image[..., :3], 0.0, None), dtype=np.float32)

    error_map, mean, _ = flip_evaluator.evaluate(rgb(reference), rgb(test), "HDR", applyMagma=picture)
    return error_map if picture else float(mean)


def render_errors(world_lit, light_lit):
    """(block difference, lit blocks, pixel difference, HDR-FLIP mean or None) of a render against the world's."""
    block, lit = block_difference(world_lit, light_lit)
    return block, lit, pixel_difference(world_lit, light_lit), flip(world_lit, light_lit)


def describe_errors(errors):
    """'block 0.31 %, pixel 2.10 %, FLIP 0.0183' for render_errors' result."""
    block, _, pixel, flip_mean = errors
    return "block %.2f %%, pixel %.2f %%, FLIP %s" % (100 * block, 100 * pixel,
                                                     "%.4f" % flip_mean if flip_mean is not None else "n/a")


def save_png(pixels, path, display=False):
    """Saves linear renders, tone-mapped (x / (1 + x), sRGB), as an 8-bit PNG; with `display`, pixels that are
    display values already (a FLIP map)."""
    if display:
        srgb = np.clip(pixels[..., :3], 0, 1)
    else:
        x = np.clip(pixels[..., :3] / (1 + pixels[..., :3]), 0, 1)
        srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    h, w = srgb.shape[:2]
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = srgb
    img = bpy.data.images.new("save", w, h)
    img.colorspace_settings.name = "Non-Color"
    img.pixels.foreach_set(rgba[::-1].ravel())
    img.filepath_raw = path
    img.file_format = "PNG"
    img.save()
    bpy.data.images.remove(img)


def eevee_comparison_scene(probe, engine, width, height, samples):
    """The sphere over a plane lit by `probe`'s world, for EEVEE held to Cycles (bench/bench_eevee_*.py): the
    add-on's EEVEE settings undone, EEVEE's shadow pool at its default, the film transparent (block_difference
    takes the lit object pixels from the alpha), EEVEE at `samples` and Cycles at 8 times as many with direct light
    only (EEVEE bounces no light off the plane without baked light probes)."""
    import harness
    harness.empty_scene()
    harness.addon_module("eevee_settings").restore(bpy.context.scene)
    harness.env_world(bpy.data.images.load(probe))
    sphere_over_plane(width, height, samples)
    scene = bpy.context.scene
    scene.render.film_transparent = True
    scene.eevee.taa_render_samples = samples
    scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale = "512", 1.0
    scene.cycles.samples = 8 * samples
    scene.cycles.max_bounces = 0
    scene.render.engine = engine
    return scene


def eevee_rivals_scene(probe, scene_name, width, height, cycles_samples, eevee_samples):
    """The sphere over a plane (`scene_name` "sphere") or the still life ("still-life") lit by `probe`'s world, for
    EEVEE held to Cycles with its bounces (bench/bench_eevee_rivals.py, bench_volume_resolution.py): the add-on's
    EEVEE settings undone, Cycles at `cycles_samples` with 4 bounces, EEVEE at `eevee_samples` with a 512 MB
    shadow pool; the engine is left at Cycles."""
    import harness
    harness.empty_scene()
    harness.addon_module("eevee_settings").restore(bpy.context.scene)
    harness.env_world(bpy.data.images.load(probe))
    {"sphere": sphere_over_plane, "still-life": still_life}[scene_name](width, height, cycles_samples)
    scene = bpy.context.scene
    scene.eevee.taa_render_samples = eevee_samples
    scene.eevee.shadow_pool_size, scene.eevee.shadow_resolution_scale = "512", 1.0
    return scene


def probe_bake_renders(scene):
    """Three renders of a scene with baked lamps and a light probe volume: Cycles (the lamps, the scene's bounces),
    EEVEE with the lamps alone, and EEVEE after the add-on's bake of the light probes; the engine is left at EEVEE."""
    import harness
    scene.render.engine = "CYCLES"
    cycles = render()
    scene.render.engine = harness.eevee_engine()
    alone = render()
    assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    return cycles, alone, render()
