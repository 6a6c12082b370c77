"""docs/results/eevee.md's table of issue 54: EEVEE with the baked lamps and a baked light probe volume, against Cycles with
4 bounces, on the bundled probe and ../shared/hdri's. The scene is the render test's diffuse sphere over a plane
(harness/render_scene.py) with a volume probe around both (8 x 8 x 4 m); 64 suns with the add-on's defaults, baked
in EEVEE; the probe baked by the add-on (probe_volumes.py). Each column is render_scene.block_difference's (8x8
blocks of lit object pixels, mean |render - Cycles| / Cycles of their luminance):
  lamps alone        EEVEE with the lamps, no probe baked (EEVEE bounces no light without one);
  lamps + probe      the same after the add-on's bake of the probe (the suns merged for the bake's shadows);
  world's part       the probe baked with the world captured (EEVEE's default) against without: what the probe
                     took of the world the lamps already carry (it should be nothing);
  16 suns: alone / + probe   the same two with 16 suns, which the bake holds without merging;
  merged 16 as 4     16 suns, the probe baked with all 16 against with them merged into 4: what merging costs.

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_probe.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [EEVEE_SAMPLES]

(16 EEVEE samples by default; Cycles takes 256)
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
samples = int(rest[0]) if rest else 16
harness.install_addon(zip_path)
PROBES = harness.bench_probes(shared, studio_lights=False)
volumes = harness.addon_module("probe_volumes")


def scene_for(probe, suns):
    harness.empty_scene()
    harness.addon_module("eevee_settings").restore(bpy.context.scene)
    harness.env_world(bpy.data.images.load(probe))
    render_scene.sphere_over_plane(160, 120, 256)
    scene = bpy.context.scene
    scene.render.engine = harness.eevee_engine()
    scene.render.film_transparent = True
    scene.eevee.taa_render_samples = samples
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=suns) == {"FINISHED"}
    bpy.ops.object.lightprobe_add(type="VOLUME", location=(0, 0, 1))
    bpy.context.object.scale = (4, 4, 2)
    return scene, bpy.context.object


def lit_difference(a, b, lit):
    ya, yb = render_scene.block_luminance(a)[lit], render_scene.block_luminance(b)[lit]
    return 100.0 * float(abs(yb - ya).mean() / ya.mean())


print("| probe | bake saw | lamps alone | lamps + probe | world's part | 16 suns: alone / + probe | merged 16 as 4 "
      "| probe bake s |")
print("|---|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene, volume = scene_for(probe, 64)
    cycles, alone, with_probe = render_scene.probe_bake_renders(scene)
    volume.data.capture_world = False
    start = time.perf_counter()
    assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    bake_s = time.perf_counter() - start
    no_world = render_scene.render()
    lit = render_scene.lit_blocks(cycles)
    seen = min(64, volumes.suns_the_bake_holds(scene))

    scene, volume = scene_for(probe, 16)
    cycles16, alone16, all16 = render_scene.probe_bake_renders(scene)
    pages = volumes.BAKE_PAGES_PER_SUN
    largest = max(mb for mb in harness.addon_module("eevee_settings").pool_sizes(scene) if mb <= 1024)
    extra = 1 if harness.addon_module("world_mix").has_residual(scene.world) else 0
    # pages a sun such that the largest pool holds 4 suns' shadows in the bake
    volumes.BAKE_PAGES_PER_SUN = largest * 4 / (1.1 * (4.5 + extra))
    assert volumes.suns_the_bake_holds(scene) == 4
    assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    as4 = render_scene.render()
    volumes.BAKE_PAGES_PER_SUN = pages
    print("| %s | %d of 64 | %.2f %% | %.2f %% | %.3f %% | %.2f / %.2f %% | %.2f %% | %.1f |" % (
        os.path.basename(probe), seen, 100 * render_scene.block_difference(cycles, alone)[0],
        100 * render_scene.block_difference(cycles, with_probe)[0], lit_difference(no_world, with_probe, lit),
        100 * render_scene.block_difference(cycles16, alone16)[0],
        100 * render_scene.block_difference(cycles16, all16)[0],
        lit_difference(all16, as4, render_scene.lit_blocks(all16)), bake_s), flush=True)
