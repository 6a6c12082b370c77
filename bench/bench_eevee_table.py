"""docs/results/eevee.md's table: EEVEE with the baked lamps against EEVEE with its own world lighting (and its sun
extraction), each against Cycles lit by the world, on the probes the tests have (the bundled noon_grass and
Blender's own studio lights). The scene is the render test's sphere over a plane (harness/render_scene.py).
Three cases of the lamps: baked in EEVEE (the pool fitted at the bake), baked under Cycles then rendered in EEVEE (fitted before
the render), and baked under Cycles with the fit undone (what users got before issue 31: a full shadow pool). The
difference is render_scene.block_difference's: 8x8 blocks of lit pixels, mean |EEVEE - Cycles| / Cycles of their
luminance (blocks average away the Cycles reference's noise), the reference with direct light only (EEVEE bounces
none without baked light probes).

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_table.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [EEVEE_SAMPLES]

(the Cycles reference takes 8 times as many samples)
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
zip_path = argv[argv.index("--zip") + 1]
rest = [a for i, a in enumerate(argv) if not a.startswith("--") and not argv[i - 1].startswith("--")]
samples = int(rest[0]) if rest else 64
harness.install_addon(zip_path)
shadows = harness.addon_module("eevee_settings")
studio = harness.blender_studiolights()
PROBES = [harness.BUNDLED_PROBE] + [os.path.join(studio, n) for n in ("forest.exr", "sunset.exr")]
W, H = 160, 120


def scene_for(probe, engine):
    return render_scene.eevee_comparison_scene(probe, engine, W, H, samples)


def difference(reference, other):
    return 100.0 * render_scene.block_difference(reference, other)[0]


eevee = harness.eevee_engine()
print("| probe | EEVEE, world (sun extraction) | EEVEE, 64 lamps baked in EEVEE | baked under Cycles, fitted at "
      "render | baked under Cycles, pool full |")
print("|---|---|---|---|---|")
for probe in PROBES:
    scene = scene_for(probe, "CYCLES")
    reference = render_scene.render()  # Cycles, world-lit
    scene.render.engine = eevee
    world = render_scene.render()  # EEVEE's own world lighting, sun extraction at its default threshold
    scene = scene_for(probe, eevee)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64) == {"FINISHED"}
    baked_eevee = render_scene.render()
    scene = scene_for(probe, "CYCLES")
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64) == {"FINISHED"}
    scene.render.engine = eevee
    switched = render_scene.render()  # fitted before the render by the add-on
    shadows.unregister()  # the add-on as it was: nothing fits the pool before the render
    shadows.restore(scene)
    full = render_scene.render()
    shadows.register()
    print("| %s | %.2f %% | %.2f %% | %.2f %% | %.2f %% |" % (
        os.path.basename(probe), difference(reference, world), difference(reference, baked_eevee),
        difference(reference, switched), difference(reference, full)), flush=True)
print("Blender %s, %dx%d, EEVEE %d samples, Cycles %d (direct light)" % (bpy.app.version_string, W, H, samples,
                                                                         8 * samples))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
