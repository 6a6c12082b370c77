"""Panels: World properties and the 3D viewport sidebar show the same controls, laid out to fit the editors' default
widths: short labels, enums as buttons, and every long line (results, notes, warnings) wrapped to the region."""

import bpy

from . import cycles_settings, eevee_settings, light_kinds, native, probe_volumes, render_cost
from .bake import eevee_cones_note, image_changed
from .light_objects import baked_worlds, world_collection
from .properties import engine_count
from .text_fit import fits, wrap
from .world_mix import has_mix

# Lines that did not fit their width in the last draw (the screenshot test asserts none); cleared at each draw.
OVERFLOW = []


def _font_measure():
    """Width in pixels of a text in the interface font (blf), at the interface's scale."""
    import blf
    prefs = bpy.context.preferences
    points = prefs.ui_styles[0].widget.points if hasattr(prefs.ui_styles[0].widget, "points") else 11
    size = points * prefs.system.ui_scale
    try:
        blf.size(0, size)
    except TypeError:  # Blender before 4.0 takes a dpi as well
        blf.size(0, size, 72)
    return lambda text: blf.dimensions(0, text)[0]


def _lines(layout, text, width, measure, icon="NONE"):
    for i, line in enumerate(wrap(text, width, measure)):
        if not fits(line, width, measure):
            OVERFLOW.append(line)
        layout.label(text=line, icon=icon if i == 0 else "BLANK1")


def draw_panel(layout, context):
    OVERFLOW.clear()
    scene = context.scene
    settings = scene.probe_lights
    measure = _font_measure()
    scale = context.preferences.system.ui_scale
    # What a label has once the panel's margins, a leading icon and the label's padding are taken off (and in the
    # sidebar its tabs), less a little to spare, as screenshots of both editors show (tests/blender/test_ui.py).
    region = context.region
    tabs = 24 if region is not None and region.type == "UI" else 0
    width = 0.95 * ((region.width if region else 300) - (58 + tabs) * scale)
    problem = native.unavailable()
    if problem:
        _lines(layout.column(align=True), problem, width, measure, icon="ERROR")

    col = layout.column(align=True)
    col.prop(settings, "method", text="")
    col.row(align=True).prop(settings, "count_mode", expand=True)
    if settings.count_mode == "ENGINE":
        count, why = engine_count(settings, scene.render.engine)
        _lines(col, "%d lights: %s" % (count, why), width, measure)
    else:
        col.prop(settings, "count" if settings.count_mode == "COUNT" else "max_error")
    col = layout.column(align=True)
    col.row(align=True).prop(settings, "light_type", expand=True)
    col.prop(settings, light_kinds.kind(settings.light_type).setting)
    sub = col.row()
    sub.enabled = settings.lamps_take == "ALL"  # lamps of the sources carry them exactly: no refit
    sub.prop(settings, "refit")
    if settings.method != "sh":  # the SH method does not cut on a working grid
        row = col.row(align=True)
        row.label(text="Grid")
        row.prop(settings, "resolution", expand=True)
    row = col.row(align=True)
    row.label(text="NaN/Inf")
    row.prop(settings, "non_finite", expand=True)

    box = layout.box()
    box.prop(settings, "lamps_take", text="")
    if settings.lamps_take == "SOURCES":
        box.prop(settings, "source_level")
    box.label(text="Lamps replace the world's:")
    c = box.column(align=True)
    sub = c.column(align=True)
    sub.enabled = settings.lamps_take == "ALL"  # the lamps of the sources light every effect, the residual the rest
    sub.prop(settings, "replace_diffuse")
    sub.prop(settings, "replace_reflections")
    c.prop(settings, "replace_background")

    row = layout.row()
    row.scale_y = 1.4
    row.operator("probe_lights.bake", icon="LIGHT_SUN")
    layout.operator("probe_lights.bake_animation", icon="RENDER_ANIMATION")
    row = layout.row(align=True)
    sub = row.row(align=True)
    sub.enabled = has_mix(scene.world) or world_collection(scene.world) is not None
    sub.operator("probe_lights.restore", text="Restore", icon="LOOP_BACK")
    row.operator("probe_lights.tradeoff", text="Tradeoff", icon="SORTTIME")

    _draw_results(layout, context, width, measure)
    if len(settings.tradeoff):
        draw_tradeoff(layout, scene, width, measure)
    _draw_baked_worlds(layout, scene)


def _draw_results(layout, context, width, measure):
    scene = context.scene
    settings = scene.probe_lights
    changed = image_changed(scene.world) if scene.world is not None and world_collection(scene.world) else ""
    if changed:
        _lines(layout.column(align=True), "The world now reads '%s': bake again to follow it" % changed, width,
               measure, icon="ERROR")
    cones = eevee_cones_note(scene)
    if cones:
        _lines(layout.column(align=True), cones, width, measure, icon="ERROR")
    if settings.last_count:
        col = layout.column(align=True)
        _lines(col, "%d lights, %.1f %% of the energy, %.0f ms" % (settings.last_count, settings.last_energy,
                                                                   settings.last_ms), width, measure, icon="CHECKMARK")
        _lines(col, "From " + settings.last_source, width, measure, icon="BLANK1")
        if settings.last_diffuse_error >= 0:
            _lines(col, "Error: diffuse %.2f %%, shadow %.2f %%" % (settings.last_diffuse_error,
                                                                  settings.last_shadow_error),
                   width, measure, icon="BLANK1")
        for note in filter(None, settings.last_notes.split("\n")):
            _lines(col, note, width, measure, icon="INFO")
        for warning in filter(None, settings.last_warnings.split("\n")):
            if "Use Cycles settings" not in warning and "Fit EEVEE shadows" not in warning:
                _lines(col, warning, width, measure, icon="ERROR")
    offer = cycles_settings.advice(scene, settings.last_count) if settings.last_count else ""
    if offer:
        box = layout.box()
        _lines(box.column(align=True), offer, width - 16, measure, icon="ERROR")
        box.operator("probe_lights.cycles_settings", icon="CHECKMARK")
    suns = eevee_settings.baked_suns(scene)
    shadows = eevee_settings.advice(scene, suns)
    if shadows:
        box = layout.box()
        _lines(box.column(align=True), shadows, width - 16, measure, icon="ERROR")
        box.operator("probe_lights.eevee_settings", icon="CHECKMARK")
    elif suns and eevee_settings.fitted(scene):
        _lines(layout.column(align=True), "EEVEE's shadows are fitted to the lamps (Restore world puts them back)",
               width, measure, icon="INFO")
    _draw_probe_bake(layout, scene, width, measure)


def _probe_bake_notes(scene, offered="", in_blenders_panel=False):
    """[(line, icon)]: that the probes were baked with other lamps or objects; what EEVEE's light probe bake lacks
    for the baked suns (in the add-on's panel not while its own bake holds: that line is for Blender's bake
    button); `offered`, probe_volumes.offer's line, when given; and what the bake costs (shown with the other
    notes, beside the bake button)."""
    stale = probe_volumes.stale(scene)
    held = not in_blenders_panel and not stale and probe_volumes.BAKED_KEY in scene
    notes = [(stale, "INFO"), ("" if held else probe_volumes.advice(scene), "ERROR"), (offered, "INFO")]
    if any(note for note, _ in notes):
        notes.append((probe_volumes.cost(scene), "TIME"))
    return [(note, icon) for note, icon in notes if note]


def _draw_probe_bake(layout, scene, width, measure, in_blenders_panel=False):
    """The probe bake's notes (_probe_bake_notes) in a box with the add-on's bake of the probes, and the offer of
    EEVEE's ray tracing where probe_volumes.offer makes one (asked once a redraw). In Blender's own bake panels
    (`in_blenders_panel`) the offer's line is left out: they belong to a volume or list the scene's."""
    offered = probe_volumes.offer(scene)
    notes = _probe_bake_notes(scene, "" if in_blenders_panel else offered, in_blenders_panel)
    if notes:
        box = layout.box()
        column = box.column(align=True)
        for note, icon in notes:
            _lines(column, note, width - 16, measure, icon=icon)
        if offered == probe_volumes.REFLECTIONS:  # the bounce is as it should be: the sphere alone
            box.operator("probe_lights.eevee_ray_tracing", icon="CHECKMARK",
                         text="Add a light probe sphere").ray_tracing = False
        elif offered:  # only EEVEE Next has an offer, and ray tracing
            traced, sphere = scene.eevee.use_raytracing, probe_volumes.wants_sphere(scene)
            if not traced or sphere:
                text = "Add a light probe sphere" if traced else "" if sphere else "Use EEVEE ray tracing"
                box.operator("probe_lights.eevee_ray_tracing", icon="CHECKMARK",
                             **({"text": text} if text else {}))
        box.operator("probe_lights.bake_light_probes", icon="LIGHTPROBE_VOLUME")


def _draw_in_blenders_bake(self, context):
    """Appended to Blender's own light probe bake panels: the same notes and button, where the user bakes (not the
    offer of a volume)."""
    if context.scene is not None:
        region = context.region
        width = 0.95 * ((region.width if region else 300) - 58 * context.preferences.system.ui_scale)
        _draw_probe_bake(self.layout, context.scene, width, _font_measure(), in_blenders_panel=True)


# Blender's panels that hold its light probe bake button: the probe's own (Object Data) and the scene's (Render
# Properties > Light Probes, named eevee_next before 5.0).
_BAKE_PANELS = ("DATA_PT_lightprobe_bake", "SCENE_PT_eevee_next_light_probes", "SCENE_PT_eevee_light_probes")


def register():
    for name in _BAKE_PANELS:
        if hasattr(bpy.types, name):
            getattr(bpy.types, name).append(_draw_in_blenders_bake)


def unregister():
    for name in _BAKE_PANELS:
        if hasattr(bpy.types, name):
            getattr(bpy.types, name).remove(_draw_in_blenders_bake)


def _draw_baked_worlds(layout, scene):
    """Every baked world with its Restore button, when there is more than the scene's own."""
    worlds = baked_worlds()
    if not worlds or worlds == [scene.world]:
        return
    box = layout.box()
    box.label(text="Baked worlds", icon="WORLD")
    for world in worlds:
        row = box.row(align=True)
        row.label(text=world.name, icon="CHECKBOX_HLT" if world == scene.world else "BLANK1")
        row.operator("probe_lights.restore", text="Restore", icon="LOOP_BACK").world = world.name


def _percent(fraction):
    """Three significant digits at most four characters wide, to fit a quarter of the sidebar."""
    p = 100 * fraction
    return "%.2f" % p if p < 10 else "%.1f" % p if p < 100 else "%.0f" % p


def _click_time(ms):
    """A click's time at most four characters wide: milliseconds, or from 10 s on whole seconds ("11s")."""
    return "%.0f" % ms if ms < 9999.5 else "%.0fs" % (ms / 1000)


def draw_tradeoff(layout, scene, width, measure):
    """What accuracy costs, per light count: a whole click's time, in Cycles and EEVEE Next the render's time as a
    multiple of the world-lit render's (render_cost.json, measured in this version or the nearest; where the panel
    is too narrow for five columns, as the sidebar at its default width, not shown), and the estimated errors
    (refit rows when the panel's Refit is on); a count's button uses it."""
    settings = scene.probe_lights
    rows = sorted((r for r in settings.tradeoff if r.refit == settings.refit), key=lambda r: r.lights)
    table = [[str(r.lights), _click_time(r.click_ms), _percent(r.diffuse), _percent(r.shadow)] for r in rows]
    header = ""
    engine = render_cost.engine_of(scene.render.engine, bpy.app.version)
    if engine is not None:
        with_render = [t[:2] + [_times(render_cost.render_factor(r.lights, bpy.app.version, engine))] + t[2:]
                       for r, t in zip(rows, table)]
        if all(fits(text, width / 5 - 6, measure) for t in with_render for text in t[1:]):
            table = with_render
            # (EEVEE's were measured without a GPU, by Mesa's llvmpipe: a GPU's times differ.)
            header = ", %s render time x the world's (%d.%d%s)" % (
                render_cost.ENGINES[engine], *render_cost.measured_version(bpy.app.version, engine)[:2],
                ", without a GPU" if engine == "eevee" else "")
    box = layout.box()
    col = box.column(align=True)
    _lines(col, "Tradeoff (%s%s): lights, ms per click (world, bake, lamps)%s, estimated diffuse and shadow error %%" % (
        settings.tradeoff_method, ", refit" if settings.refit else "", header), width - 16, measure, icon="SORTTIME")
    for r, texts in zip(rows, table):
        row = box.row(align=True)
        row.operator("probe_lights.set_count", text=texts[0]).count = r.lights
        for text in texts[1:]:
            if not fits(text, width / len(texts) - 6, measure):
                OVERFLOW.append(text)
            row.label(text=text)
    if settings.tradeoff_frames:
        _lines(box.column(align=True), animation_cost(settings), width - 16, measure, icon="RENDER_ANIMATION")


def animation_cost(settings):
    """Bake animation's cost at the count, from the Tradeoff's frame: read (or rendered) beside its bake."""
    read, bake = settings.tradeoff_frame_read_ms, settings.tradeoff_frame_bake_ms
    total = settings.tradeoff_frames * max(read, bake) / 1000
    return "Bake animation, %d frames of %d lights: about %s (the world %s in %s beside a %s bake a frame)" % (
        settings.tradeoff_frames, settings.tradeoff_frame_lights, _seconds(total),
        "rendered" if settings.tradeoff_frames_rendered else "read", _seconds(read / 1000), _seconds(bake / 1000))


def _seconds(s):
    """A duration in words: "85 ms", "1.4 s", "69 s", "3 min"."""
    if s < 0.9995:
        return "%.0f ms" % (1000 * s)
    if s < 9.95:
        return "%.1f s" % s
    return "%.0f s" % s if s < 120 else "%.0f min" % (s / 60)


def _times(factor):
    """A render time multiple at most four characters wide ("0.9x", "12x"), or "-" where none was measured."""
    if factor is None:
        return "-"
    return "%.1fx" % factor if factor < 9.95 else "%.0fx" % factor


class PROBE_LIGHTS_PT_world(bpy.types.Panel):
    bl_label = "Probe Lights"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "world"

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def draw(self, context):
        draw_panel(self.layout, context)


class PROBE_LIGHTS_PT_view3d(bpy.types.Panel):
    bl_label = "Probe Lights"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Probe Lights"

    def draw(self, context):
        draw_panel(self.layout, context)


classes = (PROBE_LIGHTS_PT_world, PROBE_LIGHTS_PT_view3d)
