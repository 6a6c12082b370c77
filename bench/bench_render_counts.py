"""Render cost of many lights, per Blender version: the sphere-over-plane scene of the render test lit by
N = 4..256 baked suns at equal samples, against the world-lit render: render time and difference (8x8 block means
of the lit pixels, harness/render_scene.py). Cycles 3.4 picks lamps nearly uniformly (no light tree), so
there more lamps add noise; 4.x and 5.x pick them through a light tree. Run it in each Blender the tests cover:

    tests/blender/run.sh blender bench/bench_render_counts.py build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBE] [SAMPLES]
    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_render_counts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared

With --engine eevee (Blender 4.2+, under Xvfb: run.sh --gl) the suns are baked and rendered in EEVEE Next as the
add-on leaves a default bake there (the shadow pool fitted, the bounce it offers: blender_caps.eevee_bounce) at
EEVEE's default 64 samples, and held to the same truth, Cycles lit by the world with 4 bounces; the render seconds
are EEVEE's against EEVEE's own world-lit render with the same ray tracing (on this machine Mesa's llvmpipe: a
CPU, not a GPU). Each count's HDR-FLIP mean is kept beside its block difference.

With PROBELIGHTS_BENCH_WRITE=addon/probe_lights/render_cost.json it also puts this version's and probe's figures
into that file (written whole: a temporary file renamed over it), the data the add-on's render-cost advice and
its default count read.
"""
import datetime
import json
import os
import re
import subprocess
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, probe, samples = harness.bench_args()
ENGINE = harness.bench_option("--engine", "cycles")
EEVEE_SAMPLES = 64  # EEVEE's default render samples
if ENGINE not in ("cycles", "eevee") or (ENGINE == "eevee" and bpy.app.version < (4, 2, 0)):
    raise SystemExit("--engine is cycles or eevee (EEVEE Next: Blender 4.2 and newer), not %r here" % ENGINE)

harness.install_addon(zip_path)
harness.empty_scene()
harness.env_world(bpy.data.images.load(probe))
render_scene.sphere_over_plane(128, 96, samples)
scene = bpy.context.scene


def timed_render():
    t = time.perf_counter()
    pixels = render_scene.render()
    return pixels, time.perf_counter() - t


reference, seconds_world = timed_render()
print("RENDER Blender %s, %s, %s, %d spp, 128x96" % (bpy.app.version_string, os.path.basename(probe), ENGINE,
                                                     samples))
print("RENDER world-lit (Cycles): %.2f s" % seconds_world)
scene.cycles.seed = 2
again, _ = timed_render()
print("RENDER noise floor (world vs world, other seed): %.2f %%" % (
    100 * render_scene.block_difference(reference, again)[0]))
scene.cycles.seed = 1
if ENGINE == "eevee":
    volumes, caps = harness.addon_module("probe_volumes"), harness.addon_module("blender_caps")
    scene.render.engine = harness.eevee_engine()
    scene.eevee.taa_render_samples = EEVEE_SAMPLES
    bounce = caps.eevee_bounce(bpy.app.version)
    scene.eevee.use_raytracing = "ray tracing" in bounce  # the world's render with it too: the lamps' cost alone
    own, seconds_world = timed_render()
    print("RENDER world-lit (EEVEE's own, %s): %.2f s, difference %.2f %%" % (
        "ray tracing" if scene.eevee.use_raytracing else "no ray tracing", seconds_world,
        100 * render_scene.block_difference(reference, own)[0]))
suns = {}
for n in (4, 8, 16, 32, 64, 128, 256):
    bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n)
    if ENGINE == "eevee" and "volume" in bounce:
        for volume in volumes.volume_probes(scene):
            volumes.remove_fitted(volume)
        assert bpy.ops.probe_lights.bake_light_probes() == {"FINISHED"}
    pixels, seconds = timed_render()
    difference = 100 * render_scene.block_difference(reference, pixels)[0]
    suns[str(n)] = {"seconds": round(seconds, 2), "difference": round(difference, 2)}
    flip = render_scene.flip(reference, pixels)
    if flip is not None:
        suns[str(n)]["flip"] = round(flip, 4)
    print("RENDER %3d suns: %.2f s, difference %.2f %%, HDR-FLIP %s" % (n, seconds, difference, flip), flush=True)

target = os.environ.get("PROBELIGHTS_BENCH_WRITE")
if target:
    with open(target, encoding="utf-8") as f:
        data = json.load(f)
    commit = subprocess.run(["git", "-C", HERE, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    name = re.sub(r"_\d+k$", "", os.path.splitext(os.path.basename(probe))[0])
    version = "%d.%d.%d" % bpy.app.version
    how = "%d samples" % samples if ENGINE == "cycles" else "EEVEE %d samples, %s, truth Cycles %d samples" % (
        EEVEE_SAMPLES, bounce, samples)
    data.setdefault("versions" if ENGINE == "cycles" else "eevee_versions", {}).setdefault(version, {})[name] = {
        "world_seconds": round(seconds_world, 2), "suns": suns,
        "measured": "%s, build %s, %s" % (datetime.date.today(), commit, how)}
    partial = target + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(json.dumps(data, indent=1) + "\n")
    os.replace(partial, target)
    print("RENDER wrote Blender %s, %s into %s" % (version, name, target))
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
