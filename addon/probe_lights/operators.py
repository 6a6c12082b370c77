"""Operators: bake the world to lights, and restore the world (and remove the lights)."""

import json
import time

import bpy
import numpy as np

from . import native, render_cost
from .light_objects import make_lights, remove_lights
from .properties import SETTING_NAMES, bake_settings
from .world_graph import find_probe
from .errors import ProbeError
from .world_image import image_pixels, render_world
from .world_mix import insert_mix, remove_mix

RENDER_WIDTH = 1024  # lat-long width a world without a readable image is rendered at


def _rendered_probe(world):
    """Renders a copy of the world without our mix (so a re-bake sees the world as the user made it)."""
    copy = world.copy()
    try:
        remove_mix(copy)
        return render_world(copy, RENDER_WIDTH)
    finally:
        bpy.data.worlds.remove(copy)


def world_probe(world):
    """The world's probe: (pixels, projection, a description, the ProbeSource). Read from its image where the rules
    of world_graph.py find one, else rendered (on a copy: the world itself is not touched)."""
    if world is None:
        raise ProbeError("the scene has no world: add one in World properties")
    try:
        source = find_probe(world, bpy.app.version)
    except ValueError as e:
        raise ProbeError(str(e))
    if source.image is not None:
        return (image_pixels(source.image), source.projection,
                "image '%s' (%s)" % (source.image.name, source.projection), source)
    return _rendered_probe(world), "latlong", "rendered world (%s)" % source.render_reason, source


def bake_world(context, settings):
    """Bakes the scene's world with `settings` (anything with the bake_settings() attributes). Returns a summary."""
    scene = context.scene
    world = scene.world
    start = time.perf_counter()
    wm = context.window_manager
    wm.progress_begin(0, 100)
    try:
        pixels, projection, described, source = world_probe(world)
        wm.progress_update(50)
        # The errors are estimated on the probe grouped to 512 pixels wide: ~50 ms at any probe size.
        max_error = settings.max_error / 100.0 if settings.count_mode == "TOLERANCE" else 0.0
        baked = native.bake(pixels, projection=projection, method=settings.method, lights=settings.count,
                                  resolution=settings.resolution, evaluate=True, effects="diffuse,shadow",
                                  evaluator_width=512, refit=settings.refit, move_directions=settings.refit,
                                  max_error=max_error)
        wm.progress_update(80)
        remove_lights(scene)
        lights = make_lights(scene, baked, source.world_from_probe, source.strength, settings.light_type,
                             settings.soft_shadows, settings.distance, lights_diffuse=settings.replace_diffuse,
                             lights_glossy=settings.replace_reflections)
        insert_mix(world, keep_background=not settings.replace_background,
                   keep_reflections=not settings.replace_reflections, keep_diffuse=not settings.replace_diffuse)
    finally:
        wm.progress_end()
    notes = list(baked["notes"])
    clamp = getattr(getattr(scene, "cycles", None), "sample_clamp_indirect", 0.0)
    if scene.render.engine == "CYCLES" and clamp > 0 and len(lights) > 1:
        # Measured: with Blender 3.x's default clamp of 10, bounce light under 64 baked suns came out 3-5 % dark.
        notes.append("Cycles clamps indirect light at %g, which darkens bounce light from the baked lights: set "
                     "Light Paths > Clamping > Indirect to 0 for exact bounces" % clamp)
    if scene.render.engine == "CYCLES" and settings.light_type == "SUN":
        advice = render_cost.count_note(len(lights), bpy.app.version)
        if advice:
            notes.append(advice)
    total = float(np.dot(baked["total_rgb"], (0.2126, 0.7152, 0.0722)))
    captured = float(np.sum(baked["rgb"] @ np.array([0.2126, 0.7152, 0.0722])))
    errors = baked.get("errors", {})
    return {"count": len(lights), "energy": 100.0 * captured / total if total > 0 else 0.0,
            "ms": 1000.0 * (time.perf_counter() - start), "source": described, "notes": notes,
            "diffuse_error": 100.0 * errors.get("diffuse", -0.01), "shadow_error": 100.0 * errors.get("shadow", -0.01)}


class PROBE_LIGHTS_OT_bake(bpy.types.Operator):
    """Turn the world's light into lamps that light the scene the same way; the world keeps only what it still shows"""

    bl_idname = "probe_lights.bake"
    bl_label = "Bake probe to lights"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = bake_settings()

    def invoke(self, context, event):
        # From a button: start from the panel's settings, except what the caller set explicitly.
        settings = context.scene.probe_lights
        for name in SETTING_NAMES:
            if not self.properties.is_property_set(name):
                setattr(self, name, getattr(settings, name))
        return self.execute(context)

    def execute(self, context):
        try:
            summary = bake_world(context, self)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        settings = context.scene.probe_lights
        for name in SETTING_NAMES:
            setattr(settings, name, getattr(self, name))
        settings.last_count = summary["count"]
        settings.last_energy = summary["energy"]
        settings.last_ms = summary["ms"]
        settings.last_source = summary["source"]
        settings.last_notes = "; ".join(summary["notes"])
        settings.last_diffuse_error = summary["diffuse_error"]
        settings.last_shadow_error = summary["shadow_error"]
        self.report({"INFO"}, "Baked %d lights from %s in %.0f ms; estimated error: diffuse %.2f %%, shadow %.2f %%" % (
            summary["count"], summary["source"], summary["ms"], summary["diffuse_error"], summary["shadow_error"]))
        return {"FINISHED"}


TRADEOFF_COUNTS = [4, 8, 16, 32, 64, 128, 256]


class PROBE_LIGHTS_OT_tradeoff(bpy.types.Operator):
    """Measure what accuracy costs: bake the world with 4 to 256 lights (with and without the refit) and show each
    count's bake time and estimated diffuse and shadow error; nothing in the scene changes"""

    bl_idname = "probe_lights.tradeoff"
    bl_label = "Measure tradeoff"
    bl_options = {"REGISTER"}

    def execute(self, context):
        settings = context.scene.probe_lights
        try:
            pixels, projection, described, _ = world_probe(context.scene.world)
            rows = native.tradeoff(pixels, projection=projection, effects="diffuse,shadow",
                                         counts=TRADEOFF_COUNTS, methods=[settings.method], refit=True,
                                         evaluator_width=512)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        settings.tradeoff_rows = json.dumps({"method": settings.method, "source": described, "rows": rows})
        self.report({"INFO"}, "Measured %d light counts of %s" % (len(TRADEOFF_COUNTS), described))
        return {"FINISHED"}


class PROBE_LIGHTS_OT_set_count(bpy.types.Operator):
    """Use this many lights"""

    bl_idname = "probe_lights.set_count"
    bl_label = "Use this count"
    bl_options = {"REGISTER", "UNDO", "INTERNAL"}
    count: bpy.props.IntProperty(min=1, max=4096)

    def execute(self, context):
        settings = context.scene.probe_lights
        settings.count = self.count
        settings.count_mode = "COUNT"
        return {"FINISHED"}


class PROBE_LIGHTS_OT_restore(bpy.types.Operator):
    """Remove the baked lights and bring the world back exactly as it was before the bake"""

    bl_idname = "probe_lights.restore"
    bl_label = "Restore world"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        removed = remove_lights(scene)
        restored = remove_mix(scene.world)
        scene.probe_lights.last_count = 0
        if not removed and not restored:
            self.report({"INFO"}, "Nothing to restore: the world was not baked")
        else:
            self.report({"INFO"}, "Removed %d lights%s" % (removed, ", restored the world" if restored else ""))
        return {"FINISHED"}


classes = (PROBE_LIGHTS_OT_bake, PROBE_LIGHTS_OT_restore, PROBE_LIGHTS_OT_tradeoff, PROBE_LIGHTS_OT_set_count)
