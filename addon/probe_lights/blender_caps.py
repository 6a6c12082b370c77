"""What a Blender does, answered once: its version (bpy.app.version) and render engine in, an answer out. No bpy
here, so the answers are tested from plain Python (tests/python/test_world_graph.py); the measurements behind them
are in the docs each answer names."""

EEVEE_ENGINES = frozenset({"BLENDER_EEVEE", "BLENDER_EEVEE_NEXT"})  # EEVEE's name before 4.2 and in 4.2-4.x
EEVEE_NEXT_SINCE = (4, 2, 0)  # one shadow pool for every light, ray visibility honoured, light probe volumes
NORMALIZED_SUN_SINCE = (4, 0, 0)  # measured: 3.4 disc; 4.5, 5.0, 5.2 normalized (3.5 to 4.4 not measured)
LIGHT_TREE_SINCE = (4, 0, 0)  # Cycles' light tree: more lamps render slower, not noisier (docs/results/renders.md)
WORLD_NODES_ALWAYS_SINCE = (5, 0, 0)  # World.use_nodes deprecated; Cycles 5.0 renders use_nodes False by its nodes
# How EEVEE Next bounces the lamps' light closest to Cycles (with its 4 bounces; 64 suns on the sphere over a plane,
# KernerEnvLatLong, bench/bench_eevee_rivals.py's renders; docs/results/eevee_rivals.md). Up to 5.0 its ray
# tracing alone (Fast GI): 3.02 % in 4.2.23 and 4.5.15, 3.05 % in 5.0.1, against 3.41-3.44 % with a light probe
# volume baked with the lamps, and both together farther than either (6.9-7.2 %). From 5.2 the volume and ray
# tracing together: 2.05 % in 5.2.3, 2.06 % in 5.3.0, against 3.07-3.08 % with the volume, 5.05-5.09 % with ray
# tracing alone. 5.1 is not measured and takes 5.0's answer (the older on a tie, as render_cost.nearest_version).
PROBE_WITH_RAY_TRACING_SINCE = (5, 2, 0)


def is_eevee(engine):
    """Whether the engine is EEVEE, Legacy or Next."""
    return engine in EEVEE_ENGINES


def has_eevee_next(blender_version):
    """Whether that Blender's EEVEE is EEVEE Next (4.2 and newer): its shadow pool, its light probe volume bake."""
    return tuple(blender_version) >= EEVEE_NEXT_SINCE


def eevee_next(engine, blender_version):
    """Whether a scene in that engine renders in EEVEE Next."""
    return has_eevee_next(blender_version) and is_eevee(engine)


def sun_cones(engine, blender_version):
    """How wide the suns' cones may be for a bake in that engine (the core's sun_cones, cone.h). EEVEE (4.2+)
    darkens a whole sun by the part of its cone below the floor's horizon, so a bake in EEVEE keeps every cone
    above it; in Cycles free cones render closer to the world (docs/results/eevee.md, bench/bench_eevee_cones.py), so a bake
    in any other engine leaves them free."""
    return "above-horizon" if eevee_next(engine, blender_version) else "free"


def preset(engine, blender_version):
    """The core's recipe for the add-on's bake in that engine (request.cpp: presets): its suns' cones as
    sun_cones says, the rest the same."""
    return "blender-eevee" if sun_cones(engine, blender_version) == "above-horizon" else "blender"


def sun_profile(blender_version):
    """How that Blender's Cycles spreads a sun's light over its angle, in the core's words (cone.h): a uniform cone
    from 4.0 on; before, a disc of radius tan(angle / 2) at unit distance (radiance 1 / cos^3 of the angle from the
    axis, which the renders of tests/blender/test_estimate.py confirm: the estimate and 3.4's render agree)."""
    return "cone" if tuple(blender_version) >= NORMALIZED_SUN_SINCE else "disc"


def has_light_tree(blender_version):
    """Whether that Blender's Cycles samples many lamps by its light tree (4.0 on)."""
    return tuple(blender_version) >= LIGHT_TREE_SINCE


def world_always_uses_nodes(blender_version):
    """Whether that Blender renders every world through its node tree, whatever World.use_nodes says (5.0 on)."""
    return tuple(blender_version) >= WORLD_NODES_ALWAYS_SINCE


def eevee_bounce(blender_version):
    """What gives EEVEE Next the lamps' bounce light closest to Cycles in that Blender: "ray tracing" (alone: a
    light probe volume with it is farther) or "volume and ray tracing" (PROBE_WITH_RAY_TRACING_SINCE)."""
    return "volume and ray tracing" if tuple(blender_version) >= PROBE_WITH_RAY_TRACING_SINCE else "ray tracing"
