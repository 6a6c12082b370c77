"""docs/results/eevee_rivals.md: what an EEVEE user has against the add-on's lamps, each held to the truth, Cycles
lit by the world with 4 bounces (issue 52). Per probe, in one scene (the render test's sphere over a plane, or a
still life of a metal sphere, a glossy and a rough dielectric and a thin rod on a floor: harness/render_scene.py):
  EEVEE's own         EEVEE lit by the world, its sun extraction at the default threshold (10), and at the
                      threshold of a sweep that came closest by HDR-FLIP;
  EEVEE's own + probe the same (best threshold) with a light probe volume fitted to the scene, baked with the
                      world captured: EEVEE's world shadowed and bounced as well as EEVEE can;
  EEVEE's own + ray tracing   the same (best threshold) with EEVEE's ray tracing instead of the probe;
  EEVEE's own + sphere + ray tracing   and with a light probe sphere around the scene as the add-on fits it;
  ours                EEVEE with the add-on's default bake (64 suns, baked in EEVEE);
  ours + probe        the same with that volume probe baked by the add-on (Bake light probes with the lamps);
  ours + ray tracing  ours with EEVEE's ray tracing on (screen-traced, Fast GI at its defaults) and no probe;
  ours + sphere + ray tracing  and a light probe sphere around the scene (the panel's Use EEVEE ray tracing and
                      reflections: what the add-on offers up to Blender 5.1, blender_caps.eevee_bounce);
  ours + probe + ray tracing   the volume probe and ray tracing, no sphere;
  ours + probe + sphere + ray tracing   all three (what the add-on offers from Blender 5.2);
  sources + residual + probe   the lamps of the bright sources and the residual world (Lamps take: The bright
                      sources), the probe baked: EEVEE's world masked by the probe's visibility (issue 52, item 3).
Each is given as HDR-FLIP's mean (flip-evaluator), the per-pixel and the 8x8-block luminance difference
(render_scene.render_errors), with the render's seconds; the first row of each probe is the truth's own noise
(Cycles against itself with another seed). With a picture directory, one row per probe: the truth, EEVEE's own
(best threshold, + ray tracing), ours + probe, ours + sphere + ray tracing, sources + residual + probe, and
their FLIP maps.

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_rivals.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [sphere|still-life] [PROBES] [PICTURE_DIR]

PROBES: a comma list of probe names without extension, or "all" (the bundled probe, ../shared/hdri's, Blender's
studio lights: 15).
"""
import os
import sys
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
SCENE = rest[0] if rest else "sphere"
PROBES = harness.named_probes(harness.bench_probes(shared), rest[1] if len(rest) > 1 else "all")
PICTURES = rest[2] if len(rest) > 2 else ""
W, H = 160, 120
CYCLES_SAMPLES, EEVEE_SAMPLES, SUNS = 256, 16, 64
THRESHOLDS = (3.0, 10.0, 30.0)  # EEVEE's sun extraction: Blender's default is 10
harness.install_addon(zip_path)
volumes = harness.addon_module("probe_volumes")


def build(probe):
    return render_scene.eevee_rivals_scene(probe, SCENE, W, H, CYCLES_SAMPLES, EEVEE_SAMPLES)


def fitted_volume(scene, capture_world):
    """The light probe volume the add-on fits around the scene (probe_volumes.fit_volume: the objects' bounds, 5 %
    more, EEVEE's default 4 cells a side), with the world captured or not."""
    volume = volumes.fit_volume(scene)
    volume.data.capture_world = capture_world
    return volume


def timed_render():
    start = time.perf_counter()
    picture = render_scene.render()
    return picture, time.perf_counter() - start


SUMMARY = {}  # probe -> {render: "FLIP / block"}


def row(name, truth, picture, seconds, note=""):
    block, _, pixel, flip = render_scene.render_errors(truth, picture)
    SUMMARY.setdefault(os.path.basename(PROBE), {})[name] = "%.4f / %.2f %%%s" % (
        flip, 100 * block, note if name == "EEVEE's own, best threshold" else "")
    print("| %s | %s%s | %.4f | %.2f %% | %.2f %% | %.1f |" % (name, os.path.basename(PROBE), note, flip, 100 * pixel,
                                                             100 * block, seconds), flush=True)
    return flip


eevee = harness.eevee_engine()
print("Blender %s, %s, %dx%d; Cycles %d samples, 4 bounces; EEVEE %d samples; %d suns" % (
    bpy.app.version_string, SCENE, W, H, CYCLES_SAMPLES, EEVEE_SAMPLES, SUNS))
print("| render | probe | HDR-FLIP | pixel | block | seconds |")
print("|---|---|---|---|---|---|")
for PROBE in PROBES:
    scene = build(PROBE)
    truth, seconds = timed_render()
    scene.cycles.seed += 1
    row("Cycles, another seed", truth, timed_render()[0], seconds)
    scene.cycles.seed -= 1
    scene.render.engine = eevee
    best = None
    for threshold in THRESHOLDS:
        scene.world.sun_threshold = threshold
        own, seconds = timed_render()
        if threshold == 10.0:
            row("EEVEE's own, threshold 10", truth, own, seconds)
        flip = render_scene.flip(truth, own)
        if best is None or flip < best[0]:
            best = (flip, threshold, own, seconds)
    row("EEVEE's own, best threshold", truth, best[2], best[3], " (%g)" % best[1])
    scene.world.sun_threshold = best[1]
    scene.eevee.use_raytracing = True  # as below for ours: EEVEE's ray tracing and Fast GI, no probe
    own_traced, seconds = timed_render()
    row("EEVEE's own + ray tracing", truth, own_traced, seconds)
    sphere = volumes.fit_sphere(scene)  # as a user would add one (EEVEE captures it at render time: no bake)
    row("EEVEE's own + sphere + ray tracing", truth, *timed_render())
    volumes.remove_fitted(sphere)
    scene.eevee.use_raytracing = False
    volume = fitted_volume(scene, capture_world=True)
    start = time.perf_counter()
    bpy.ops.object.lightprobe_cache_bake(subset="ALL")
    bake_s = time.perf_counter() - start
    own_probe, seconds = timed_render()
    row("EEVEE's own + probe", truth, own_probe, seconds, " (bake %.0f s)" % bake_s)
    volumes.remove_fitted(volume)

    scene = build(PROBE)
    scene.render.engine = eevee
    start = time.perf_counter()
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SUNS) == {"FINISHED"}
    ours, seconds = timed_render()
    row("ours", truth, ours, seconds)
    # EEVEE's own ray tracing (4.2+: Render > Raytracing, screen-traced, its Fast GI for diffuse bounces) in place
    # of a volume probe: the bounce from what is on screen, no bake.
    scene.eevee.use_raytracing = True
    ours_traced, seconds = timed_render()
    row("ours + ray tracing", truth, ours_traced, seconds)
    assert bpy.ops.probe_lights.eevee_ray_tracing() == {"FINISHED"}  # adds the sphere where something reflects
    sphere = (volumes.sphere_probes(scene) or [volumes.fit_sphere(scene)])[0]  # and here where nothing does
    ours_reflected, seconds = timed_render()
    row("ours + sphere + ray tracing", truth, ours_reflected, seconds)
    volumes.remove_fitted(sphere)
    scene.eevee.use_raytracing = False
    fitted_volume(scene, capture_world=False)
    start = time.perf_counter()
    assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    bake_s = time.perf_counter() - start
    ours_probe, seconds = timed_render()
    row("ours + probe", truth, ours_probe, seconds, " (bake %.0f s)" % bake_s)
    scene.eevee.use_raytracing = True  # both: farther than either up to 5.0, closest from 5.2 (blender_caps)
    row("ours + probe + ray tracing", truth, *timed_render())
    volumes.fit_sphere(scene)
    row("ours + probe + sphere + ray tracing", truth, *timed_render())
    scene.eevee.use_raytracing = False

    scene = build(PROBE)
    scene.render.engine = eevee
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=SUNS, lamps_take="SOURCES") == {"FINISHED"}
    fitted_volume(scene, capture_world=False)
    start = time.perf_counter()
    assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    bake_s = time.perf_counter() - start
    residual, seconds = timed_render()
    row("sources + residual + probe", truth, residual, seconds, " (%d lamps, bake %.0f s)" % (
        len([o for o in scene.objects if o.type == "LIGHT"]), bake_s))
    if PICTURES:
        os.makedirs(PICTURES, exist_ok=True)
        name = os.path.splitext(os.path.basename(PROBE))[0]
        render_scene.save_png(np.concatenate([truth, own_traced, ours_probe, ours_reflected, residual], axis=1),
                              os.path.join(PICTURES, "%s_%s.png" % (SCENE, name)))
        maps = np.concatenate([render_scene.flip(truth, p, picture=True)
                               for p in (own_traced, ours_probe, ours_reflected, residual)], axis=1)
        render_scene.save_png(maps, os.path.join(PICTURES, "%s_%s_flip.png" % (SCENE, name)), display=True)
print("\nHDR-FLIP / block difference:\n")
names = ["Cycles, another seed", "EEVEE's own, threshold 10", "EEVEE's own, best threshold", "EEVEE's own + probe",
         "EEVEE's own + ray tracing", "EEVEE's own + sphere + ray tracing", "ours", "ours + probe",
         "ours + ray tracing", "ours + sphere + ray tracing", "ours + probe + ray tracing",
         "ours + probe + sphere + ray tracing",
         "sources + residual + probe"]
print("| probe | " + " | ".join(names) + " |")
print("|---" * (len(names) + 1) + "|")
for probe, cells in SUMMARY.items():
    print("| %s | %s |" % (probe, " | ".join(cells.get(name, "-") for name in names)))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
