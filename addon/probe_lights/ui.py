"""Panels: World properties and the 3D viewport sidebar show the same controls."""

import json

import bpy

from . import native
from .world_mix import has_mix


def draw_panel(layout, context):
    settings = context.scene.probe_lights
    problem = native.unavailable()
    if problem:
        layout.label(text=problem, icon="ERROR")
    col = layout.column(align=True)
    col.prop(settings, "method")
    row = col.row(align=True)
    row.prop(settings, "count_mode", expand=True)
    col.prop(settings, "count" if settings.count_mode == "COUNT" else "max_error")
    col.prop(settings, "refit")
    col.prop(settings, "light_type")
    if settings.light_type == "SUN":
        col.prop(settings, "soft_shadows")
    else:
        col.prop(settings, "distance")
    if settings.method != "sh":  # the SH method does not cut on a working grid
        col.prop(settings, "resolution")
    box = layout.box()
    box.label(text="Replace with lights:")
    row = box.row(align=True)
    row.prop(settings, "replace_diffuse", toggle=True)
    row.prop(settings, "replace_reflections", toggle=True)
    row.prop(settings, "replace_background", toggle=True)
    row = layout.row(align=True)
    row.scale_y = 1.4
    row.operator("probe_lights.bake", icon="LIGHT_SUN")
    sub = row.row(align=True)
    sub.enabled = has_mix(context.scene.world) or settings.last_count > 0
    sub.operator("probe_lights.restore", icon="LOOP_BACK")
    layout.operator("probe_lights.tradeoff", icon="SORTTIME")
    if settings.tradeoff_rows:
        draw_tradeoff(layout, json.loads(settings.tradeoff_rows))
    if settings.last_count:
        col = layout.column(align=True)
        col.label(text="%d lights, %.1f %% of the energy, %.0f ms" % (settings.last_count, settings.last_energy,
                                                                    settings.last_ms))
        col.label(text="From " + settings.last_source)
        if settings.last_diffuse_error >= 0:
            col.label(text="Estimated error: diffuse %.2f %%, shadow %.2f %%" % (settings.last_diffuse_error,
                                                                            settings.last_shadow_error))
        if settings.last_notes:
            col.label(text=settings.last_notes, icon="INFO")


def draw_tradeoff(layout, table):
    """What accuracy costs, per light count: bake time and estimated errors, plain and refit; a count's button uses
    it."""
    box = layout.box()
    box.label(text="Accuracy vs time, %s, %s" % (table["method"], table["source"]), icon="SORTTIME")
    by_count = {}
    for r in table["rows"]:
        by_count.setdefault(r["lights"], {})[r["refit"]] = r
    header = box.row()
    for text in ("Lights", "Bake ms", "Diffuse", "Shadow", "Refit: diffuse", "Shadow"):
        header.label(text=text)
    for n in sorted(by_count):
        plain, refit = by_count[n].get(False), by_count[n].get(True)
        row = box.row()
        row.operator("probe_lights.set_count", text=str(n)).count = n
        row.label(text="%.1f" % plain["bake_ms"])
        row.label(text="%.2f %%" % (100 * plain["diffuse"]))
        row.label(text="%.2f %%" % (100 * plain["shadow"]))
        row.label(text="%.2f %%" % (100 * refit["diffuse"]) if refit else "")
        row.label(text="%.2f %%" % (100 * refit["shadow"]) if refit else "")


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
