"""The lights a bake makes: one collection owned by the add-on; a re-bake replaces exactly its own lights."""

import bpy
import numpy as np
from mathutils import Matrix

from .conversion import point_parameters, sun_parameters

COLLECTION_TAG = "probe_lights_collection"
OBJECT_TAG = "probe_lights"
COLLECTION_NAME = "Probe Lights"


def find_collection(scene):
    for c in bpy.data.collections:
        if c.get(COLLECTION_TAG) and scene.user_of_id(c):
            return c
    return None


def baked_lights(scene):
    c = find_collection(scene)
    return [o for o in c.objects if o.get(OBJECT_TAG)] if c else []


def remove_lights(scene):
    """Deletes the lights an earlier bake made (only those: anything else in the collection stays)."""
    removed = 0
    for obj in baked_lights(scene):
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            bpy.data.lights.remove(data)
        removed += 1
    return removed


def make_lights(scene, baked, world_from_probe, strength, light_type="SUN", soft_shadows=True, distance=10.0,
                lights_diffuse=True, lights_glossy=False):
    """Creates one lamp per baked light. `baked` is the module's result; directions are turned into the world by
    world_from_probe (the world's mapping) and energies scaled by the Background strength.

    lights_diffuse / lights_glossy: which effects the lamps provide (the world keeps the others, world_mix.py), set
    both as Cycles ray visibility and as EEVEE's diffuse/specular factors."""
    collection = find_collection(scene)
    if collection is None:
        collection = bpy.data.collections.new(COLLECTION_NAME)
        collection[COLLECTION_TAG] = 1
        scene.collection.children.link(collection)
    rotation = np.asarray(world_from_probe, dtype=float)
    directions = baked["direction"] @ rotation.T
    rgb = baked["rgb"] * float(strength)
    objects = []
    for i in range(len(directions)):
        name = "Probe Light %03d" % i
        if light_type == "SUN":
            p = sun_parameters(directions[i], rgb[i], baked["angular_radius"][i], bpy.app.version, soft_shadows)
            data = bpy.data.lights.new(name, "SUN")
            data.angle = p["angle"]
        else:
            p = point_parameters(directions[i], rgb[i], distance)
            data = bpy.data.lights.new(name, "POINT")
            data.shadow_soft_size = 0.0
        data.color = p["color"]
        data.energy = p["energy"]
        if hasattr(data, "diffuse_factor"):
            data.diffuse_factor = 1.0 if lights_diffuse else 0.0
            data.specular_factor = 1.0 if lights_glossy else 0.0
        obj = bpy.data.objects.new(name, data)
        obj[OBJECT_TAG] = 1
        if light_type == "SUN":
            # Where a sun is does not matter; put it where it shines from so the viewport shows the layout.
            obj.matrix_world = Matrix.Translation(tuple(distance * directions[i])) @ Matrix(p["rotation"].tolist()).to_4x4()
        else:
            obj.location = p["location"]
        obj.visible_diffuse = lights_diffuse
        obj.visible_glossy = lights_glossy
        obj.visible_transmission = lights_diffuse
        obj.visible_volume_scatter = lights_diffuse
        collection.objects.link(obj)
        objects.append(obj)
    return objects
