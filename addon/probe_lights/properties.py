"""Settings the panels show (per scene) and what the last bake measured."""

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import core_tables, light_kinds, render_cost

METHODS = core_tables.METHODS  # the core's menu (methodMenu)
LIGHT_TYPES = light_kinds.enum_items()
# The suns' angles (the core's sun_angles: fit, spread, points).
SHADOWS = [("FIT", "Fitted", "Soft shadows: each sun's angle chosen so its shadow matches the probe's light (the "
            "estimated shadow error, on a sphere over a plane)"),
           ("SPREAD", "Region spread", "Soft shadows: each sun as wide as the spread of its region's light"),
           ("HARD", "Hard", "Sharp shadows: suns of angle 0")]
NATIVE_SUN_ANGLES = {"FIT": "fit", "SPREAD": "spread", "HARD": "points"}
RESOLUTIONS = [("auto", "Auto", "Cuts on a grid at most 2048 pixels wide (exact lights either way)"),
               ("full", "Full", "Cuts at full resolution, as the papers (slower for 4K and larger probes)"),
               ("512", "512", "Cuts on a 512-pixel-wide grid: fastest")]
# Numbered as before Engine came first: a file keeps the mode it was saved with.
COUNT_MODES = [("ENGINE", "Engine", "Make the fewest lights that render as close to the world as more do in this "
                                    "render engine and Blender, as measured (more only cost render time)", "NONE", 2),
               ("COUNT", "Count", "Make this many lights", "NONE", 0),
               ("TOLERANCE", "Max error", "Make the fewest lights whose estimated diffuse and shadow error is within the "
                                          "tolerance", "NONE", 1)]
LAMPS_TAKE = [("ALL", "All of the light", "The lamps light the scene in place of the world (for the effects below)"),
              ("SOURCES", "The bright sources", "The lamps take only the world's bright sources (the sun, lamps in "
                                                "it) and cast their shadows; the world keeps the rest of its light, "
                                                "nothing counted twice. Closest in Cycles on glossy materials; in "
                                                "EEVEE the world's part casts no shadows, so All of the light is "
                                                "closer there")]
NON_FINITE = [("error", "Stop", "Stop with an error naming how many NaN/Inf samples the image has"),
              ("zero", "Zero", "Read NaN/Inf samples as 0 (black) and say how many")]


def bake_settings():
    """The settings a bake takes: shared by the scene's settings (panels) and the operator (redo panel)."""
    return {
        "count": IntProperty(name="Lights", description="How many lights to make", default=64, min=1,
                             soft_max=1024, max=4096),
        "method": EnumProperty(name="Method", items=METHODS, default="auto"),
        "light_type": EnumProperty(name="Light type", items=LIGHT_TYPES, default=light_kinds.DEFAULT),
        "resolution": EnumProperty(name="Working resolution", items=RESOLUTIONS, default="auto"),
        "shadows": EnumProperty(name="Shadows", items=SHADOWS, default="FIT",
                                description="How soft each sun's shadow is (its angle)"),
        "distance": FloatProperty(name="Distance", default=light_kinds.DEFAULT_DISTANCE, min=0.01, unit="LENGTH",
                                  description="How far from the origin point lights are placed"),
        "replace_diffuse": BoolProperty(name="Diffuse + shadows", default=True,
                                        description="Lights give diffuse light and shadows; the world no longer does "
                                                    "(Cycles; in EEVEE the lights give every effect)"),
        "replace_reflections": BoolProperty(name="Reflections", default=False,
                                            description="Lights give reflections; the world no longer does (Cycles; "
                                                        "in EEVEE the lights give every effect)"),
        "replace_background": BoolProperty(name="Background", default=False,
                                           description="Hide the world from the camera"),
        "lamps_take": EnumProperty(name="Lamps take", items=LAMPS_TAKE, default="ALL"),
        "source_level": FloatProperty(name="Sources above", default=10.0, min=1.0, soft_max=1000.0, max=1.0e6,
                                      description="A pixel brighter than this many times the world's mean "
                                                  "brightness is a source's; the world keeps up to that of it"),
        "count_mode": EnumProperty(name="Count by", items=COUNT_MODES, default="ENGINE"),
        "max_error": FloatProperty(name="Max error", default=2.0, min=0.05, max=50.0, subtype="PERCENTAGE",
                                   description="Largest estimated diffuse/shadow error (relative RMS) to accept"),
        "non_finite": EnumProperty(name="NaN/Inf pixels", items=NON_FINITE, default="error"),
        "refit": BoolProperty(name="Refit", default=True,
                              description="Place each light at its region's brightest light and refit the lights' "
                                          "colours and directions so their diffuse light and shadows match the "
                                          "world's: closer renders, about twice the bake time"),
    }


SETTING_NAMES = tuple(bake_settings())


def given_count(operator):
    """A caller who gives an operator a count and no way to count by (a script: bake(count=16)) gets that many
    lights, whatever the default or the panel counts by."""
    if operator.properties.is_property_set("count") and not operator.properties.is_property_set("count_mode"):
        operator.count_mode = "COUNT"


def from_panel(operator, settings):
    """An operator started from a button takes the panel's settings, except those its caller set explicitly."""
    given_count(operator)
    for name in SETTING_NAMES:
        if not operator.properties.is_property_set(name):
            setattr(operator, name, getattr(settings, name))


def engine_count(settings, render_engine):
    """(count, why) of Count by Engine for a bake of `settings` in `render_engine` (render_cost.default_count)."""
    return render_cost.default_count(render_engine, bpy.app.version, light_kinds.kind(settings.light_type).render_cost)


def light_count(settings, render_engine):
    """How many lights a bake of `settings` in `render_engine` makes (with Max error: the most it may make)."""
    return engine_count(settings, render_engine)[0] if settings.count_mode == "ENGINE" else settings.count


def cut_method(method):
    """The core's method for a panel's method: auto and both cut with variance minimization first."""
    return "variance" if method in ("auto", "both") else method


def cuts(method, tolerance):
    """The core's cuts for a panel's method (CutChoice: one, both, or auto: both up to 16 lights, above both
    started and the better finished); one when a tolerance picks the count."""
    return method if method in ("auto", "both") and not tolerance else "one"


class ProbeLightsTradeoffRow(bpy.types.PropertyGroup):
    """One row of the accuracy-vs-time table: a light count, plain or refit."""
    __annotations__ = {
        "lights": IntProperty(),
        "refit": BoolProperty(),
        "bake_ms": FloatProperty(),
        "click_ms": FloatProperty(),  # what a click costs: reading or rendering the world, the bake, the lamps
        "diffuse": FloatProperty(),   # estimated relative RMS errors, fractions
        "shadow": FloatProperty(),
    }


class ProbeLightsSettings(bpy.types.PropertyGroup):
    __annotations__ = {
        **bake_settings(),
        "last_count": IntProperty(default=0),
        "last_energy": FloatProperty(default=0.0, subtype="PERCENTAGE"),
        "last_ms": FloatProperty(default=0.0),
        "last_source": StringProperty(default=""),
        "last_notes": StringProperty(default=""),     # one per line
        "last_warnings": StringProperty(default=""),  # one per line
        "last_report": StringProperty(default=""),    # the bake's summary report (the status bar's line)
        "last_diffuse_error": FloatProperty(default=-1.0),
        "last_shadow_error": FloatProperty(default=-1.0),
        "last_ms_per_lamp": FloatProperty(default=0.0),
        "tradeoff": CollectionProperty(type=ProbeLightsTradeoffRow),
        "tradeoff_method": StringProperty(default=""),
        "tradeoff_source": StringProperty(default=""),
        # Bake animation at the count, for a world that changes over time (0 frames: none): a frame's read (or
        # render) and bake, which run side by side.
        "tradeoff_frames": IntProperty(default=0),
        "tradeoff_frame_lights": IntProperty(default=0),
        "tradeoff_frame_read_ms": FloatProperty(default=0.0),
        "tradeoff_frame_bake_ms": FloatProperty(default=0.0),
        "tradeoff_frames_rendered": BoolProperty(default=False),
    }


classes = (ProbeLightsTradeoffRow, ProbeLightsSettings)


def register():
    bpy.types.Scene.probe_lights = bpy.props.PointerProperty(type=ProbeLightsSettings)


def unregister():
    del bpy.types.Scene.probe_lights
