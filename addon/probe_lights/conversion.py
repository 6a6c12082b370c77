"""From baked lights to Blender light parameters: units and orientations, no bpy.

Units per Blender version, from Cycles renders of a white diffuse patch (tests/blender/test_render.py derives them
from the renders and checks these models in each version; the figures are in docs/renders.md, "Light units"):
  - a sun lamp of strength S and angle 0 gives irradiance S (W/m^2) on a surface facing it, so a light's rgb (the
    sum of L dOmega over its region: the irradiance it gives a facing surface) is sun colour x strength;
  - a sun of angle 2a: Blender 3.4's Cycles samples a disc of radius tan(a) at unit distance with pdf
    invarea/cos^3, so a facing surface receives S x 2 cos(a) / (1 + cos(a)); the strength is divided by that
    factor so the irradiance stays the region's. Blender 4.5 and 5.x normalize the cone: a facing surface receives
    S at every angle. Versions 3.5 to 4.4 are not measured; they are taken to behave like 4.5 from 4.0 on.
  - a point lamp of power P (W) at distance D gives irradiance P / (4 pi D^2), so P = 4 pi D^2 x E.
"""

import math

import numpy as np


def rotation_to_direction(d):
    """A rotation matrix (columns = the object's x, y, z axes in the world) whose local +Z points along d.

    A sun lamp shines along its local -Z, so pointing +Z at the light's direction makes it shine from there."""
    z = np.asarray(d, dtype=float)
    z = z / np.linalg.norm(z)
    up = np.array([0.0, 0.0, 1.0]) if abs(z[2]) < 0.999 else np.array([0.0, 1.0, 0.0])
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.column_stack([x, y, z])


def colour_and_scale(rgb):
    """Split an rgb irradiance into a colour with a largest channel of 1 and the scale that multiplies it."""
    rgb = np.maximum(np.asarray(rgb, dtype=float), 0.0)
    peak = float(rgb.max())
    if peak <= 0:
        return (0.0, 0.0, 0.0), 0.0
    return tuple(float(c) for c in rgb / peak), peak


MAX_SUN_ANGLE = math.radians(180.0)
MAX_DISC_SUN_ANGLE = math.radians(178.0)  # a 3.x sun is a disc of radius tan(angle / 2): kept finite (the core too)


def sun_cones(engine, blender_version):
    """How wide the suns' cones may be for a bake in that engine (the core's sun_cones, cone.h). EEVEE (4.2+)
    darkens a whole sun by the part of its cone below the floor's horizon, so a bake in EEVEE keeps every cone
    above it: 16 lamps then render within 0.2-3.5 % of Cycles' world on the 15 probes in 4.5.15, against 0.3-7.4 %
    with free cones; in Cycles the free cones are closer (0.2-1.6 % against 0.2-2.0 %; docs/eevee.md,
    bench/bench_eevee_cones.py), so a bake in any other engine leaves them free."""
    eevee_next = tuple(blender_version) >= (4, 2, 0) and engine in ("BLENDER_EEVEE_NEXT", "BLENDER_EEVEE")
    return "above-horizon" if eevee_next else "free"


def preset(engine, blender_version):
    """The core's recipe for the add-on's bake in that engine (request.cpp: presets): its suns' cones as
    sun_cones says, the rest the same."""
    return "blender-eevee" if sun_cones(engine, blender_version) == "above-horizon" else "blender"


NORMALIZED_SUN_SINCE = (4, 0, 0)  # measured: 3.4 disc; 4.5, 5.0, 5.2 normalized (3.5 to 4.4 not measured)


def sun_profile(blender_version):
    """How that Blender's Cycles spreads a sun's light over its angle, in the core's words (cone.h): a uniform cone
    from 4.0 on; before, a disc of radius tan(angle / 2) at unit distance (radiance 1 / cos^3 of the angle from the
    axis, which the renders of tests/blender/test_estimate.py confirm: the estimate and 3.4's render agree)."""
    return "cone" if tuple(blender_version) >= NORMALIZED_SUN_SINCE else "disc"


def sun_normal_irradiance(angle, blender_version):
    """Irradiance a Cycles sun of strength 1 and the given angle (radians, full) gives a surface facing it, in the
    Blender of that version (bpy.app.version)."""
    if tuple(blender_version) >= NORMALIZED_SUN_SINCE:
        return 1.0
    c = math.cos(0.5 * angle)
    return 2.0 * c / (1.0 + c) if c > 0 else 0.0


def sun_parameters(direction, rgb, angle, blender_version):
    """Rotation, colour, strength and angle of a sun lamp that gives a facing surface `rgb` in that Blender.

    `angle`: the light's full cone angle from the core (radians; its `angle` column: fitted to the probe's shadows
    when they are evaluated, 0 for hard shadows), at most 180 degrees."""
    colour, irradiance = colour_and_scale(rgb)
    widest = MAX_SUN_ANGLE if sun_profile(blender_version) == "cone" else MAX_DISC_SUN_ANGLE
    angle = min(max(float(angle), 0.0), widest)
    factor = sun_normal_irradiance(angle, blender_version)
    return {"rotation": rotation_to_direction(direction), "color": colour,
            "energy": irradiance / factor if factor > 0 else 0.0, "angle": angle}


def point_parameters(direction, rgb, distance):
    colour, irradiance = colour_and_scale(rgb)
    d = np.asarray(direction, dtype=float)
    return {"location": tuple(float(c) for c in distance * d / np.linalg.norm(d)), "color": colour,
            "energy": 4.0 * math.pi * distance * distance * irradiance}


def srgb_to_linear(a):
    """The sRGB transfer function's inverse (for 8-bit environment images stored in sRGB)."""
    a = np.asarray(a, dtype=np.float32)
    return np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4).astype(np.float32)
