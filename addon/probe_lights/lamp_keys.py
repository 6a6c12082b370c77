"""The keys Bake animation puts on lamps (animation.py), and taking them off again: a single bake that reuses a
lamp, and Restore, leave no keyframes or actions behind."""

import bpy

ENERGY_KEY = "probe_lights_energy"  # on a lamp's light: its keyed strength before the world's (Bake animation)


def actions_of(owners):
    """The keyframe actions (Bake animation's) only these owners use."""
    found = {o.animation_data.action for o in owners if o.animation_data is not None}
    return [a for a in found if a is not None and a.users == sum(
        1 for o in owners if o.animation_data is not None and o.animation_data.action == a)]


def drop_keyframes(obj):
    """Takes a lamp's keyframes (and their actions) off it and its light, and its keyed strength: a bake that
    reuses it sets plain values."""
    owners = [o for o in (obj, obj.data) if o is not None]
    actions = actions_of(owners)
    for o in owners:
        if o.animation_data is not None:
            o.animation_data.action = None
    if obj.data is not None and ENERGY_KEY in obj.data:
        del obj.data[ENERGY_KEY]
    if actions:
        bpy.data.batch_remove(actions)
    obj.rotation_mode = "XYZ"


def drive_energy_by_key(data, key):
    """A lamp's energy driver (e * s: the world's Strength s) made to read e from the light's property `key`,
    which keyframes change (Bake animation); a simple expression, evaluated without Python."""
    driver = next(d for d in data.animation_data.drivers if d.data_path == "energy").driver
    var = driver.variables.get("e") or driver.variables.new()
    var.name, var.type = "e", "SINGLE_PROP"
    var.targets[0].id_type, var.targets[0].id, var.targets[0].data_path = "LIGHT", data, '["%s"]' % key
    driver.expression = "e*s"
