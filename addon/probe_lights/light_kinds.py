"""The kinds of lamp a bake makes, described once (no bpy): what the panel offers and asks for each, how the core
is asked for their angles, where the lamps sit and whether the render-cost advice speaks of them. The lamp code
(light_objects.py), the panel (ui.py, properties.py) and the bake (bake.py) read these instead of testing names."""
from collections import namedtuple

LightKind = namedtuple("LightKind", [
    "id",           # Blender's light type
    "label",        # the panel's button
    "description",  # its tooltip
    "soft",         # soft shadows from an angle the core fits (sun_parameters); else hard points (point_parameters)
    "on_dome",      # placed on a dome around the scene (only its direction matters); else at the chosen distance
    "setting",      # the panel's setting for this kind: "shadows" or "distance"
    "render_cost",  # the advice on how many lamps pay off in a render (render_cost.py) was measured for it
])

KINDS = (
    LightKind("SUN", "Sun", "Sun lamps: parallel light, each with a soft shadow fitted to its region's light",
              soft=True, on_dome=True, setting="shadows", render_cost=True),
    LightKind("POINT", "Point", "Point lamps on a sphere around the origin",
              soft=False, on_dome=False, setting="distance", render_cost=False),
)
BY_ID = {k.id: k for k in KINDS}
DEFAULT = KINDS[0].id


def kind(light_type):
    """The description of a light type ("SUN", "POINT")."""
    return BY_ID[light_type]


def enum_items():
    """The panel's choices, as Blender's EnumProperty takes them."""
    return [(k.id, k.label, k.description) for k in KINDS]
