"""From baked lights to Blender light parameters: units and orientations, no bpy.

Units (measured with Cycles 3.4 renders of a white diffuse plane, tests/blender/test_units.py):
  - a sun lamp of strength S gives irradiance S (W/m^2) on a surface facing it, so a light's rgb (the sum of
    L dOmega over its region: the irradiance it gives a facing surface) is exactly sun colour x strength;
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


def sun_parameters(direction, rgb, angular_radius, soft_shadows=True):
    colour, strength = colour_and_scale(rgb)
    angle = min(2.0 * float(angular_radius), math.pi) if soft_shadows else 0.0
    return {"rotation": rotation_to_direction(direction), "color": colour, "energy": strength, "angle": angle}


def point_parameters(direction, rgb, distance):
    colour, irradiance = colour_and_scale(rgb)
    d = np.asarray(direction, dtype=float)
    return {"location": tuple(float(c) for c in distance * d / np.linalg.norm(d)), "color": colour,
            "energy": 4.0 * math.pi * distance * distance * irradiance}


def srgb_to_linear(a):
    """The sRGB transfer function's inverse (for 8-bit environment images stored in sRGB)."""
    a = np.asarray(a, dtype=np.float32)
    return np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4).astype(np.float32)
