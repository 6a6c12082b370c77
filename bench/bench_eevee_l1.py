"""docs/results/eevee.md: how much of EEVEE's error from a world is its spherical harmonics, no render needed (issue 30).

EEVEE (4.2 and newer) lights a diffuse surface from the world through the world's first two bands of spherical
harmonics only (Blender's eevee_lightprobe_eval_lib.glsl: spherical_harmonics_evaluate_lambert on a
SphericalHarmonicL1). For a surface facing up (the render benches' plane, +Z) the cosine lobe's bands 0 and 1 are
A0 = pi and A1 = 2 pi / 3 (Ramamoorthi & Hanrahan 2001), so EEVEE's irradiance is

    E1 = sum over pixels of L (1/4 + z/2) dOmega,   against the exact   E = sum of L max(0, z) dOmega

(z the pixel's direction's height, dOmega its exact solid angle). For each probe this prints E1 / E of the probe
and of the residual world the add-on leaves with 16 lamps of the bright sources (Lamps take: The bright sources),
to set beside bench_eevee_parts.py's measured "residual light, EEVEE / Cycles".

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_l1.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared
"""
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402

SOURCE_LAMPS = 16
LUM = np.array([0.2126, 0.7152, 0.0722])


def up_irradiance(image):
    """(E1, E): the first two bands' and the exact irradiance on a surface facing +Z from a lat-long image."""
    w, h = image.size
    rgba = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(rgba)
    lum = rgba.reshape(h, w, 4)[::-1, :, :3].astype(np.float64) @ LUM  # rows from the top
    top = np.pi / 2 - np.pi * np.arange(h) / h  # each row's upper and lower elevation
    bottom = top - np.pi / h
    d_omega = (2 * np.pi / w) * (np.sin(top) - np.sin(bottom))  # a pixel's exact solid angle, row by row
    z = np.sin((top + bottom) / 2)
    row = lum.sum(axis=1) * d_omega
    return float((row * (0.25 + 0.5 * z)).sum()), float((row * np.maximum(z, 0.0)).sum())


zip_path, shared, _ = harness.bench_argv()
harness.install_addon(zip_path)
print("| probe | world: E1 / E on +Z | residual world (%d lamps of the sources): E1 / E |" % SOURCE_LAMPS)
print("|---|---|---|")
for probe in harness.bench_probes(shared):
    harness.empty_scene()
    image = bpy.data.images.load(probe)
    harness.env_world(image)
    world = up_irradiance(image)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SOURCE_LAMPS, lamps_take="SOURCES") == {"FINISHED"}
    residual = next(i for i in bpy.data.images if i.name.startswith("Probe Lights residual"))
    rest = up_irradiance(residual)
    print("| %s | %.3f | %.3f |" % (os.path.basename(probe), world[0] / world[1], rest[0] / rest[1]), flush=True)
print("Blender %s" % bpy.app.version_string)
sys.stdout.flush()
os._exit(0)
