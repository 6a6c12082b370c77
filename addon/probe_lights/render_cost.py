"""What more lights cost in a Cycles render, per Blender version, as measured (no bpy): the advice a bake gives.

scripts/bench_render_counts.py renders the sphere-over-plane scene (128 x 96, 256 samples, Poly Haven noon_grass)
lit by the world and by N baked suns: render seconds and the difference to the world-lit render (8 x 8 block means,
noise floor 0.17-0.22 %). Cycles 3.4 picks lamps nearly uniformly, so past 64 suns the renders get noisier; 4.5 and
5.x pick them through a light tree (no extra noise) but every sun adds render time, and past 64 they get no closer.
"""

# Blender version -> world-lit render seconds, and {suns: (render seconds, difference %)}.
MEASURED = {
    (3, 4, 1): (2.39, {4: (1.30, 7.09), 8: (1.36, 3.40), 16: (1.44, 2.03), 32: (1.59, 1.45), 64: (1.90, 0.95),
                       128: (2.52, 3.43), 256: (3.71, 3.65)}),
    (4, 5, 15): (2.94, {4: (2.35, 6.65), 8: (2.96, 2.90), 16: (4.35, 1.50), 32: (6.93, 0.70), 64: (11.76, 0.26),
                        128: (21.82, 0.21), 256: (41.56, 0.22)}),
    (5, 0, 1): (2.72, {4: (2.14, 6.73), 8: (2.75, 2.95), 16: (4.17, 1.57), 32: (6.72, 0.66), 64: (11.54, 0.32),
                       128: (21.62, 0.26), 256: (41.14, 0.27)}),
    (5, 2, 3): (2.94, {4: (2.13, 6.65), 8: (2.54, 2.90), 16: (3.65, 1.50), 32: (5.54, 0.70), 64: (8.90, 0.26),
                       128: (16.01, 0.21), 256: (29.96, 0.22)}),
}
WITHIN = 0.1  # percentage points: differences closer than this to the least one are as good (noise floor ~0.2)


def measured_version(blender_version):
    """The measured version that stands for `blender_version`: the nearest by major.minor (the older on a tie), so
    4.2 takes 4.5's light-tree measurements, not 3.4's."""
    def minor(v):
        return 100 * v[0] + v[1]
    b = tuple(blender_version)
    return min(MEASURED, key=lambda v: (abs(minor(v) - minor(b)), v > b))


def sweet_spot(blender_version):
    """The fewest suns whose render is as close to the world's as any count measured in that version."""
    _, suns = MEASURED[measured_version(blender_version)]
    least = min(d for _, d in suns.values())
    return min(n for n, (_, d) in suns.items() if d <= least + WITHIN)


def count_note(count, blender_version):
    """One line of advice when `count` suns is past the version's sweet spot, else ''."""
    best = sweet_spot(blender_version)
    if count <= best:
        return ""
    version = measured_version(blender_version)
    world, suns = MEASURED[version]
    n = min((k for k in suns if k >= count), default=max(suns))
    (t_best, d_best), (t_n, d_n) = suns[best], suns[n]
    return ("more suns than %d bring this Cycles no closer to the world: measured in Blender %s (noon_grass, 256 "
            "samples), %d suns render in %.1fx the world's time and differ by %.2f %%, %d suns %.1fx and %.2f %%" % (
                best, ".".join(str(v) for v in version), best, t_best / world, d_best, n, t_n / world, d_n))
