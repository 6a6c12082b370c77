"""The kinds of lamp a bake makes (no bpy): the core's kinds (lightKinds, light_export.h: core_tables.py) with what
Blender adds to each: what the panel offers and asks for each, how the core is asked for their angles, where the
lamps sit and whether the render-cost advice speaks of them. The lamp code (light_objects.py), the panel (ui.py,
properties.py) and the bake (bake.py) read these instead of testing names."""
from collections import namedtuple

try:
    from . import core_tables
except ImportError:  # plain Python's tests, with the add-on's folder on the path
    import core_tables

LightKind = namedtuple("LightKind", [
    "id",           # Blender's light type: the core's name in capitals
    "label",        # the panel's button
    "description",  # its tooltip
    "soft",         # soft shadows from an angle the core fits (sun_parameters); else hard points (point_parameters)
    "on_dome",      # placed on a dome around the scene (only its direction matters); else at the chosen distance
    "setting",      # the panel's setting for this kind: "shadows" (its angles) or "distance"
    "render_cost",  # the advice on how many lamps pay off in a render (render_cost.py) was measured for it
])

# bench/bench_render_counts.py measures renders with suns (render_cost.json).
_RENDER_COST_MEASURED = {"sun"}

KINDS = tuple(LightKind(k["name"].upper(), k["label"], k["description"], soft=k["fitted_angle"],
                        on_dome=k["on_dome"], setting="shadows" if k["fitted_angle"] else "distance",
                        render_cost=k["name"] in _RENDER_COST_MEASURED) for k in core_tables.LIGHT_KINDS)
BY_ID = {k.id: k for k in KINDS}
DEFAULT = KINDS[0].id
DEFAULT_DISTANCE = core_tables.DEFAULT_DISTANCE  # metres from the origin, point lamps


def kind(light_type):
    """The description of a light type ("SUN", "POINT")."""
    return BY_ID[light_type]


def enum_items():
    """The panel's choices, as Blender's EnumProperty takes them."""
    return [(k.id, k.label, k.description) for k in KINDS]
