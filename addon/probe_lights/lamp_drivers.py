"""The drivers a baked lamp carries, so that a file renders right without the add-on (a render farm worker runs no
handler and no script): its strength and its rig's rotation read the world's nodes (light_objects.make_lights), and
the rays it lights follow the render engine (route_by_engine). Every expression is a simple one: Blender evaluates
it without Python, also with auto-run off."""

import bpy

from .blender_caps import is_eevee

LAMP_RAYS = ("diffuse", "glossy", "transmission", "volume_scatter")


def _driver_target(socket):
    """(id_type, id, data path) of a node socket's default_value, for a driver variable."""
    tree = socket.id_data
    path = socket.path_from_id("default_value")
    for world in bpy.data.worlds:
        if world.node_tree == tree:
            return "WORLD", world, "node_tree." + path
    return "NODETREE", tree, path


def drive(owner, path, index, expression, name, socket, socket_index=None):
    """owner.path[index] = expression of the variable `name`, read from a node socket's value."""
    id_type, id_, data_path = _driver_target(socket)
    drive_by(owner, path, index, expression, name,
              (id_type, id_, data_path + ("[%d]" % socket_index if socket_index is not None else "")))


def drive_by(owner, path, index, expression, name, target):
    """owner.path[index] = expression of the variable `name`, read from `target` (id_type, id, data path)."""
    fcurve = owner.driver_add(path, index) if index is not None else owner.driver_add(path)
    for m in list(fcurve.modifiers):
        fcurve.modifiers.remove(m)
    driver = fcurve.driver
    driver.type = "SCRIPTED"
    while len(driver.variables) > 1:  # a lamp's strength keyed by Bake animation read a second one
        driver.variables.remove(driver.variables[-1])
    var = driver.variables[0] if len(driver.variables) else driver.variables.new()
    var.name, var.type = name, "SINGLE_PROP"
    var.targets[0].id_type, var.targets[0].id, var.targets[0].data_path = target
    driver.expression = expression  # a simple expression: evaluated without Python, also with auto-run off


# A driver's variable reads an enum property as its value: render.engine's is the engine's place among the
# registered engines, and Blender registers EEVEE first (0), Workbench next, add-ons' engines (Cycles) after; measured
# in 3.4.1, 4.2.23, 4.5.15 and 5.3.0. A simple expression: evaluated without Python, so also with auto-run off.
ENGINE_EXPRESSION = "engine == 0"


def engine_drivers_work(scene):
    """Whether this Blender numbers its engines as ENGINE_EXPRESSION expects (EEVEE first)."""
    items = scene.render.bl_rna.properties["engine"].enum_items
    return any(item.value == 0 and is_eevee(item.identifier) for item in items)


def route_by_engine(obj, split, scene):
    """The lamp lights every ray in EEVEE and its Cycles split elsewhere, by drivers on the rays outside the split:
    the file renders right in either engine on a machine without the add-on (a render farm worker runs no handler;
    `blender -b file.blend -E BLENDER_EEVEE_NEXT -f 1`). The rays of the split carry no driver: the user may turn
    them off."""
    for ray in LAMP_RAYS:
        path = "visible_" + ray
        if ray in split:
            obj.driver_remove(path)
        else:
            drive_by(obj, path, None, ENGINE_EXPRESSION, "engine", ("SCENE", scene, "render.engine"))


def routed_by_engine(obj):
    ad = obj.animation_data
    return ad is not None and any(d.data_path.startswith("visible_") for d in ad.drivers)
