"""What more lights cost in a Cycles render, per Blender version, as measured (no bpy): the advice a bake gives.

scripts/bench_render_counts.py renders the sphere-over-plane scene (128 x 96, 256 samples) lit by the world and by
N suns baked with the add-on's defaults: render seconds and the difference to the world-lit render (8 x 8 block
means, noise floor 0.17-0.32 %), on three probes: Poly Haven's noon_grass (one sun holds 64 % of the light), Blender's
own forest.exr (dappled light, shipped with every Blender) and Poly Haven's st_peters_square_night (lamp posts: the
hardest shadows of issue 9's fifteen). Cycles 3.4 picks lamps nearly uniformly, so past its sweet spot the renders
get noisier; 4.5 and 5.x pick them through a light tree (no extra noise) but every sun adds render time. A count is
past the sweet spot when no probe renders measurably closer with more (the bench's resolution: WITHIN).
"""
# Blender version -> {probe: (world-lit render seconds, {suns: (render seconds, difference %)})}, measured with the
# build of 2026-12-01 (Auto cuts, Refit, fitted angles; render seconds on a loaded 2-core machine, +-30 %).
MEASURED = {
    (3, 4, 1): {
        "noon_grass": (3.80, {4: (1.78, 1.31), 8: (2.17, 0.95), 16: (2.00, 0.74), 32: (2.35, 0.95),
            64: (2.79, 0.94), 128: (3.37, 1.16), 256: (4.38, 1.41)}),
        "forest": (4.73, {4: (2.28, 1.54), 8: (1.84, 0.77), 16: (1.95, 0.62), 32: (2.51, 0.33),
            64: (3.29, 0.34), 128: (4.49, 0.43), 256: (6.15, 0.53)}),
        "st_peters_square_night": (3.21, {4: (2.00, 2.38), 8: (1.85, 2.01), 16: (2.26, 1.11), 32: (2.45, 0.53),
            64: (2.61, 0.53), 128: (3.06, 0.76), 256: (4.37, 0.75)}),
    },
    (4, 5, 15): {
        "noon_grass": (4.35, {4: (3.14, 0.90), 8: (4.04, 0.81), 16: (6.11, 0.26), 32: (10.57, 0.26),
            64: (17.61, 0.25), 128: (26.86, 0.28), 256: (43.53, 0.30)}),
        "forest": (4.50, {4: (3.95, 1.06), 8: (4.97, 0.79), 16: (7.19, 0.53), 32: (10.76, 0.25),
            64: (19.08, 0.25), 128: (33.64, 0.22), 256: (57.40, 0.22)}),
        "st_peters_square_night": (4.53, {4: (2.77, 2.33), 8: (3.98, 1.81), 16: (5.10, 1.07), 32: (7.06, 0.31),
            64: (13.28, 0.31), 128: (23.90, 0.25), 256: (48.93, 0.27)}),
    },
    (5, 0, 1): {
        "noon_grass": (6.98, {4: (6.57, 0.90), 8: (5.89, 0.83), 16: (8.67, 0.29), 32: (13.44, 0.32),
            64: (17.23, 0.40), 128: (30.02, 0.31), 256: (45.71, 0.37)}),
        "forest": (4.55, {4: (3.90, 1.00), 8: (5.04, 0.86), 16: (6.33, 0.54), 32: (10.58, 0.31),
            64: (18.31, 0.31), 128: (33.43, 0.24), 256: (52.00, 0.31)}),
        "st_peters_square_night": (3.57, {4: (2.77, 2.31), 8: (3.56, 1.80), 16: (4.51, 1.11), 32: (7.00, 0.37),
            64: (12.88, 0.36), 128: (21.50, 0.33), 256: (47.11, 0.33)}),
    },
    (5, 2, 3): {
        "noon_grass": (4.81, {4: (3.82, 0.90), 8: (4.13, 0.81), 16: (5.76, 0.26), 32: (9.44, 0.26),
            64: (14.17, 0.25), 128: (19.13, 0.26), 256: (36.20, 0.24)}),
        "forest": (4.23, {4: (2.80, 1.06), 8: (3.66, 0.79), 16: (4.72, 0.53), 32: (6.50, 0.25),
            64: (11.99, 0.25), 128: (24.81, 0.22), 256: (41.04, 0.20)}),
        "st_peters_square_night": (3.89, {4: (2.74, 2.33), 8: (3.37, 1.81), 16: (4.37, 1.08), 32: (6.38, 0.31),
            64: (11.49, 0.32), 128: (19.04, 0.24), 256: (40.61, 0.29)}),
    },
    (5, 3, 0): {
        "noon_grass": (4.50, {4: (5.15, 0.90), 8: (5.82, 0.81), 16: (5.22, 0.26), 32: (7.37, 0.26),
            64: (10.96, 0.25), 128: (18.49, 0.29), 256: (26.48, 0.30)}),
        "forest": (4.86, {4: (3.67, 1.06), 8: (3.65, 0.79), 16: (5.38, 0.53), 32: (7.69, 0.25),
            64: (11.39, 0.25), 128: (22.98, 0.22), 256: (36.32, 0.20)}),
        "st_peters_square_night": (4.78, {4: (3.13, 2.33), 8: (3.36, 1.81), 16: (3.97, 1.08), 32: (5.79, 0.31),
            64: (11.21, 0.32), 128: (15.98, 0.24), 256: (32.25, 0.29)}),
    },
}
WITHIN = 0.1  # percentage points: differences closer than this to the least one are as good (noise floor ~0.2)


def measured_version(blender_version):
    """The measured version that stands for `blender_version`: the nearest by major.minor (the older on a tie), so
    4.2 takes 4.5's light-tree measurements, not 3.4's."""
    def minor(v):
        return 100 * v[0] + v[1]
    b = tuple(blender_version)
    return min(MEASURED, key=lambda v: (abs(minor(v) - minor(b)), v > b))


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
    in MEASURED and docs/renders.md, not in the panel."""
    best = sweet_spot(blender_version)
    if count <= best:
        return ""
    version = measured_version(blender_version)
    # Without a light tree (3.x) more lamps make a render noisier; with one (4.0+) slower.
    cost = "noisier" if version < (4, 0, 0) else "slower"
    return "More than %d suns: %s renders, no closer in Cycles %d.%d" % (best, cost, version[0], version[1])
