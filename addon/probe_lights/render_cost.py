"""What more lights cost in a Cycles render, per Blender version, as measured (no bpy): the advice a bake gives, and
the render time the Tradeoff shows per count.

bench/bench_render_counts.py renders the sphere-over-plane scene lit by the world and by N suns baked with the
add-on's defaults and writes render_cost.json: render seconds and the difference to the world-lit render, on three
probes: Poly Haven's noon_grass (one strong sun), Blender's own forest.exr (dappled light, shipped with every
Blender) and Poly Haven's st_peters_square_night (lamp posts: the hardest shadows of the probes here). Cycles 3.4 picks lamps nearly uniformly, so past its sweet spot the renders
get noisier; 4.5 and 5.x pick them through a light tree (no extra noise) but every sun adds render time. A count is
past the sweet spot when no probe renders measurably closer with more (the bench's resolution: WITHIN).
"""
import json
import os

try:
    from .blender_caps import has_light_tree
except ImportError:  # imported on its own, as the bpy-free tests do
    from blender_caps import has_light_tree


def _load(path=os.path.join(os.path.dirname(os.path.abspath(__file__)), "render_cost.json")):
    """render_cost.json, as bench/bench_render_counts.py writes it, as
    {(major, minor, patch): {probe: (world-lit render seconds, {suns: (render seconds, difference %)})}}."""
    with open(path, encoding="utf-8") as f:
        versions = json.load(f)["versions"]
    return {tuple(int(p) for p in version.split(".")): {
        probe: (m["world_seconds"], {int(n): (s["seconds"], s["difference"]) for n, s in m["suns"].items()})
        for probe, m in probes.items()} for version, probes in versions.items()}


MEASURED = _load()
WITHIN = 0.1  # percentage points: differences closer than this to the least one are as good (noise floor ~0.2)


def nearest_version(measured, blender_version):
    """Of the versions `measured` holds (keys (major, minor, patch)), the one that stands for `blender_version`: the
    nearest by major.minor (the older on a tie), so 4.2 takes 4.5's light-tree measurements, not 3.4's."""
    def minor(v):
        return 100 * v[0] + v[1]
    b = tuple(blender_version)
    return min(measured, key=lambda v: (abs(minor(v) - minor(b)), v > b))


def measured_version(blender_version):
    """The version of render_cost.json that stands for `blender_version` (nearest_version)."""
    return nearest_version(MEASURED, blender_version)


def _probe_sweet_spot(suns):
    least = min(d for _, d in suns.values())
    return min(n for n, (_, d) in suns.items() if d <= least + WITHIN)


def _deciding_probe(blender_version):
    """(probe, its measurements) of the probe whose own sweet spot is the largest in that version."""
    probes = MEASURED[measured_version(blender_version)]
    name = max(sorted(probes), key=lambda p: _probe_sweet_spot(probes[p][1]))
    return name, probes[name]


def sweet_spot(blender_version):
    """The fewest suns whose render is as close to the world's as any count measured in that version, on every
    measured probe."""
    _, (_, suns) = _deciding_probe(blender_version)
    return _probe_sweet_spot(suns)


def count_note(count, blender_version):
    """One line of advice when `count` suns is past the version's sweet spot, else ''. The figures behind it are
    in MEASURED and docs/results/renders.md, not in the panel."""
    best = sweet_spot(blender_version)
    if count <= best:
        return ""
    version = measured_version(blender_version)
    # Without a light tree (3.x) more lamps make a render noisier; with one (4.0+) slower.
    cost = "slower" if has_light_tree(version) else "noisier"
    return "More than %d suns: %s renders, no closer in Cycles %d.%d" % (best, cost, version[0], version[1])


def render_factor(count, blender_version):
    """The measured Cycles render time of `count` suns as a multiple of the world-lit render's, the mean over the
    measured probes (straight between measured counts), in the measurements standing for `blender_version`; None
    outside the measured counts. The Tradeoff shows it beside each count's error."""
    factors = []
    for world_seconds, suns in MEASURED[measured_version(blender_version)].values():
        counts = sorted(suns)
        if not counts[0] <= count <= counts[-1]:
            return None
        lo = max(n for n in counts if n <= count)
        hi = min(n for n in counts if n >= count)
        seconds = suns[lo][0] if hi == lo else suns[lo][0] + (suns[hi][0] - suns[lo][0]) * (count - lo) / (hi - lo)
        factors.append(seconds / world_seconds)
    return sum(factors) / len(factors)
