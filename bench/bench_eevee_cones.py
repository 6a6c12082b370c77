"""docs/results/eevee.md's table of the suns' cones: EEVEE and Cycles with 16 lamps (Lamps take: All of the light) whose
fitted cones may cross the horizon (sun_cones "free", the add-on's bake in Cycles) or not ("above-horizon", its bake
in EEVEE: blender_caps.sun_cones), each against Cycles lit by the world. Same scene and measure as
bench_eevee_residual.py (the diffuse sphere over a plane, 160x120, direct light only, EEVEE 32 samples, Cycles 256).

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_cones.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [NAME,NAME,...]
"""
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
harness.install_addon(zip_path)
PROBES = harness.named_probes(harness.bench_probes(shared), rest[0] if rest else "")
W, H, SAMPLES, LAMPS = 160, 120, 32, 16
bake_module = harness.addon_module("bake")
eevee = harness.eevee_engine()

print("| probe | EEVEE, cones free | EEVEE, cones above the horizon | Cycles, free | Cycles, above the horizon |")
print("|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.eevee_comparison_scene(probe, "CYCLES", W, H, SAMPLES)
    ref = render_scene.render()
    lit = render_scene.lit_blocks(ref)
    r = render_scene.block_luminance(ref)[lit]

    def cell(picture):
        d = (render_scene.block_luminance(picture)[lit] - r) / r
        return "%.2f %% (%+.2f)" % (100 * np.abs(d).mean(), 100 * d.mean())

    cells = {}
    for cones in ("free", "above-horizon"):
        bake_module.sun_cones = lambda *_, c=cones: c
        scene.render.engine = "CYCLES"
        assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=LAMPS, lamps_take="ALL") == {"FINISHED"}
        cells["Cycles", cones] = cell(render_scene.render())
        scene.render.engine = eevee
        cells["EEVEE", cones] = cell(render_scene.render())
    print("| %s | %s | %s | %s | %s |" % (os.path.basename(probe), cells["EEVEE", "free"],
                                         cells["EEVEE", "above-horizon"], cells["Cycles", "free"],
                                         cells["Cycles", "above-horizon"]), flush=True)
print("Blender %s, %dx%d, %d lamps, EEVEE %d samples, Cycles %d (direct light)" % (
    bpy.app.version_string, W, H, LAMPS, SAMPLES, 8 * SAMPLES))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
