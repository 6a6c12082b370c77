"""From baked lights to Blender light parameters: units and orientations, no bpy.

Units per Blender version, from Cycles renders of a white diffuse patch (tests/blender/test_render.py derives them
from the renders and checks these models in each version; the figures are in docs/results/renders.md, "Light units"):
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

try:
    from .blender_caps import NORMALIZED_SUN_SINCE, sun_profile
except ImportError:  # imported on its own, as the bpy-free tests do
    from blender_caps import NORMALIZED_SUN_SINCE, sun_profile


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
    return {"rotation": rotation_to_direction(direction), **sun_strength(rgb, angle, blender_version)}


def sun_strength(rgb, angle, blender_version):
    """sun_parameters without the rotation: colour, strength and angle (Bake animation turns its suns' keys by
    the shortest arc instead)."""
    colour, irradiance = colour_and_scale(rgb)
    widest = MAX_SUN_ANGLE if sun_profile(blender_version) == "cone" else MAX_DISC_SUN_ANGLE
    angle = min(max(float(angle), 0.0), widest)
    factor = sun_normal_irradiance(angle, blender_version)
    return {"color": colour, "energy": irradiance / factor if factor > 0 else 0.0, "angle": angle}


def point_parameters(direction, rgb, distance):
    colour, irradiance = colour_and_scale(rgb)
    d = np.asarray(direction, dtype=float)
    return {"location": tuple(float(c) for c in distance * d / np.linalg.norm(d)), "color": colour,
            "energy": 4.0 * math.pi * distance * distance * irradiance}


def srgb_to_linear(a):
    """The sRGB transfer function's inverse (for 8-bit environment images stored in sRGB)."""
    a = np.asarray(a, dtype=np.float32)
    return np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4).astype(np.float32)
