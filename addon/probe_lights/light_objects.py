"""The lamps a bake makes: each baked world owns one collection ("Probe Lights: <world>") holding one rig empty and
the lamps parented to it. A re-bake replaces exactly its own objects; anything a user adds to the collection stays.

    rig (an empty at the dome's centre, drawn as the dome)    rotation = the world's Mapping rotation (driver)
      +- lamp i at radius * d_i (d_i: the light's direction in the probe's own frame)
           energy = e_i * Background strength (driver)

Suns sit on a dome around the scene's bounds (where a sun is does not change its light); point lamps at their
distance from the origin (where their light is measured). Only the lamps of the scene's current world are in its
view layers: switching the scene's world switches the lamps (sync_visibility, run after every depsgraph update).
"""

import bpy
import numpy as np
from mathutils import Matrix, Vector

from . import light_kinds, world_mix
from .blender_caps import is_eevee
from .lamp_drivers import LAMP_RAYS, drive, engine_drivers_work, route_by_engine, routed_by_engine
from .lamp_keys import actions_of, drop_keyframes
from .conversion import point_parameters, sun_parameters

COLLECTION_TAG = "probe_lights_collection"
WORLD_KEY = "probe_lights_world"  # on the collection: the world it was baked from (an ID pointer)
OBJECT_TAG = "probe_lights"
RIG_TAG = "probe_lights_rig"
VOLUME_TAG = "probe_lights_volume"  # a light probe (volume or sphere) the add-on fitted (probe_volumes.py): Restore
# removes it
COLLECTION_NAME = "Probe Lights: %s"
SUN_SCALE = 0.1  # a sun's object scale: its light does not change, its viewport line is a tenth as long
NOT_SCENERY = {"LIGHT", "CAMERA", "EMPTY", "SPEAKER", "LIGHT_PROBE", "LIGHTPROBE"}
RAYS_KEY = "probe_lights_rays"  # on a lamp: the rays it lights in Cycles, its bake's split ("diffuse,volume_scatter")


def world_collection(world):
    """The collection holding `world`'s lamps, or None."""
    if world is None:
        return None
    for c in bpy.data.collections:
        if c.get(COLLECTION_TAG) and c.get(WORLD_KEY) == world:
            return c
    # Version 0.1 made one "Probe Lights" collection per scene, not tied to a world: it belongs to a baked world
    # of a scene it is in (adopted, i.e. tied to it, by the next bake).
    from .world_mix import has_mix
    if has_mix(world):
        for c in bpy.data.collections:
            if c.get(COLLECTION_TAG) and c.get(WORLD_KEY) is None and any(
                    s.world == world and s.user_of_id(c) for s in bpy.data.scenes):
                return c
    return None


def baked_worlds():
    """Every world that has baked lamps or the add-on's mix, by name."""
    from .world_mix import has_mix
    worlds = {c.get(WORLD_KEY) for c in bpy.data.collections if c.get(COLLECTION_TAG)} - {None}
    worlds |= {w for w in bpy.data.worlds if has_mix(w)}
    return sorted(worlds, key=lambda w: w.name)


def sun_direction(lamp):
    """The unit direction towards a sun lamp as it stands now (rig and drivers applied): a sun shines along its
    -Z."""
    up = lamp.matrix_world.to_3x3().col[2]
    return up / max(up.length, 1e-12)


def sun_height(lamp):
    """|sin| of a sun lamp's elevation as it stands now."""
    return min(1.0, abs(sun_direction(lamp).z))


def baked_lights(world):
    c = world_collection(world)
    return [o for o in c.objects if o.get(OBJECT_TAG)] if c else []


def rig(world):
    c = world_collection(world)
    return next((o for o in c.objects if o.get(RIG_TAG)), None) if c else None


def remove_lights(world):
    """Deletes the lamps (and rig) an earlier bake of `world` made; anything else in the collection stays. Returns
    how many lamps were removed."""
    c = world_collection(world)
    if c is None:
        return 0
    objects = [o for o in c.objects if o.get(OBJECT_TAG) or o.get(RIG_TAG) or o.get(VOLUME_TAG)]
    lamps = sum(1 for o in objects if o.get(OBJECT_TAG))
    _remove(c, objects)
    return lamps


def _remove(collection, objects):
    """Removes `objects` (of `collection`) and their lamps' data in two batches, with the collection unlinked
    meanwhile (no view-layer update per object, which made removing thousands of lamps one by one slow)."""
    if not objects:
        return
    data = [o.data for o in objects if o.data is not None and o.data.users == 1]
    data += actions_of(objects + data)
    parents = [p for p in list(bpy.data.collections) + [s.collection for s in bpy.data.scenes]
               if p.children.get(collection.name) == collection]
    for p in parents:
        p.children.unlink(collection)
    try:
        bpy.data.batch_remove(objects)
        bpy.data.batch_remove(data)
    finally:
        for p in parents:
            p.children.link(collection)


def remove_collection_if_empty(world):
    """Removes `world`'s collection when nothing is left in it. True if removed."""
    c = world_collection(world)
    if c is None or len(c.all_objects) or len(c.children):
        return False
    bpy.data.collections.remove(c)
    return True


def _collection(scene, world):
    c = world_collection(world)
    if c is None:
        c = bpy.data.collections.new(COLLECTION_NAME % world.name)
        c[COLLECTION_TAG] = 1
    if c.get(WORLD_KEY) is None:
        c[WORLD_KEY] = world
    if c.name not in scene.collection.children:
        scene.collection.children.link(c)
    return c


def scenery(scene, rendered_only=False):
    """The scene's objects that light falls on (not lamps, cameras, empties or light probes; with `rendered_only`,
    not those hidden from renders)."""
    return [o for o in scene.objects
            if not (o.type in NOT_SCENERY or o.get(OBJECT_TAG) or (rendered_only and o.hide_render))]


def scene_box(scene, rendered_only=False):
    """(lowest, highest corner) of the box around the scenery (`rendered_only` as scenery's), or None."""
    corners = []
    for obj in scenery(scene, rendered_only):
        m = obj.matrix_world
        corners += [m @ Vector(tuple(v)) for v in obj.bound_box]
    if not corners:
        return None
    a = np.array([tuple(c) for c in corners])
    return a.min(axis=0), a.max(axis=0)


def scene_bounds(scene):
    """Centre and radius of the sphere around the scene's objects (not lamps, cameras or empties), or None."""
    box = scene_box(scene)
    if box is None:
        return None
    lo, hi = box
    return (lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2)


def add_to_lamps(scene, obj, tag):
    """Puts `obj` (tagged `tag`) in the collection of the lamps of the scene's world: it goes with them (Restore,
    a switch of the world)."""
    obj[tag] = 1
    _collection(scene, scene.world).objects.link(obj)


def make_lights(scene, world, baked, source, light_type=light_kinds.DEFAULT, distance=light_kinds.DEFAULT_DISTANCE,
                lights_diffuse=True, lights_glossy=False):
    """Creates one lamp per baked light under `world`'s rig. `baked` is the module's result (directions in the
    probe's frame); `source` (world_graph.ProbeSource) says how the world turns the probe (world_from_probe, the
    rig's rotation) and its Background strength (the lamps' energy scale); both are followed by drivers when the
    world sets them with one Mapping node and a constant Strength. Suns get the angle the core gave each light.

    lights_diffuse / lights_glossy: which effects the lamps provide in Cycles (the world keeps the others,
    world_mix.py), set as their ray visibility; in EEVEE they light every effect."""
    collection = _collection(scene, world)
    kind = light_kinds.kind(light_type)
    if kind.on_dome:  # where a sun is does not change its light: around the scene, drawn small
        bounds = scene_bounds(scene)
        centre, radius = (bounds[0], max(1.0, 1.5 * bounds[1])) if bounds else ((0.0, 0.0, 0.0), distance)
    else:
        centre, radius = (0.0, 0.0, 0.0), distance
    holder = _rig(collection, world, source, centre, radius)

    # A re-bake reuses the lamps it can (same type, in name order) and removes only the surplus: re-baking
    # thousands of lamps costs no removal.
    lights = baked["lights"]
    count = len(lights["direction"])
    reusable = sorted((o for o in collection.objects if o.get(OBJECT_TAG) and o.data is not None
                       and o.data.type == light_type and o.data.users == 1), key=lambda o: o.name)
    kept = reusable[:count]
    _remove(collection, [o for o in collection.objects if o.get(OBJECT_TAG) and o not in kept])

    light_tree = hasattr(getattr(scene, "cycles", None), "use_light_tree")  # Cycles 3.5+ (None: Cycles disabled)
    by_drivers = engine_drivers_work(scene)
    strength = float(source.strength)
    follow_strength = source.strength_socket is not None and strength != 0.0
    objects = []
    for i, direction in enumerate(np.asarray(lights["direction"], float)):
        rgb = lights["rgb"][i]
        if i < len(kept):
            obj = kept[i]
            data = obj.data
            drop_keyframes(obj)
        else:
            name = "Probe Light %03d" % i
            data = bpy.data.lights.new(name, light_type)
            obj = bpy.data.objects.new(name, data)
            obj[OBJECT_TAG] = 1
            collection.objects.link(obj)
        obj.parent = holder
        if kind.soft:
            p = sun_parameters(direction, rgb, lights["angle"][i], bpy.app.version)  # the core's angle: fitted or 0
            data.angle = p["angle"]
            # Drawn small: the viewport draws a sun's direction line in object space; Cycles and EEVEE use only the
            # sun's direction (tests/blender/test_render.py renders a scaled sun).
            obj.matrix_basis = (Matrix.Translation(tuple(radius * direction)) @
                                Matrix(p["rotation"].tolist()).to_4x4() @ Matrix.Scale(SUN_SCALE, 4))
        else:
            p = point_parameters(direction, rgb, distance)
            data.shadow_soft_size = 0.0
            obj.matrix_basis = Matrix.Translation(p["location"])
        data.color = p["color"]
        if follow_strength:
            drive(data, "energy", None, "%.9g*s" % p["energy"], "s", source.strength_socket)
        else:
            data.driver_remove("energy")
            data.energy = p["energy"] * strength
        # Cycles routes the lamps by their ray visibility (below) and ignores these factors (3.4.1, 4.5.15, 5.3.0);
        # EEVEE honours them. EEVEE shows the world to the camera only (world_mix.py), so there the lamps light
        # everything whatever Cycles keeps of the world: with the specular factor at 0, the default bake rendered a
        # Glossy BSDF ball black in EEVEE (0.548 lit by the world; tests/blender/test_eevee.py).
        if hasattr(data, "diffuse_factor"):
            data.diffuse_factor = data.specular_factor = 1.0
        # Transmission goes with reflections: glass refracts the world, which lamps seen through it would light
        # again (world_mix.py; docs/decisions.md)
        rays = [r for r, lit in zip(LAMP_RAYS, (lights_diffuse, lights_glossy, lights_glossy, lights_diffuse)) if lit]
        obj[RAYS_KEY] = ",".join(rays)
        _show_to(obj, LAMP_RAYS if is_eevee(scene.render.engine) else rays)
        route_by_engine(obj, rays if by_drivers else LAMP_RAYS, scene)  # else the handler routes it
        # Multiple importance sampling only when the lamps light reflections, in a Cycles with a light tree. With MIS
        # a lamp's light on a many-closure BSDF (Principled) is shared between the lamp's own samples, which Cycles
        # evaluates closure by closure against the lamp's visibility (the glossy closures left out), and rays
        # bounced off the surface, labelled by the one closure they sampled but carrying the whole BSDF's value:
        # the two shares do not add up to the diffuse closures' light. Without MIS only the lamp's own samples
        # reach it (docs/results/glossy.md: closer to the world's render on glossy materials in 4.5, shorter renders).
        # Cycles 3.x has no light tree: it picks among the lamps nearly uniformly and MIS keeps its many-lamp
        # renders from getting noisier (docs/decisions.md).
        if hasattr(data, "cycles"):  # not when the Cycles add-on is disabled
            data.cycles.use_multiple_importance_sampling = bool(lights_glossy) or not light_tree
        objects.append(obj)
    sync_visibility(scene)
    _hide_rig(scene, holder)
    return objects


def _hide_rig(scene, holder):
    """Hides the rig in the scene's view layers (eye icon): a visible parent draws a dashed line to each of its
    lamps (the viewport's relationship lines), which covered the scene. Hidden this way it is still evaluated, so it
    still turns its lamps (hidden with hide_viewport it would not be)."""
    for layer in scene.view_layers:
        try:
            holder.hide_set(True, view_layer=layer)
        except RuntimeError:  # not in that view layer (its collection excluded)
            pass


def _rig(collection, world, source, centre, radius):
    """The world's rig (made or reused): at the dome's centre, drawn as the dome, turned as the world turns the
    probe; by drivers on the world's Mapping rotation when one Mapping node sets it."""
    holder = next((o for o in collection.objects if o.get(RIG_TAG)), None)
    if holder is None:
        holder = bpy.data.objects.new("Probe Lights rig: %s" % world.name, None)
        holder[RIG_TAG] = 1
        holder.hide_render = True
        collection.objects.link(holder)
    holder.empty_display_type = "SPHERE"
    holder.empty_display_size = radius
    holder.location = tuple(centre)
    holder.driver_remove("rotation_euler")
    holder.rotation_euler = (0.0, 0.0, 0.0)
    if source.rotation_socket is not None:
        # Mapping (Point/Vector/Normal) looks up R @ d, so the world turns the probe by R^T = Rx(-x) Ry(-y) Rz(-z):
        # Euler ZYX (-x, -y, -z); a Texture mapping turns it by R: Euler XYZ (x, y, z).
        holder.rotation_mode = "ZYX" if source.rotation_inverted else "XYZ"
        sign = "-" if source.rotation_inverted else ""
        for i in range(3):
            drive(holder, "rotation_euler", i, sign + "r", "r", source.rotation_socket, i)
    else:
        holder.rotation_mode = "QUATERNION"
        holder.rotation_quaternion = Matrix(np.asarray(source.world_from_probe, float).tolist()).to_quaternion()
    return holder


def sync_visibility(scene):
    """Only the scene's current world's lamps take part in its view layers (the others' collections are excluded,
    never deleted): a scene is never lit by two worlds' lamps."""
    for c in scene.collection.children:
        if not c.get(COLLECTION_TAG):
            continue
        exclude = c.get(WORLD_KEY) != scene.world
        for layer in scene.view_layers:
            child = layer.layer_collection.children.get(c.name)
            if child is not None and child.exclude != exclude:
                child.exclude = exclude
                if not exclude:
                    for holder in (o for o in c.objects if o.get(RIG_TAG)):
                        _hide_rig(scene, holder)


def _show_to(obj, rays):
    """Makes the lamp light exactly `rays` (LAMP_RAYS names); True if anything changed."""
    changed = False
    for ray in LAMP_RAYS:
        if getattr(obj, "visible_" + ray) != (ray in rays):
            setattr(obj, "visible_" + ray, ray in rays)
            changed = True
    return changed


def _shown_to(obj):
    return {ray for ray in LAMP_RAYS if getattr(obj, "visible_" + ray)}


def follow_engine(scene):
    """The lamps' ray visibility follows the render engine. Cycles keeps the world for the effects the bake's split
    left to it (reflections by default) and the lamps light the others, routed by ray visibility. EEVEE shows the
    world to the camera only (world_mix.py), so there the lamps light every effect: EEVEE 4.2 and newer honours a
    lamp's ray visibility (a Glossy BSDF ball lit by 16 lamps of the default split rendered black; bpy 4.5.15 and
    5.3.0), EEVEE Legacy does not. A lamp whose visibility is neither of the two (the user's own) is left as it
    is. Lamps baked since 2026-12-06 follow it by drivers (lamp_drivers.route_by_engine), which need no add-on;
    this keeps earlier bakes' lamps following it. Returns how many lamps changed."""
    eevee = is_eevee(scene.render.engine)
    changed = 0
    lamps = (o for c in scene.collection.children if c.get(COLLECTION_TAG) for o in c.objects)
    for obj in lamps:  # the baked collections only: this runs after every depsgraph update
        if obj.type != "LIGHT" or not obj.get(OBJECT_TAG) or routed_by_engine(obj):
            continue
        if RAYS_KEY not in obj:  # baked before 2026-12-05 (in Cycles' split, factors 0): adopted once
            obj[RAYS_KEY] = ",".join(sorted(_shown_to(obj)))
            if hasattr(obj.data, "diffuse_factor"):
                obj.data.diffuse_factor = obj.data.specular_factor = 1.0
        split = {r for r in str(obj[RAYS_KEY]).split(",") if r in LAMP_RAYS}
        want, other = (set(LAMP_RAYS), split) if eevee else (split, set(LAMP_RAYS))
        if _shown_to(obj) == other and _show_to(obj, want):
            changed += 1
    return changed


@bpy.app.handlers.persistent
def _follow_world(scene, *_):
    """After every depsgraph update and before every render: the lamps of the scene's world only, lighting the rays
    the engine needs, and the residual at the world's strength."""
    try:
        sync_visibility(scene)
        follow_engine(scene)
        world_mix.follow_strength(scene.world)
    except (AttributeError, ReferenceError, RuntimeError):
        pass


_HANDLERS = (("depsgraph_update_post", _follow_world), ("render_pre", _follow_world))


def register():
    for name, f in _HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if f not in handlers:
            handlers.append(f)


def unregister():
    for name, f in _HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if f in handlers:
            handlers.remove(f)
