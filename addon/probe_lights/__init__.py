"""Probe Lights: bake the world's HDRI into sun or point lights that light the scene the way the world does.

Layout (glTF-Blender-IO style): rules that need no bpy (core_tables.py: the core's menus; blender_caps.py: what
each Blender does; world_graph.py, conversion.py, light_kinds.py, render_cost.py, text_fit.py) apart from Blender
glue (world_image.py, world_mix.py, light_objects.py and its lamps' drivers in lamp_drivers.py, cycles_settings.py,
eevee_settings.py, probe_volumes.py), what a click does (bake.py; animation.py for a world that changes over time,
its lamps' keys in lamp_keys.py), and the thin shells the user touches (operators.py, animation_operator.py,
properties.py, ui.py). The sampling itself is the native module _probelights, built into this package and imported on first use (native.py).
"""

bl_info = {
    "name": "Probe Lights",
    "author": "probelights developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > World > Probe Lights; 3D View > Sidebar > Probe Lights",
    "description": "Bake the world's HDRI into sun or point lights with matching colour, strength and shadows",
    "category": "Lighting",
}

import bpy  # noqa: E402

from . import animation_operator, eevee_settings, light_objects, native, operators, properties, ui, world_image  # noqa: E402,E501

classes = properties.classes + operators.classes + animation_operator.classes + ui.classes


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    properties.register()
    light_objects.register()
    eevee_settings.register()
    ui.register()


def unregister():
    world_image.unregister()
    ui.unregister()
    eevee_settings.unregister()
    native.unregister()
    light_objects.unregister()
    properties.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
