"""docs/results/eevee.md's table of issue 30: what comes closest to Cycles lit by the world, in EEVEE and in Cycles, on
every probe the tests have (the bundled one, ../shared/hdri's, Blender's own studio lights: 15). The scene is the
render test's diffuse sphere over a plane (harness/render_scene.py); the reference is Cycles lit by the world with
direct light only (EEVEE bounces none without baked light probes). Against it:
  (a) EEVEE lit by the world alone, with its sun extraction at its default;
  (b) EEVEE with the add-on's lamps taking all of the light (Lamps take: All of the light, the default);
  (c) EEVEE with 16 lamps of the bright sources and the residual world (Lamps take: The bright sources; the
      first table, of 2026-12-02, had 4: 16 sharp suns overflowed EEVEE's shadow pool before the add-on counted a
      sun's pages by its elevation);
and, in Cycles, (c) against the world alone, with the render time of each. The difference is
render_scene.block_difference's: 8x8 blocks of lit pixels, mean |render - reference| / reference of their luminance.

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_residual.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [LAMPS] [EEVEE_SAMPLES] [SOURCE_LAMPS]

(16 lamps in (b), 32 EEVEE samples, 16 lamps in (c) by default; the Cycles renders take 8 times as many samples)
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
lamps = int(rest[0]) if rest else 16
samples = int(rest[1]) if len(rest) > 1 else 32
SOURCE_LAMPS = int(rest[2]) if len(rest) > 2 else 16
harness.install_addon(zip_path)
PROBES = harness.bench_probes(shared)
W, H = 160, 120


def scene_for(probe, engine):
    return render_scene.eevee_comparison_scene(probe, engine, W, H, samples)


def difference(reference, other):
    return 100.0 * render_scene.block_difference(reference, other)[0]


def timed_render():
    start = time.perf_counter()
    picture = render_scene.render()
    return picture, time.perf_counter() - start


eevee = harness.eevee_engine()
print("| probe | lamps take (c) | EEVEE (a) world, sun extraction | EEVEE (b) all lamps | EEVEE (c) sources + "
      "residual | Cycles (c) against the world | Cycles world / (c) seconds |")
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene = scene_for(probe, "CYCLES")
    reference, world_s = timed_render()
    scene.render.engine = eevee
    a = render_scene.render()
    scene = scene_for(probe, eevee)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=lamps, lamps_take="ALL") == {"FINISHED"}
    b = render_scene.render()
    scene = scene_for(probe, eevee)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SOURCE_LAMPS, lamps_take="SOURCES") == {"FINISHED"}
    share = scene.probe_lights.last_energy
    c = render_scene.render()
    scene.render.engine = "CYCLES"
    c_cycles, c_s = timed_render()
    print("| %s | %.0f %% | %.2f %% | %.2f %% | %.2f %% | %.2f %% | %.1f / %.1f |" % (
        os.path.basename(probe), share, difference(reference, a), difference(reference, b), difference(reference, c),
        difference(reference, c_cycles), world_s, c_s), flush=True)
print("Blender %s, %dx%d, %d lamps in (b), %d in (c), EEVEE %d samples, Cycles %d (direct light)" % (
    bpy.app.version_string, W, H, lamps, SOURCE_LAMPS, samples, 8 * samples))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
