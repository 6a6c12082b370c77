"""EEVEE with the add-on's lamps and its fitted light probe volume at several resolutions, against Cycles lit by
the world with 4 bounces (issue 52: "its resolution chosen from their size"). Per probe: the add-on's default bake
(64 suns) in EEVEE, the volume the add-on fits (probe_volumes.fit_volume: the rendered objects' bounds, 5 % more),
baked with the lamps (Bake light probes with the lamps) at each resolution; HDR-FLIP, 8x8-block and per-pixel
differences (render_scene.render_errors) and the bake's seconds. About 8 minutes a probe on 2 cores, under Xvfb:

  tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_volume_resolution.py \\
      build/probe_lights-0.1.0-linux_x64.zip ../shared sphere noon_grass_1k,StageEnvLatLong 4x4x4,8x8x8,8x8x2,12x12x4

Written up in docs/decisions.md (the fitted volume's resolution).
"""
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
SCENE = rest[0] if rest else "sphere"
PROBES = harness.named_probes(harness.bench_probes(shared), rest[1] if len(rest) > 1 else "noon_grass_1k")
RESOLUTIONS = [tuple(int(c) for c in r.split("x")) for r in (rest[2] if len(rest) > 2 else "4x4x4,8x8x8").split(",")]
W, H, CYCLES_SAMPLES, EEVEE_SAMPLES, SUNS = 160, 120, 256, 16, 64  # as bench_eevee_rivals.py
harness.install_addon(zip_path)
volumes = harness.addon_module("probe_volumes")
eevee = harness.eevee_engine()
print("Blender %s, %s, %dx%d; Cycles %d samples, 4 bounces; EEVEE %d samples; %d suns" % (
    bpy.app.version_string, SCENE, W, H, CYCLES_SAMPLES, EEVEE_SAMPLES, SUNS))
print("| probe | cells | HDR-FLIP | block | pixel | bake s |\n|---|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.eevee_rivals_scene(probe, SCENE, W, H, CYCLES_SAMPLES, EEVEE_SAMPLES)
    truth = render_scene.render()
    scene.render.engine = eevee
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SUNS) == {"FINISHED"}
    volume = volumes.fit_volume(scene)
    for cells in RESOLUTIONS:
        volume.data.resolution_x, volume.data.resolution_y, volume.data.resolution_z = cells
        start = time.perf_counter()
        assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
        seconds = time.perf_counter() - start
        block, _, pixel, flip = render_scene.render_errors(truth, render_scene.render())
        print("| %s | %s | %.4f | %.2f %% | %.2f %% | %.0f |" % (
            os.path.basename(probe), "x".join(map(str, cells)), flip, 100 * block, 100 * pixel, seconds), flush=True)
