"""What more lights cost in a render, per render engine and Blender version, as measured (no bpy): the default count
a bake makes, the advice it gives, and the render time the Tradeoff shows per count.

bench/bench_render_counts.py renders the sphere-over-plane scene lit by the world and by N suns baked with the
add-on's defaults and writes render_cost.json: render seconds and the difference to the world-lit render, on three
probes: Poly Haven's noon_grass (one strong sun), Blender's own forest.exr (dappled light, shipped with every
Blender) and Poly Haven's st_peters_square_night (lamp posts: the hardest shadows of the probes here). Cycles 3.4
picks lamps nearly uniformly, so past its sweet spot the renders get noisier; 4.5 and 5.x pick them through a light
tree (no extra noise) but every sun adds render time. In EEVEE Next (--engine eevee) the suns are rendered in EEVEE
and held to Cycles' world-lit render with its bounces; every sun adds a shadow (pages in the pool, render time). A
count is past the sweet spot when no probe renders measurably closer with more (the bench's resolution: WITHIN),
and that sweet spot is the count a bake makes by default ("Count by: Engine").
"""
import functools
import json
import os

try:
    from .blender_caps import eevee_next, has_light_tree
except ImportError:  # imported on its own, as the bpy-free tests do
    from blender_caps import eevee_next, has_light_tree


ENGINES = {"cycles": "Cycles", "eevee": "EEVEE"}  # render_cost.json's engines: Cycles, EEVEE Next (4.2+)
_KEYS = {"cycles": "versions", "eevee": "eevee_versions"}
UNMEASURED_COUNT = 64  # the count where no measurement stands for the engine (Workbench, EEVEE Legacy, point lamps)


def _load(path=os.path.join(os.path.dirname(os.path.abspath(__file__)), "render_cost.json")):
    """render_cost.json, as bench/bench_render_counts.py writes it, as {engine: {(major, minor, patch): {probe:
    (world-lit render seconds, {suns: (render seconds, difference %, HDR-FLIP mean or None)})}}}."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    return {engine: {tuple(int(p) for p in version.split(".")): {
        probe: (m["world_seconds"], {int(n): (s["seconds"], s["difference"], s.get("flip"))
                                     for n, s in m["suns"].items()})
        for probe, m in probes.items()} for version, probes in data.get(key, {}).items()}
        for engine, key in _KEYS.items()}


MEASURED = _load()
WITHIN = 0.1  # percentage points: differences closer than this to the least one are as good (noise floor ~0.2)
FLIP_WITHIN = 0.002  # HDR-FLIP means closer than this to the least one are as good


def engine_of(render_engine, blender_version):
    """render_cost.json's engine for a scene's render engine in that Blender ("cycles", "eevee" for EEVEE Next), or
    None where nothing stands for it (Workbench, EEVEE Legacy: its soft shadows and light limit are another
    engine's)."""
    if render_engine == "CYCLES":
        return "cycles"
    return "eevee" if eevee_next(render_engine, blender_version) and MEASURED["eevee"] else None


def nearest_version(measured, blender_version):
    """Of the versions `measured` holds (keys (major, minor, patch)), the one that stands for `blender_version`: the
    nearest by major.minor (the older on a tie), so 4.2 takes 4.5's light-tree measurements, not 3.4's."""
    def minor(v):
        return 100 * v[0] + v[1]
    b = tuple(blender_version)
    return min(measured, key=lambda v: (abs(minor(v) - minor(b)), v > b))


def measured_version(blender_version, engine="cycles"):
    """The version of render_cost.json that stands for `blender_version` in `engine` (nearest_version)."""
    return nearest_version(MEASURED[engine], blender_version)


def _probe_sweet_spot(suns):
    """The fewest of `suns` ({count: (seconds, difference, flip)}) as close as the closest: within WITHIN of the
    least difference and, where HDR-FLIP was measured, within FLIP_WITHIN of the least FLIP. Where no count is
    closest by both (EEVEE 5.3 on noon_grass: 8 suns by blocks, 4 and 16 by FLIP), the count whose farther measure
    is the nearest to its best, in those units."""
    least = min(d for _, d, _ in suns.values())
    flips = [f for _, _, f in suns.values() if f is not None]

    def excess(n):
        _, d, f = suns[n]
        return max((d - least) / WITHIN, (f - min(flips)) / FLIP_WITHIN if f is not None else 0.0)
    close = [n for n in suns if excess(n) <= 1.0 + 1e-9]
    return min(close) if close else min(sorted(suns), key=excess)


def _deciding_probe(blender_version, engine="cycles"):
    """(probe, its measurements) of the probe whose own sweet spot is the largest in that version."""
    probes = MEASURED[engine][measured_version(blender_version, engine)]
    name = max(sorted(probes), key=lambda p: _probe_sweet_spot(probes[p][1]))
    return name, probes[name]


def sweet_spot(blender_version, engine="cycles"):
    """The fewest suns whose render is as close to the world's as any count measured in that version and engine,
    on every measured probe."""
    return _sweet_spot(tuple(blender_version), engine)


@functools.lru_cache(maxsize=None)  # the panel asks on every redraw; the measurements do not change
def _sweet_spot(blender_version, engine):
    _, (_, suns) = _deciding_probe(blender_version, engine)
    return _probe_sweet_spot(suns)


def default_count(render_engine, blender_version, measured_kind=True):
    """(count, why) a bake makes by default ("Count by: Engine"): the engine's sweet spot in the measurements
    standing for that Blender; UNMEASURED_COUNT where none stands for the engine or the light kind
    (`measured_kind`: the kind's renders were measured, light_kinds.LightKind.render_cost). `why` says so in a few
    words for the panel."""
    engine = engine_of(render_engine, blender_version)
    if engine is None or not measured_kind:
        return UNMEASURED_COUNT, ("renders in this engine not measured" if measured_kind
                                  else "this light type's renders not measured")
    version = measured_version(blender_version, engine)
    return sweet_spot(blender_version, engine), "more render no closer in %s %d.%d" % (ENGINES[engine], *version[:2])


def count_note(count, blender_version, engine="cycles"):
    """One line of advice when `count` suns is past the version's sweet spot in `engine`, else ''. The figures
    behind it are in MEASURED and docs/results/renders.md, not in the panel."""
    best = sweet_spot(blender_version, engine)
    if count <= best:
        return ""
    version = measured_version(blender_version, engine)
    # Without a light tree (Cycles 3.x) more lamps make a render noisier; with one (4.0+), and in EEVEE, slower.
    cost = "slower" if engine == "eevee" or has_light_tree(version) else "noisier"
    return "More than %d suns: %s renders, no closer in %s %d.%d" % (best, cost, ENGINES[engine], *version[:2])


def render_factor(count, blender_version, engine="cycles"):
    """The measured render time of `count` suns as a multiple of the world-lit render's in `engine` (EEVEE's: its
    own world-lit render), the mean over the measured probes (straight between measured counts), in the
    measurements standing for `blender_version`; None outside the measured counts. The Tradeoff shows it beside
    each count's error."""
    factors = []
    for world_seconds, suns in MEASURED[engine][measured_version(blender_version, engine)].values():
        counts = sorted(suns)
        if not counts[0] <= count <= counts[-1]:
            return None
        lo = max(n for n in counts if n <= count)
        hi = min(n for n in counts if n >= count)
        seconds = suns[lo][0] if hi == lo else suns[lo][0] + (suns[hi][0] - suns[lo][0]) * (count - lo) / (hi - lo)
        factors.append(seconds / world_seconds)
    return sum(factors) / len(factors)
