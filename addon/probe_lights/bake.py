"""What a click does, apart from the operators that call it: read (or render) a world's probe, bake it, make its
lamps and mix, and take them out again. The operators (operators.py) only pass settings in and report.

    world --world_graph.find_probe--> image pixels | rendered world (world_image.py)
          --native.bake--> lights + estimated errors
          --light_objects.make_lights--> the world's lamp collection (rig, drivers)
          --world_mix.insert_mix--> the world keeps only what the lamps do not replace
"""

import math
import time

import bpy
import numpy as np

from . import cycles_settings, eevee_settings, light_kinds, native, render_cost
from .blender_caps import preset, sun_cones, sun_profile
from .errors import ProbeError
from .light_objects import (baked_worlds, make_lights, remove_collection_if_empty, remove_lights, sun_height,
                            world_collection)
from .properties import NATIVE_SUN_ANGLES, cut_method, cuts, light_count
from .world_graph import find_probe
from .world_image import image_pixels, render_world, sequence_pixels
from .world_mix import insert_mix, remove_mix, residual_world

RENDER_WIDTH = 1024  # lat-long width a world without a readable image is rendered at
IMAGE_KEY = "probe_lights_image"  # on a baked world: the image it was baked from (a re-bake is suggested if it changes)
CONES_KEY = "probe_lights_cones_cross"  # on a baked world: a sun's cone crosses the horizon (blender_caps.sun_cones)
LUM = np.array([0.2126, 0.7152, 0.0722])


def _rendered_probe(world):
    """The world rendered to a lat-long image now (blocking; the world itself is not touched)."""
    return render_world(world, RENDER_WIDTH)


def needs_render(world):
    """Why the world has to be rendered rather than read (one line), or '' when its image is read directly."""
    try:
        source = find_probe(world, bpy.app.version)
    except ValueError:
        return ""
    return source.render_reason if source.image is None else ""


def world_source(world):
    """Where the world's probe comes from (world_graph.find_probe's ProbeSource); ProbeError for no world or a world
    without one."""
    if world is None:
        raise ProbeError("the scene has no world: add one in World properties")
    try:
        return find_probe(world, bpy.app.version)
    except ValueError as e:
        raise ProbeError(str(e))


def world_probe(world, rendered=None):
    """The world's probe: (pixels, projection, a description, the ProbeSource, warnings). Read from its image where
    the rules of world_graph.py find one, else rendered (on a copy: the world itself is not touched); `rendered`:
    pixels already rendered by a WorldRender job."""
    source = world_source(world)
    if source.image is None:
        pixels = rendered if rendered is not None else _rendered_probe(world)
        return pixels, "latlong", "rendered world (%s)" % source.render_reason, source, []
    if source.image.source == "SEQUENCE":  # the file of the scene's frame (Bake animation bakes them all)
        frame = bpy.context.scene.frame_current
        pixels = sequence_pixels(source.image_node, frame)
        name = "image sequence '%s' frame %d" % (source.image.name, frame)
    else:
        pixels, name = image_pixels(source.image), "image '%s'" % source.image.name
    warnings = []
    h, w = pixels.shape[:2]
    if source.projection == "latlong" and abs(w - 2 * h) > 1:
        warnings.append("image '%s' is %dx%d, not 2:1: baked as Equirectangular as the world says, but it may be "
                        "another projection" % (source.image.name, w, h))
    if source.projection == "mirror-ball" and w != h:
        warnings.append("image '%s' is %dx%d, not square: a mirror ball image usually is" % (source.image.name, w, h))
    return pixels, source.projection, "%s (%s)" % (name, source.projection), source, warnings


def bake_world(context, settings, progress=lambda fraction: None, rendered=None, render_ms=0.0):
    """Bakes the scene's world with `settings` (anything with the properties.bake_settings() attributes). Returns a
    summary: count, energy, ms, timings, source, notes, warnings, errors. `rendered`: the world's pixels from a
    WorldRender job that took `render_ms`."""
    scene = context.scene
    world = scene.world
    start = time.perf_counter() - render_ms / 1000
    pixels, projection, described, source, warnings = world_probe(world, rendered)
    probe_ms = 1000 * (time.perf_counter() - start)
    progress(0.5)
    kind = light_kinds.kind(settings.light_type)
    # The errors are estimated on the probe grouped to 512 pixels wide: the same small cost at any probe size.
    max_error = settings.max_error / 100.0 if settings.count_mode == "TOLERANCE" else 0.0
    sources = settings.lamps_take == "SOURCES"
    # With the bright sources, the lamps carry them exactly, as the residual world needs: no refit (the panel
    # greys it out), and the count is chosen.
    count = light_count(settings, scene.render.engine)
    if sources and max_error > 0:
        warnings.append("The bright sources: %d lamps made (Max error chooses the count for all of the light)"
                        % count)
        max_error = 0.0
    # (The refit's limit is the core's: more lights are baked without it, and its note says so.)
    refit = settings.refit and not sources
    extra = {"source_level": settings.source_level} if sources else {}
    # The core's recipe for this engine (request.cpp: presets), changed by the panel's settings; without the
    # refit each light sits at its region's energy centroid (energy^2 leans towards the brightest light, which
    # only the refit's colours make up for: docs/results/shadows.md).
    baked = native.bake(pixels, projection=projection, preset=preset(scene.render.engine, bpy.app.version),
                        method=cut_method(settings.method), lights=count,
                        resolution=settings.resolution, max_error=max_error, nonfinite=settings.non_finite,
                        sun_angles=NATIVE_SUN_ANGLES[settings.shadows] if kind.soft else "points",
                        sun_profile=sun_profile(bpy.app.version), cuts=cuts(settings.method, max_error > 0),
                        **({} if refit else {"refit": False, "centroid": "energy"}), **extra)
    bake_done = time.perf_counter()
    progress(0.8)
    # The lamps of the sources light every effect, the residual world the rest (world_mix.py says why).
    lights = make_lights(scene, world, baked, source, settings.light_type, settings.distance,
                         lights_diffuse=settings.replace_diffuse or sources,
                         lights_glossy=settings.replace_reflections or sources)
    residual = residual_world(world, baked["sources"]["residual"], source) if sources else None
    more_notes, more_warnings = finish_world(context, settings, lights, source, residual)
    lamps_ms = 1000 * (time.perf_counter() - bake_done)
    # The panel's notes say what the core chose (note.h: their kind); the figures behind a choice stay in the
    # core's JSON. Every other note is a warning, with its figures.
    notes = [n["text"] for n in baked["notes"] if n["kind"] == "chosen"]
    total = float(np.dot(baked["total_rgb"], LUM))
    captured = float(np.sum(baked["lights"]["rgb"] @ LUM))
    if sources:  # "% of the energy": the lamps' share of the world's light (the residual keeps the rest)
        total += float(np.dot(baked["sources"]["residual_rgb"], LUM))
    warnings += [n["text"] + (" (%s)" % n["detail"] if n["detail"] else "") for n in baked["notes"]
                 if n["kind"] != "chosen"] + more_warnings
    notes += more_notes
    errors = baked["evaluation"] or {}
    return {"count": len(lights), "energy": 100.0 * captured / total if total > 0 else 0.0,
            "ms": 1000.0 * (time.perf_counter() - start),
            "timings": {"probe": probe_ms, "bake": 1000 * (bake_done - start) - probe_ms, "lamps": lamps_ms},
            "source": described, "notes": notes, "warnings": warnings,
            "diffuse_error": 100.0 * errors.get("diffuse", -0.01), "shadow_error": 100.0 * errors.get("shadow", -0.01)}


def finish_world(context, settings, lights, source, residual):
    """What follows the lamps of any bake: the world's mix (it keeps only what the lamps do not replace), the
    records a re-bake and the panel read, and the engines' settings the lamps need. Returns (notes, warnings)."""
    scene = context.scene
    world = scene.world
    insert_mix(world, keep_background=not settings.replace_background,
               keep_reflections=not settings.replace_reflections, keep_diffuse=not settings.replace_diffuse,
               residual=residual)
    if source.image is not None:
        world[IMAGE_KEY] = source.image.name
    elif IMAGE_KEY in world:
        del world[IMAGE_KEY]
    context.view_layer.update()  # drivers and the rig put the lamps where they shine from
    if any(_crosses_horizon(o) for o in lights):
        world[CONES_KEY] = 1
    elif CONES_KEY in world:
        del world[CONES_KEY]
    notes, warnings = [], []
    offer = cycles_settings.advice(scene, len(lights))
    if offer:
        warnings.append(offer + " (Use Cycles settings for lamps in the panel)")
    # The pool made to hold every sun's shadow, by itself, in any engine: the file renders right in EEVEE also
    # where the add-on is not installed (a render farm worker); EEVEE's settings change no Cycles render.
    fitted = eevee_settings.follow(scene, any_engine=True)
    if fitted:
        notes.append("EEVEE: %s so that no shadow is dropped (Restore world puts it back)"
                     % eevee_settings.describe(fitted))
    noise = cycles_settings.noise_note(scene, len(lights))
    engine = render_cost.engine_of(scene.render.engine, bpy.app.version)
    if noise:
        warnings.append(noise)
    elif engine is not None and light_kinds.kind(settings.light_type).render_cost:
        # What more suns cost the renders: a note (nothing is wrong with the bake), shown in the panel.
        advice = render_cost.count_note(len(lights), bpy.app.version, engine)
        if advice:
            notes.append(advice)
    return notes, warnings


def report_lines(summary):
    """The bake's reports, [(type, text)]: one WARNING per warning, then the summary line (last: the status bar shows
    it), which carries the count, the estimated errors and the warnings."""
    line = "Baked %d lights from %s in %.0f ms; estimated error: diffuse %.2f %%, shadow %.2f %%" % (
        summary["count"], summary["source"], summary["ms"], summary["diffuse_error"], summary["shadow_error"])
    warnings = summary["warnings"]
    if not warnings:
        return [("INFO", line)]
    return [("WARNING", w) for w in warnings] + [("WARNING", line + "; warning: " + "; ".join(warnings))]


def image_changed(world):
    """The name of the image the world now reads if it differs from the one it was baked from, else ''."""
    baked_from = world.get(IMAGE_KEY) if world is not None else None
    if not baked_from:
        return ""
    source = find_probe(world, bpy.app.version)
    now = source.image.name if source.image is not None else "a rendered world"
    return now if now != baked_from else ""


def _crosses_horizon(lamp):
    """Whether a sun's cone reaches across the horizon (half its angle above its elevation)."""
    if lamp.type != "LIGHT" or lamp.data.type != "SUN":
        return False
    return lamp.data.angle > 2 * math.asin(sun_height(lamp)) + 1e-4


def eevee_cones_note(scene):
    """What the panel says when the scene renders in EEVEE with suns baked for another engine whose cones cross the
    horizon (EEVEE renders them darker: blender_caps.sun_cones), else ''."""
    world = scene.world
    if world is None or not world.get(CONES_KEY) or sun_cones(scene.render.engine, bpy.app.version) == "free":
        return ""
    return "Some suns were baked wide and low for Cycles, and EEVEE renders them darker: bake again in EEVEE"


def restore_world(scene, world):
    """Takes `world`'s lamps, mix and records out; its collection goes when empty; the Cycles settings the add-on
    and EEVEE settings the add-on set go back once no baked world is left in the scene. Returns a one-line summary ('' if nothing was baked)."""
    if world is None:
        return ""
    removed = remove_lights(world)
    restored = remove_mix(world)
    collection_gone = remove_collection_if_empty(world)
    for key in (IMAGE_KEY, CONES_KEY):
        if key in world:
            del world[key]
    cycles = eevee = []
    if not any(world_collection(w) is not None and scene.user_of_id(world_collection(w)) for w in baked_worlds()):
        cycles = cycles_settings.restore(scene)
        eevee = eevee_settings.restore(scene)
    if not (removed or restored or collection_gone or cycles or eevee):
        return ""
    parts = ["removed %d lights" % removed]
    if restored:
        parts.append("restored world '%s'" % world.name)
    if cycles:
        parts.append("Cycles %s back" % " and ".join(c.replace("sample_clamp_indirect", "indirect clamp")
                                                     .replace("use_light_tree", "light tree") for c in cycles))
    if eevee:
        parts.append("EEVEE %s back" % " and ".join(eevee_settings.WORDS[e] for e in eevee))
    return ", ".join(parts)
