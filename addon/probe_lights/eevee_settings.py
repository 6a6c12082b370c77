"""EEVEE shadow settings the baked suns need, offered and reversible (EEVEE Next: Blender 4.2 and newer).

EEVEE Next keeps every shadow in one pool of pages (Render > Performance > Shadow Pool, 512 MB by default: 2,048
pages). Each sun takes about 106 pages whatever the image size, so past about 19 suns the pool is full; EEVEE then
drops pages by thread timing, and the shadows (and the picture's brightness) change from one render to the next.
Measured (tests/blender/test_eevee.py's scene, noon_grass, 64 suns): 6,299 pages at 1920x1080 and 6,807 at
320x240; lit objects 4.2 % to 7.3 % from the world-lit render in repeated runs, 4.29 % every time once the pool
held them. Halving the shadow resolution (Shadows > Resolution) takes 64 suns to 749 pages and changed a 16-sun
render by 0.14 %. The panel says what the pool lacks and offers one click that sets the smallest pool that holds the
suns' pages (and half or quarter resolution when even the largest pool cannot); the values it replaced are kept on
the scene and put back by Restore world.
"""

import bpy

from .remembered import put_back, set_remembering

BEFORE_KEY = "probe_lights_eevee_before"  # on the scene: the settings the offer replaced

# Pages one sun needs, by the scene's shadow resolution scale (64 suns, Blender 4.5.15 and 5.2.3 alike:
# 6,807 / 749 / 445 pages at 320x240); a scale between two rows costs what the row above it does.
PAGES_PER_SUN = ((1.0, 107), (0.5, 12), (0.25, 7))
PAGES_PER_MB = 4  # measured: the 512 MB pool holds 2,048 pages, 1024 MB 4,096, 16 MB 64
MARGIN = 1.1  # the page count varies a little with the view (6,299 to 6,807 for 64 suns)
MAX_POOL_MB = 1024  # Blender 5.2 offers 2 GB, which failed here ("Could not allocate shadow atlas": nothing rendered)


def _eevee_next(scene):
    return bpy.app.version >= (4, 2, 0) and scene.render.engine in ("BLENDER_EEVEE_NEXT", "BLENDER_EEVEE")


def _pages(suns, scale):
    per_sun = next((pages for at, pages in reversed(PAGES_PER_SUN) if at >= scale - 1e-6), PAGES_PER_SUN[0][1])
    return int(suns * per_sun * MARGIN)


def _pools(scene):
    """The pool sizes this Blender offers, in MB, smallest first."""
    items = scene.eevee.bl_rna.properties["shadow_pool_size"].enum_items
    return sorted(int(item.identifier) for item in items)


def _wanted(scene, suns):
    """{setting: value}: the smallest pool (no smaller than the scene's, at most 1 GB) that holds the suns' pages at
    the scene's shadow resolution, else at half or a quarter of it; {} when the pool already holds them."""
    eevee = scene.eevee
    scale = eevee.shadow_resolution_scale
    if _pages(suns, scale) <= int(eevee.shadow_pool_size) * PAGES_PER_MB:
        return {}
    pool = int(eevee.shadow_pool_size)
    pools = [mb for mb in _pools(scene) if pool <= mb <= max(pool, MAX_POOL_MB)]  # never smaller than the user's
    for try_scale in [scale] + [s for s, _ in PAGES_PER_SUN if s < scale - 1e-6]:
        fits = [mb for mb in pools if mb * PAGES_PER_MB >= _pages(suns, try_scale)]
        if fits:
            wanted = {"shadow_pool_size": str(fits[0])} if fits[0] != pool else {}
            if try_scale != scale:
                wanted["shadow_resolution_scale"] = try_scale
            return wanted
    return {"shadow_pool_size": str(pools[-1]), "shadow_resolution_scale": PAGES_PER_SUN[-1][0]}


def advice(scene, suns):
    """One line on what the shadow pool lacks for the baked suns, or '' when it holds them (or the engine is not
    EEVEE Next)."""
    if not _eevee_next(scene) or suns < 2 or not _wanted(scene, suns):
        return ""
    eevee = scene.eevee
    return ("EEVEE: %d suns need about %s shadow pages and the pool (%s MB) holds %s: EEVEE drops shadows at random "
            "(measured: the lit objects up to 3.3 %% brighter from one render to the next)"
            % (suns, format(_pages(suns, eevee.shadow_resolution_scale), ","), eevee.shadow_pool_size,
               format(int(eevee.shadow_pool_size) * PAGES_PER_MB, ",")))


def apply(scene, suns):
    """Sets the pool (and resolution) the suns need, remembering what it replaced (once). Returns {name: value}."""
    if not _eevee_next(scene):
        return {}
    wanted = _wanted(scene, suns)
    set_remembering(scene, BEFORE_KEY, scene.eevee, wanted)
    return wanted


def restore(scene):
    """Puts back what apply() replaced. Returns the names restored."""
    return put_back(scene, BEFORE_KEY, scene.eevee,
                    lambda name, value: str(value) if name == "shadow_pool_size" else float(value))


def describe(wanted):
    """'shadow pool 1024 MB, shadow resolution 0.5' for a dict apply() returned."""
    names = {"shadow_pool_size": "shadow pool %s MB", "shadow_resolution_scale": "shadow resolution %g"}
    return ", ".join(names[name] % value for name, value in sorted(wanted.items()))
