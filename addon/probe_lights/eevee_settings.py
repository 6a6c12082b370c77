"""EEVEE shadow settings the baked suns need, offered and reversible (EEVEE Next: Blender 4.2 and newer).

EEVEE Next keeps every shadow in one pool of pages (Render > Performance > Shadow Pool, 512 MB by default: 2,048
pages). Each sun takes 50 to 165 pages whatever the image size (the higher the sun, the more), so past 12 to 40
suns the pool is full; EEVEE then drops pages by thread timing, and the shadows (and the picture's brightness)
change from one render to the next. Halving the shadow resolution (Shadows > Resolution) takes a sun to about a
tenth of the pages and changes the picture by little (docs/results/eevee.md). The fit is the smallest pool that holds the
suns' pages (and half or quarter resolution when even the largest pool cannot); the values it replaced are kept
on the scene and put back by Restore world.

The fit follows the scene, not the click: a bake makes it in any engine (the file then renders right in EEVEE where
the add-on is not installed: `blender -b file.blend -E BLENDER_EEVEE_NEXT -f 1` on a render farm worker), and it is
made again by itself whenever the scene is to render in EEVEE with baked suns the pool cannot hold (before every
render; when the engine changes to EEVEE; when a file opens in EEVEE), because a full pool is never what the user
wants: its renders are farther from Cycles and differ from one render to the next (docs/results/eevee.md). The panel
says it was done; Restore world undoes it.
"""

import bpy

from . import blender_caps
from .light_objects import baked_lights, sun_height
from .world_mix import has_residual
from .remembered import put_back, set_remembering

BEFORE_KEY = "probe_lights_eevee_before"  # on the scene: the settings the offer replaced

# Pages one sun needs at shadow resolution scale 1, by its elevation: EEVEE Next covers what the sun sees of the
# scene, the more the higher the sun (the fit and its measurements: docs/decisions.md).
PAGES_AT_HORIZON, PAGES_PER_SINE = 44.0, 121.0
# The share of those pages a sun takes at a lower shadow resolution scale (docs/results/eevee.md); a scale between two rows
# costs what the row above does.
RESOLUTION_SHARE = ((1.0, 1.0), (0.5, 12 / 107), (0.25, 7 / 107))
PAGES_PER_MB = 4  # the 512 MB pool holds 2,048 pages
MARGIN = 1.1  # the page count varies a little with the view
MAX_POOL_MB = 1024  # Blender 5.2 offers 2 GB, which failed here ("Could not allocate shadow atlas": nothing rendered)


def eevee_next(scene):
    """Whether the scene renders in EEVEE Next (Blender 4.2 and newer), which keeps every shadow in one pool."""
    return blender_caps.eevee_next(scene.render.engine, bpy.app.version)


def _pages(load, scale):
    """Pages at shadow resolution `scale` of suns that need `load` pages at scale 1 (sun_pages)."""
    share = next((share for at, share in reversed(RESOLUTION_SHARE) if at >= scale - 1e-6), 1.0)
    return int(load * share * MARGIN)


def sun_pages(scene):
    """The pages the baked suns need at shadow resolution scale 1, by their elevations; with a residual world, one
    sun more overhead (EEVEE's own sun extraction may take one from it)."""
    total = 0.0
    for o in baked_lights(scene.world):
        if o.type == "LIGHT" and o.data.type == "SUN":
            total += PAGES_AT_HORIZON + PAGES_PER_SINE * sun_height(o)
    if has_residual(scene.world):
        total += PAGES_AT_HORIZON + PAGES_PER_SINE
    return total


def pool_sizes(scene):
    """The pool sizes this Blender offers, in MB, smallest first."""
    items = scene.eevee.bl_rna.properties["shadow_pool_size"].enum_items
    return sorted(int(item.identifier) for item in items)


def _wanted(scene, suns=None):
    """{setting: value}: the smallest pool (no smaller than the scene's, at most 1 GB) that holds the baked suns'
    pages at the scene's shadow resolution, else at half or a quarter of it; {} when the pool already holds them.
    Given the count of baked suns, it answers from their fewest and most pages (every sun at the horizon, or
    overhead) when both give the same answer, as they do for a few suns or thousands (the answer grows with the
    pages, so the suns' own pages give it too): the panel asks on every redraw, and reading the elevations of
    4,096 suns took 26 ms."""
    if suns is not None:
        extra = PAGES_AT_HORIZON + PAGES_PER_SINE if has_residual(scene.world) else 0.0
        fewest = _wanted_for(scene, suns * PAGES_AT_HORIZON + extra)
        if fewest == _wanted_for(scene, suns * (PAGES_AT_HORIZON + PAGES_PER_SINE) + extra):
            return fewest
    return _wanted_for(scene, sun_pages(scene))


def _wanted_for(scene, load):
    """_wanted for suns that need `load` pages at shadow resolution scale 1."""
    eevee = scene.eevee
    scale = eevee.shadow_resolution_scale
    if _pages(load, scale) <= int(eevee.shadow_pool_size) * PAGES_PER_MB:
        return {}
    pool = int(eevee.shadow_pool_size)
    pools = [mb for mb in pool_sizes(scene) if pool <= mb <= max(pool, MAX_POOL_MB)]  # never smaller than the user's
    for try_scale in [scale] + [s for s, _ in RESOLUTION_SHARE if s < scale - 1e-6]:
        fits = [mb for mb in pools if mb * PAGES_PER_MB >= _pages(load, try_scale)]
        if fits:
            wanted = {"shadow_pool_size": str(fits[0])} if fits[0] != pool else {}
            if try_scale != scale:
                wanted["shadow_resolution_scale"] = try_scale
            return wanted
    return {"shadow_pool_size": str(pools[-1]), "shadow_resolution_scale": RESOLUTION_SHARE[-1][0]}


def advice(scene, suns):
    """One line on what the shadow pool lacks for the `suns` baked suns, or '' when it holds them (or the engine is
    not EEVEE Next)."""
    if not eevee_next(scene) or suns < 2 or not _wanted(scene, suns):
        return ""
    return ("EEVEE's shadow pool is too small for %d suns and drops shadows at random: fit the shadows to the lamps"
            % suns)


def apply(scene):
    """Sets the pool (and resolution) the baked suns need, remembering what it replaced (once). Returns
    {name: value}."""
    if not eevee_next(scene):
        return {}
    return _apply(scene)


def _apply(scene):
    wanted = _wanted(scene)
    set_remembering(scene, BEFORE_KEY, scene.eevee, wanted)
    return wanted


def restore(scene):
    """Puts back what apply() and use_ray_tracing() replaced. Returns the names restored."""
    return sorted(put_back(scene, BEFORE_KEY, scene.eevee,
                           lambda name, value: str(value) if name == "shadow_pool_size" else float(value))
                  + put_back(scene, RAYS_KEY, scene.eevee, lambda name, value: bool(value)))


# EEVEE Next bounces no light by itself. Its ray tracing (Render > Raytracing: screen-traced, with its Fast GI for
# rough surfaces) bounces the lamps' light from what is on screen, with no bake; up to 5.1 that alone comes closest
# to Cycles, from 5.2 it does with a light probe volume baked with the lamps (blender_caps.eevee_bounce). The panel
# offers it as probe_volumes.offer says.
# The settings this module changes, in the panel's and the reports' words.
WORDS = {"shadow_pool_size": "shadow pool", "shadow_resolution_scale": "shadow resolution",
         "use_raytracing": "ray tracing"}
RAYS_KEY = "probe_lights_eevee_rays_before"  # on the scene: ray tracing as it was before use_ray_tracing()


def use_ray_tracing(scene):
    """Turns on EEVEE's ray tracing, remembering it was off (Restore world turns it off again). Returns whether
    it changed."""
    if not eevee_next(scene) or scene.eevee.use_raytracing:
        return False
    set_remembering(scene, RAYS_KEY, scene.eevee, {"use_raytracing": True})
    return True


def baked_suns(scene):
    """The sun lamps the add-on baked for the scene's world: what the shadow pool must hold."""
    return sum(1 for o in baked_lights(scene.world) if o.type == "LIGHT" and o.data.type == "SUN")


def fitted(scene):
    """Whether the pool (or resolution) was fitted to the lamps and not put back yet."""
    return bool(scene.get(BEFORE_KEY))


def follow(scene, any_engine=False):
    """Fits the shadow pool to the scene's baked suns when it renders in EEVEE Next and the pool cannot hold them;
    with `any_engine` (a bake) whatever the engine is now, in a Blender with EEVEE Next: EEVEE's settings change no
    Cycles render, and the file then renders right in EEVEE on a machine without the add-on (a render farm worker,
    `blender -b file.blend -E BLENDER_EEVEE_NEXT -f 1`, runs no handler of ours). Returns what it set ({} when
    nothing was needed)."""
    if not (blender_caps.has_eevee_next(bpy.app.version) if any_engine else eevee_next(scene)):
        return {}
    suns = baked_suns(scene)
    if suns < 2 or not _wanted(scene, suns):
        return {}
    return _apply(scene)


def _say(scene, changed):
    print("Probe Lights: EEVEE %s for the %d baked suns, so that no shadow is dropped (Restore world puts it back)"
          % (describe(changed), baked_suns(scene)))


@bpy.app.handlers.persistent
def _before_render(scene, *_):
    try:
        changed = follow(scene)
    except (AttributeError, ReferenceError, RuntimeError, TypeError):
        return
    if changed:
        _say(scene, changed)


def _engine_changed():
    scene = getattr(bpy.context, "scene", None)
    if scene is not None:
        _before_render(scene)


_OWNER = object()


def _subscribe():
    bpy.msgbus.clear_by_owner(_OWNER)
    bpy.msgbus.subscribe_rna(key=(bpy.types.RenderSettings, "engine"), owner=_OWNER, args=(),
                             notify=_engine_changed, options={"PERSISTENT"})


@bpy.app.handlers.persistent
def _after_load(*_):
    _subscribe()  # a file load clears the message bus
    for scene in bpy.data.scenes:
        _before_render(scene)


def register():
    if not blender_caps.has_eevee_next(bpy.app.version):
        return
    for handlers, f in ((bpy.app.handlers.render_pre, _before_render), (bpy.app.handlers.load_post, _after_load)):
        if f not in handlers:
            handlers.append(f)
    _subscribe()


def unregister():
    for handlers, f in ((bpy.app.handlers.render_pre, _before_render), (bpy.app.handlers.load_post, _after_load)):
        if f in handlers:
            handlers.remove(f)
    bpy.msgbus.clear_by_owner(_OWNER)


def describe(wanted):
    """'shadow pool 1024 MB, shadow resolution 0.5' for a dict apply() returned."""
    units = {"shadow_pool_size": " %s MB", "shadow_resolution_scale": " %g"}
    return ", ".join(WORDS[name] + units[name] % value for name, value in sorted(wanted.items()))
