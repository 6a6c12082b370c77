"""Does the add-on's estimate predict the render? The evaluator's shadow scene (render_scene.ground_under_sphere: a
plane under a unit sphere, direct light, the 16 x 16 ground points as pixels) rendered by Cycles lit by the world
and by N baked suns (the default bake: fitted angles, the 512-wide estimate), on six probes that every machine has
(the bundled one and five of Blender's studio lights) and N = 8, 16, 64. The rendered relative RMS difference,
less the renders' own noise (two seeds of each), must agree with the estimated shadow error within a third of the
rendered figure or 0.3 points, whichever is larger (issue 9). The estimate models each Blender's sun (4.0+: a
uniform cone; 3.x: a disc of radius tan(angle / 2), conversion.sun_profile).

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python tests/blender/test_estimate.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared
"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

# Cycles 3.x picks among the lamps uniformly (no light tree): 64 suns are ~2x noisier there at equal samples.
SAMPLES = int(os.environ.get("PROBELIGHTS_ESTIMATE_SAMPLES", "4096" if bpy.app.version >= (4, 0, 0) else "16384"))
STUDIOLIGHTS = tuple(os.environ.get("PROBELIGHTS_ESTIMATE_PROBES", "city.exr forest.exr interior.exr sunrise.exr studio.exr").split())

# The add-on's default bake (Refit on); PROBELIGHTS_ESTIMATE_REFIT=0 checks the bake without it.
REFIT = os.environ.get("PROBELIGHTS_ESTIMATE_REFIT", "1") == "1"
a = harness.args()
harness.install_addon(a.zip)


def noisy_pair():
    """Renders with seeds 1 and 2; returns the first and the noise of one render relative to it (sqrt of half
    the two renders' mean squared difference, relative like the error)."""
    scene = bpy.context.scene
    scene.cycles.seed = 1
    first = render_scene.render()
    scene.cycles.seed = 2
    second = render_scene.render()
    scene.cycles.seed = 1
    return first, render_scene.relative_rms(first, second) / math.sqrt(2)


def estimate_against_render(probe, counts=(8, 16, 64), world_from_pixels=False):
    """world_from_pixels: compare the lamps' render with the probe's truth computed from its pixels
    (render_scene.ground_truth) instead of with the world's render."""
    harness.empty_scene()
    image = bpy.data.images.load(probe)
    world = harness.env_world(image)
    # The truth is the probe's pixels: the world shows them unfiltered (Blender's default, Linear, blurs each by
    # a pixel; measured on sunrise at 64 suns, 0.65 % rendered against 0.59 % Closest, the estimate 0.33 %).
    world.node_tree.nodes["Environment Texture"].interpolation = "Closest"
    render_scene.ground_under_sphere(SAMPLES)
    world, world_noise = noisy_pair()
    if world_from_pixels:
        truth = render_scene.ground_truth(image)
        print("  %s: the world's render is %.2f %% from the probe's truth (noise %.2f %%); the lamps are compared "
              "with the truth" % (os.path.basename(probe), 100 * render_scene.relative_rms(truth, world),
                                  100 * world_noise))
        world, world_noise = truth, 0.0
    settings = bpy.context.scene.probe_lights
    worst = 0.0
    for n in counts:
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n, shadows="FIT", refit=REFIT)
        scene = bpy.context.scene
        estimate = settings.last_shadow_error / 100
        for samples in sorted({SAMPLES, max(SAMPLES, 16384)}):
            scene.cycles.samples = samples
            lit, lamp_noise = noisy_pair()
            rendered = render_scene.relative_rms(world, lit)
            # E[rendered^2] = difference^2 + both renders' noise^2 (relative to the world's rms).
            denoised = math.sqrt(max(0.0, rendered ** 2 - world_noise ** 2 - lamp_noise ** 2))
            bound = max(denoised / 3, 0.003)
            # Where the two disagree and the lamps' noise outweighs the difference, the difference is not measured
            # (sunrise, 64 suns at 4096 samples in 4.5: rendered 0.65 %, lamps' noise 0.63 %, less noise
            # 0.11 +- 0.1): once more at 16384 samples (3.4's own count), which halve the noise. Only then: 64
            # suns at 16384 samples take minutes in 4.5.
            if abs(estimate - denoised) <= bound or lamp_noise <= max(denoised, 0.003):
                break
        scene.cycles.samples = SAMPLES
        print("  %s, %2d suns: estimate %.2f %%, rendered %.2f %% (noise: world %.2f %%, lamps %.2f %% at %d samples; "
              "less noise %.2f %%)" % (os.path.basename(probe), n, 100 * estimate, 100 * rendered,
                                       100 * world_noise, 100 * lamp_noise, samples, 100 * denoised), flush=True)
        assert abs(estimate - denoised) <= bound, (probe, n, estimate, denoised)
        worst = max(worst, abs(estimate - denoised) / bound)
    return worst


def test_the_estimated_shadow_error_is_the_rendered_one():
    probes = [harness.BUNDLED_PROBE] + [os.path.join(harness.studiolights(a), f) for f in STUDIOLIGHTS]
    print("  Blender %s, Cycles %d samples, 16 x 16 ground points" % (bpy.app.version_string, SAMPLES))
    worst = max(estimate_against_render(p) for p in probes)
    print("  worst |estimate - rendered| / bound: %.2f" % worst)


def test_negative_samples_are_light_the_lamps_and_the_estimate_keep():
    """pmndrs_esplanade_dwab (../shared): DWAB's ringing leaves 5054 negative samples beside its sun, -6.5 % of its
    light, which Cycles renders. When the lights and the estimate dropped them, 16 suns rendered 10.2 % from the
    world-lit render against an estimate of 2.5 %; keeping them, the two agree (4.5.15: 2.59 % / 2.70 %).
    Cycles 3.x renders a world's negative pixels only in part (3.4.1: its world render 1.75 % from the probe's
    truth at the ground points, 4.5's 0.58 %, its noise; bench/render_vs_model.py), so there the lamps' render is
    compared with the truth computed from the probe's pixels (3.4.1, 16 refit suns: 0.87 %, estimated 0.80 %)."""
    probe = harness.shared_probe(a, "pmndrs_esplanade_dwab.exr")
    if probe:
        estimate_against_render(probe, counts=(16,), world_from_pixels=bpy.app.version < (4, 0, 0))


harness.run([test_the_estimated_shadow_error_is_the_rendered_one,
             test_negative_samples_are_light_the_lamps_and_the_estimate_keep])
