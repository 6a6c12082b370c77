"""docs/results/eevee.md's split of (c)'s difference from Cycles into its two parts (issue 30): the add-on's lamps of the
bright sources and the residual world. Same scene and reference as bench_eevee_residual.py (the diffuse sphere over
a plane, Cycles lit by the world, direct light only); for each probe it renders
  ref  Cycles lit by the world,          a   EEVEE lit by the world, its sun extraction at its default,
  c    EEVEE with 16 lamps of the sources and the residual world (Lamps take: The bright sources),
  cc   the same scene in Cycles,         ew, cw  the residual world alone (lamps hidden) in EEVEE and Cycles,
and over render_scene.block_difference's lit 8x8 blocks, relative to ref's luminance there:
  lamps part     ((c - ew) - (cc - cw)) / ref: what EEVEE makes of the lamps, against Cycles;
  residual part  (ew - cw) / ref: what EEVEE makes of the residual world, against Cycles;
(c) - ref = lamps part + residual part + (cc - ref), and cc - ref is the Cycles renders' own difference. Each is
printed as the mean of |.| (the tables' measure) and, in brackets, the signed mean; the last column is the residual
world's light in EEVEE over Cycles' (its sum over the blocks).

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_parts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [NAME,NAME,...]

(NAME: probe file names without their extension, e.g. pmndrs_esplanade_dwab,forest; all 15 by default)
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
W, H, SAMPLES, SOURCE_LAMPS = 160, 120, 32, 16


def cell(d):
    return "%.2f %% (%+.2f)" % (100 * np.abs(d).mean(), 100 * d.mean())


eevee = harness.eevee_engine()
print("| probe | EEVEE (a) world, sun extraction | EEVEE (c) sources + residual | lamps part | residual part | "
      "Cycles (c) against the world | residual light, EEVEE / Cycles |")
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.eevee_comparison_scene(probe, "CYCLES", W, H, SAMPLES)
    ref = render_scene.render()
    scene.render.engine = eevee
    a = render_scene.render()
    lit = render_scene.lit_blocks(ref)  # the blocks render_scene.block_difference compares
    scene = render_scene.eevee_comparison_scene(probe, eevee, W, H, SAMPLES)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SOURCE_LAMPS, lamps_take="SOURCES") == {"FINISHED"}
    c = render_scene.render()
    scene.render.engine = "CYCLES"
    cc = render_scene.render()
    lamps = [o for o in scene.objects if o.type == "LIGHT"]
    for o in lamps:
        o.hide_render = True
    cw = render_scene.render()
    scene.render.engine = eevee
    ew = render_scene.render()
    y = {k: render_scene.block_luminance(v)[lit] for k, v in {"a": a, "c": c, "cc": cc, "cw": cw, "ew": ew}.items()}
    r = render_scene.block_luminance(ref)[lit]
    print("| %s | %s | %s | %s | %s | %s | %.3f |" % (
        os.path.basename(probe), cell((y["a"] - r) / r), cell((y["c"] - r) / r),
        cell(((y["c"] - y["ew"]) - (y["cc"] - y["cw"])) / r), cell((y["ew"] - y["cw"]) / r), cell((y["cc"] - r) / r),
        y["ew"].sum() / y["cw"].sum()), flush=True)
print("Blender %s, %dx%d, %d lamps of the sources, EEVEE %d samples, Cycles %d (direct light)" % (
    bpy.app.version_string, W, H, SOURCE_LAMPS, SAMPLES, 8 * SAMPLES))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
