"""EEVEE's light probe volume bake with baked suns (EEVEE Next: Blender 4.2 and newer).

A volume probe stores the light that reaches each of its points: the world's (which the add-on shows EEVEE for the
camera only, world_mix.py, so the probe keeps no second copy of it) and the light the lamps' light makes bouncing
off the scene. To bounce a sun's light the bake needs its shadow over every surface element it spawns, and it
takes those pages from the same pool as renders, whatever shadow resolution the scene sets: ~100 to 160 pages a
sun (BAKE_PAGES_PER_SUN). Past 13 to 20 suns in the default 512 MB pool, 26 to 40 in 1 GB, the pool is full: EEVEE
drops pages, reports "Shadow buffer full" (an error for a script) and bakes bounce light with shadows missing.

bake() bakes the probes for the lamps as they are when the largest pool holds their shadows; otherwise the
bake sees fewer suns carrying the same light: the brightest suns, each with the light of the suns nearest to it
in direction. Bounce light is smooth (a volume probe keeps two bands of spherical harmonics a point), so the
merged suns bounce nearly the same light (docs/results/eevee.md measures it). The lamps and the pool are put back as
they were when the bake ends, whether it succeeded or not.
"""

import hashlib
import math

import bpy

from . import blender_caps, eevee_settings
from .bake import LUM
from .light_objects import (OBJECT_TAG, VOLUME_TAG, add_to_lamps, baked_lights, scene_box, scenery,
                            sun_direction)
from .world_mix import has_residual

# Shadow pages one sun takes in a volume probe bake, at any shadow resolution scale: the most measured over plane
# and probe sizes (docs/decisions.md), with the render fit's margin on top.
BAKE_PAGES_PER_SUN = 160.0


def volume_probes(scene):
    """The scene's light probe volumes (their data's type is 'VOLUME' from 4.1 on, 'GRID' before)."""
    return [o for o in scene.objects if o.type == "LIGHT_PROBE" and o.data.type in ("VOLUME", "GRID")]


def sphere_probes(scene):
    """The scene's light probe spheres (EEVEE Next's reflection probes; 'CUBEMAP' before 4.1)."""
    return [o for o in scene.objects if o.type == "LIGHT_PROBE" and o.data.type in ("SPHERE", "CUBEMAP")]


def _suns(scene):
    return [o for o in baked_lights(scene.world) if o.type == "LIGHT" and o.data.type == "SUN" and not o.hide_render]


def _largest_pool(scene):
    return max(mb for mb in eevee_settings.pool_sizes(scene) if mb <= eevee_settings.MAX_POOL_MB)


def suns_the_bake_holds(scene, pool_mb=None):
    """How many suns' shadows a volume probe bake holds in a pool of `pool_mb` (the largest the add-on sets by
    default), a residual world counted as one sun more."""
    pages = (pool_mb or _largest_pool(scene)) * eevee_settings.PAGES_PER_MB
    extra = 1 if has_residual(scene.world) else 0
    return max(1, int(pages / (BAKE_PAGES_PER_SUN * eevee_settings.MARGIN)) - extra)


def advice(scene):
    """One line when a volume probe bake in this scene would drop the baked suns' shadows at the scene's pool, or
    ''."""
    if not eevee_settings.eevee_next(scene) or not volume_probes(scene):
        return ""
    suns = len(_suns(scene))
    if suns < 2 or suns <= suns_the_bake_holds(scene, int(scene.eevee.shadow_pool_size)):
        return ""
    return ("EEVEE's light probe bake drops shadows of more than %d suns at this shadow pool: bake the probes here"
            % suns_the_bake_holds(scene, int(scene.eevee.shadow_pool_size)))


# The fitted volume: the objects' bounds and a little more, at EEVEE's default of 4 cells a side. Around the still
# life of docs/results/eevee_rivals.md 4 a side baked in 8-17 s and 16 a side in 275-349 s (2 cores); with 4 a
# side around the sphere over a plane EEVEE came from 7.2-10.9 % to 3.2-6.3 % of Cycles with 4 bounces (15 probes).
# Cells chosen from the objects' size (finer, or about cubic) were no closer to Cycles on one probe in two and
# baked 3-18x longer (docs/decisions.md), so the count stays EEVEE's.
VOLUME_MARGIN, VOLUME_CELLS = 1.05, 4


def _objects_box(scene, what):
    """The box around the scene's rendered objects; ValueError naming `what` when there are none."""
    box = scene_box(scene, rendered_only=True)
    if box is None:
        raise ValueError("the scene has no objects for %s" % what)
    return box


def fit_volume(scene):
    """A light probe volume around the scene's rendered objects, in the lamps' collection (Restore removes it).
    Raises ValueError when the scene has no objects."""
    lo, hi = _objects_box(scene, "a light probe volume to hold")
    half = [max(0.25, (b - a) / 2) * VOLUME_MARGIN for a, b in zip(lo, hi)]
    data = bpy.data.lightprobes.new("Probe Lights volume", "VOLUME")
    data.resolution_x = data.resolution_y = data.resolution_z = VOLUME_CELLS
    obj = bpy.data.objects.new("Probe Lights volume", data)
    obj.location = [(a + b) / 2 for a, b in zip(lo, hi)]
    obj.scale = half
    add_to_lamps(scene, obj, VOLUME_TAG)
    return obj


# The fitted sphere. With all of the light in the lamps EEVEE's world lights nothing (world_mix.py), so what EEVEE
# reflects off the screen is black: a polished metal shows the suns as dots on black. A light probe sphere
# captures the scene as the lamps light it (floor, objects; the world stays black to it: no light twice, measured
# 0.0000 with the lamps hidden) and EEVEE reflects that. On the still life of docs/results/eevee_rivals.md (bpy
# 4.5.15, with ray tracing) it took the add-on from 9.83 to 7.81 % of Cycles on KernerEnvLatLong, 8.71 to 6.79 %
# on noon_grass, 9.02 to 7.44 % on the small studio. EEVEE Next captures it at render time: nothing to bake.
def fit_sphere(scene):
    """A light probe sphere at the centre of the scene's rendered objects, its influence over all of them, in the
    lamps' collection (Restore removes it). Raises ValueError when the scene has no objects."""
    lo, hi = _objects_box(scene, "a light probe sphere to reflect")
    radius = max(0.25, math.dist(tuple(lo), tuple(hi)) / 2) * VOLUME_MARGIN
    data = bpy.data.lightprobes.new("Probe Lights reflections", "SPHERE")
    data.influence_distance = radius
    data.clip_end = max(data.clip_end, 2.0 * radius)  # what it captures: the whole scene from its centre
    obj = bpy.data.objects.new("Probe Lights reflections", data)
    obj.location = [(a + b) / 2 for a, b in zip(lo, hi)]
    add_to_lamps(scene, obj, VOLUME_TAG)
    return obj


# Shader nodes with no mirror-like part for a light probe sphere to give: a material of these alone (with mixes,
# adds and node groups of them) reflects nothing sharp. Any other shader node (Principled, Glossy, Metallic, Glass,
# Toon, Hair, an OSL script...) counts as reflecting, and so do a material without nodes and an object without a
# material (the engines' default surface has a specular part). On the sphere over a plane, all Diffuse BSDF, the
# sphere changed no render of the 15 probes and took each 1.4-2.2x as long (docs/results/eevee_rivals.md).
_MATTE = {"BSDF_DIFFUSE", "BSDF_SHEEN", "BSDF_VELVET", "BSDF_TRANSLUCENT", "BSDF_TRANSPARENT", "EMISSION", "HOLDOUT",
          "SUBSURFACE_SCATTERING", "VOLUME_ABSORPTION", "VOLUME_SCATTER", "PRINCIPLED_VOLUME", "MIX_SHADER",
          "ADD_SHADER", "GROUP_INPUT", "REROUTE"}


def _tree_reflects(tree, seen):
    if tree is None or tree in seen:  # a node group already looked into reflects nothing, or the answer was given
        return False
    seen.add(tree)
    for node in tree.nodes:
        if node.type == "GROUP":
            if _tree_reflects(node.node_tree, seen):
                return True
        elif node.type not in _MATTE and any(socket.type == "SHADER" for socket in node.outputs):
            return True
    return False


def _reflects(material, seen):
    if material is None or not getattr(material, "use_nodes", True) or material.node_tree is None:
        return True
    return _tree_reflects(material.node_tree, seen)


def scene_reflects(scene):
    """Whether a rendered object of the scene has a material that reflects (what a light probe sphere is for):
    its own materials, or the view layers' material override where every view layer rendered has one."""
    seen, materials = set(), set()
    overrides = [layer.material_override for layer in scene.view_layers if layer.use]
    if overrides and all(overrides):
        materials.update(overrides)
    else:
        for obj in scenery(scene, rendered_only=True):
            slots = [slot.material for slot in obj.material_slots] or [None]
            if None in slots:
                return True
            materials.update(slots)
    return any(_reflects(material, seen) for material in materials)


def wants_sphere(scene):
    """Whether a light probe sphere would give the scene something: none yet, and something reflects."""
    return not sphere_probes(scene) and scene_reflects(scene)


def remove_fitted(obj):
    data = obj.data
    bpy.data.objects.remove(obj)
    if data is not None and data.users == 0:
        bpy.data.lightprobes.remove(data)


# What offer() says when EEVEE bounces the lamps' light as it should but has no sphere to reflect the scene by.
REFLECTIONS = "EEVEE reflects only what is on screen of the lamps' light: add a light probe sphere around the scene"


def offer(scene):
    """One line on how EEVEE (Next) should bounce the baked suns' light and reflect the lit scene, or '' when it
    already does as it comes closest to Cycles in this Blender (blender_caps.eevee_bounce): up to 5.1 its ray
    tracing alone, from 5.2 a light probe volume baked with the lamps and ray tracing; in both a light probe sphere
    around the scene (fit_sphere) where something reflects (wants_sphere)."""
    if not eevee_settings.eevee_next(scene) or len(_suns(scene)) == 0:
        return ""
    traced, volumes = scene.eevee.use_raytracing, bool(volume_probes(scene))
    sphere = wants_sphere(scene)
    with_sphere = " with a light probe sphere" if sphere else ""
    version = "%d.%d" % bpy.app.version[:2]
    if blender_caps.eevee_bounce(bpy.app.version) == "ray tracing":
        if volumes and traced:
            return ("In Blender %s EEVEE's ray tracing and a light probe volume together bounce the lamps' light "
                    "farther from Cycles than either alone: turn one off" % version)
        if volumes or traced:
            return REFLECTIONS if sphere else ""
        return ("EEVEE bounces no light by itself%s: turn on its ray tracing%s (in Blender %s closest to Cycles, no "
                "bake), or bake a light probe volume around the scene with the lamps"
                % (" and reflects none of the lamps'" if sphere else "", with_sphere, version))
    if not volumes:
        return ("EEVEE bounces no light without a light probe volume: bake one around the scene with the lamps%s"
                % ("" if traced and not sphere else
                   ", and turn on its ray tracing%s (together closest to Cycles in Blender %s)" % (with_sphere,
                                                                                                 version)))
    if not traced:
        return ("With the light probe volume, EEVEE's ray tracing %s closer to Cycles in Blender %s"
                % ("and a light probe sphere come" if sphere else "comes", version))
    return REFLECTIONS if sphere else ""


# On the scene, after the add-on's bake of the probes: what the bake saw, the lamps' and the scene's part apart;
# and how long it took.
BAKED_KEY = "probe_lights_probes_baked"
SECONDS_KEY = "probe_lights_probes_bake_seconds"

# What a baked volume probe keeps in the .blend: a cell's irradiance as L0 and L1 (4 RGB floats), the sky's
# visibility (4 floats) and a validity byte (DNA's LightProbeGridCacheFrame), 65 bytes, and some 700 a volume: the
# saved file grew by 4,826 bytes at EEVEE's default 4 x 4 x 4 cells, by 33,728 at 8 x 8 x 8 (bpy 4.5.15). EEVEE
# draws the cells from a pool of fixed size (Render > Light Probes > Volume Pool): no more memory on the GPU.
CELL_BYTES, VOLUME_BYTES = 65, 700


def _kilobytes(cells, volumes):
    return "%d KB" % max(1, round((cells * CELL_BYTES + volumes * VOLUME_BYTES) / 1024.0))


def cost(scene):
    """One line on what the bake of the probes costs in EEVEE Next: the scene's volume probes' cells and what they
    keep in the file, and how long the add-on's last bake here took; with no volume yet, those of the one the bake
    fits (fit_volume). '' outside EEVEE Next."""
    if not eevee_settings.eevee_next(scene):
        return ""
    probes = volume_probes(scene)
    if not probes:
        cells = VOLUME_CELLS ** 3
        return "The bake adds a volume of %d cells (%s in the file)" % (cells, _kilobytes(cells, 1))
    cells = sum(math.prod(getattr(o.data, "resolution_" + a) for a in "xyz") for o in probes)
    line = "Light probe volume%s: %d cells, %s in the file" % ("s" if len(probes) > 1 else "", cells,
                                                              _kilobytes(cells, len(probes)))
    seconds = scene.get(SECONDS_KEY)
    return line + ("; the last bake here took %.1f s" % seconds if seconds is not None else "")


def _digest(items):
    return hashlib.sha1(repr(items).encode()).hexdigest()[:16]


def _placed(obj):
    return tuple(round(x, 5) for row in obj.matrix_world for x in row)


def _seen(scene):
    """(the lamps, the rest of the scene) as a volume probe bake sees them: each lamp's place, colour, strength and
    size (the baked world's and the user's own); each rendered object's place and data, each volume probe's place
    and cells. Materials are not read."""
    lights = baked_lights(scene.world) + [o for o in scene.objects if o.type == "LIGHT" and not o.get(OBJECT_TAG)]
    lamps = [(o.name, _placed(o), tuple(round(c, 5) for c in o.data.color), round(o.data.energy, 5),
              round(getattr(o.data, "angle", 0.0), 5), round(getattr(o.data, "shadow_soft_size", 0.0), 5))
             for o in lights if o.type == "LIGHT" and not o.hide_render]
    objects = [(o.name, _placed(o), o.data.name if o.data else "") for o in scenery(scene, rendered_only=True)]
    probes = [(o.name, _placed(o), tuple(getattr(o.data, "resolution_" + a) for a in "xyz"))
              for o in volume_probes(scene)]
    return _digest(sorted(lamps)), _digest(sorted(objects) + sorted(probes))


def remember(scene, seconds):
    """Called after the add-on's bake of the probes: what it baked, for stale(), and how long it took, for cost()."""
    scene[BAKED_KEY] = ",".join(_seen(scene))
    scene[SECONDS_KEY] = float(seconds)


def stale(scene):
    """One line when the lamps or the objects changed since the add-on's last bake of the probes (a new bake of the
    lamps, the world's strength, a moved object), or ''. Blender's own bake button is not seen: the line says
    what changed since the add-on's bake, and shows in Blender's bake panels too."""
    baked = str(scene.get(BAKED_KEY, ""))
    if not baked or not eevee_settings.eevee_next(scene) or not volume_probes(scene):
        return ""
    lamps, scenery = baked.split(",") if "," in baked else (baked, "")
    now_lamps, now_scenery = _seen(scene)
    if lamps != now_lamps:
        return "The lamps changed since the light probes were baked here: bake them again for their bounce light"
    if scenery != now_scenery:
        return "The objects changed since the light probes were baked here: bake them again"
    return ""


def _luminance(lamp):
    return lamp.data.energy * float(LUM @ tuple(lamp.data.color))


def merge_plan(suns, keep):
    """{representative: [suns it carries, itself first]} for the `keep` brightest suns, each other sun joined to
    the representative nearest to it in direction."""
    order = sorted(suns, key=_luminance, reverse=True)
    reps = order[:keep]
    plan = {rep: [rep] for rep in reps}
    directions = {o: sun_direction(o) for o in suns}
    for o in order[keep:]:
        nearest = max(reps, key=lambda rep: directions[rep].dot(directions[o]))
        plan[nearest].append(o)
    return plan


class _Merged:
    """Within `with`: each representative's colour carries its group's light (Light.color has no upper limit; the
    energy stays the world-strength driver's), the rest hidden from renders and bakes. Put back on exit."""

    def __init__(self, plan):
        self.plan = plan
        self.saved = []

    def __enter__(self):
        try:
            for rep, group in self.plan.items():
                if len(group) == 1:
                    continue
                energy = rep.data.energy
                total = [sum(o.data.energy * o.data.color[i] for o in group) for i in range(3)]
                self.saved.append((rep, "color", tuple(rep.data.color)))
                rep.data.color = [max(0.0, t / energy) if energy else 0.0 for t in total]
                for o in group[1:]:
                    self.saved.append((o, "hide_render", o.hide_render))
                    o.hide_render = True
        except BaseException:
            self.__exit__()  # what was changed before the failure
            raise
        return self

    def __exit__(self, *_):
        for obj, name, value in reversed(self.saved):
            if name == "color":
                obj.data.color = value
            else:
                obj.hide_render = value
        return False


def bake(context):
    """Bakes every light probe volume of the scene with its baked suns (at most as many as the largest pool's
    shadows hold, merged as the module says). Should EEVEE still find the pool full (a scene beyond the pages
    measured above), the bake is made again with half as many suns. Returns (suns baked, suns the bake saw)."""
    scene = context.scene
    suns = _suns(scene)
    pool = _largest_pool(scene)
    keep = min(len(suns), suns_the_bake_holds(scene, pool))
    eevee = scene.eevee
    before = (eevee.shadow_pool_size, eevee.shadow_resolution_scale)
    extra = 1 if has_residual(scene.world) else 0
    try:
        while True:
            needed = math.ceil((keep + extra) * BAKE_PAGES_PER_SUN * eevee_settings.MARGIN
                               / eevee_settings.PAGES_PER_MB)
            fits = [mb for mb in eevee_settings.pool_sizes(scene) if needed <= mb <= pool]
            eevee.shadow_pool_size = str(max(int(before[0]), fits[0] if fits else pool))
            try:
                with _Merged(merge_plan(suns, keep) if keep < len(suns) else {}):
                    bpy.ops.object.lightprobe_cache_bake(subset="ALL")
                return len(suns), keep
            except RuntimeError as e:
                if "Shadow buffer full" not in str(e) or keep <= 1:  # Blender's words: its only sign of it
                    raise
                keep //= 2
    finally:
        eevee.shadow_pool_size, eevee.shadow_resolution_scale = before
