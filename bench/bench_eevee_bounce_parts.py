"""docs/results/renders.md's "What keeps EEVEE from Cycles" (issue 52): where the add-on's lamps in EEVEE, with its
ray tracing, part from Cycles' whole-world render with bounces. On the sphere over a plane (bench_eevee_rivals.py's
scene: Cycles 256 samples, 4 bounces; EEVEE 16 samples), 64 suns baked in EEVEE, per probe:
  lamps        Cycles lit by the lamps (4 bounces) against Cycles lit by the world: the lamps' own difference;
  bounce       Cycles lit by the lamps without bounces against with: how much of the picture the bounce is;
  direct       EEVEE lit by the lamps (no ray tracing: no bounce) against Cycles without bounces;
  traced       EEVEE with its ray tracing against Cycles lit by the lamps with 4 bounces (and against the world);
  bounce light EEVEE's bounce (traced - direct) over Cycles' (4 bounces - none), summed over the picture.
Each difference is HDR-FLIP's mean / the 8x8-block difference (render_scene.render_errors).

    tests/blender/run.sh --gl ~/.cache/probelights/bpy-4.5.15/bin/python bench/bench_eevee_bounce_parts.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared [PROBES]

PROBES: a comma list of probe names without extension, or "all" (default: noon_grass_1k,KernerEnvLatLong,interior).
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

zip_path, shared, rest = harness.bench_argv()
PROBES = harness.named_probes(harness.bench_probes(shared), rest[0] if rest else
                              "noon_grass_1k,KernerEnvLatLong,interior")
harness.install_addon(zip_path)
eevee = harness.eevee_engine()


def diff(a, b):
    block, _, _, flip = render_scene.render_errors(a, b)
    return "%.4f / %.2f %%" % (flip, 100 * block)


print("Blender %s, the sphere over a plane, 160 x 120, 64 suns" % bpy.app.version_string)
print("| probe | lamps (Cycles) | bounce's share (Cycles) | direct (EEVEE) | traced (EEVEE) | traced against the world |"
      " bounce light EEVEE / Cycles |")
print("|---|---|---|---|---|---|---|")
for probe in PROBES:
    scene = render_scene.eevee_rivals_scene(probe, "sphere", 160, 120, 256, 16)
    world = render_scene.render()
    scene.render.engine = eevee
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=64) == {"FINISHED"}
    scene.render.engine = "CYCLES"
    lamps = render_scene.render()
    scene.cycles.max_bounces = 0
    lamps_direct = render_scene.render()
    scene.cycles.max_bounces = 4
    scene.render.engine = eevee
    scene.eevee.use_raytracing = False
    direct = render_scene.render()
    scene.eevee.use_raytracing = True
    traced = render_scene.render()
    ratio = float((traced - direct)[..., :3].sum()) / max(1e-9, float((lamps - lamps_direct)[..., :3].sum()))
    print("| %s | %s | %s | %s | %s | %s | %.3f |" % (
        os.path.basename(probe), diff(world, lamps), diff(lamps, lamps_direct), diff(lamps_direct, direct),
        diff(lamps, traced), diff(world, traced), ratio), flush=True)
sys.stdout.flush()
os._exit(0)  # bpy 4.5's teardown can hang after EEVEE renders (harness.run says more)
