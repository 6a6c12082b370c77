"""Does the add-on's estimate predict the render? The evaluator's shadow scene (render_scene.ground_under_sphere: a
plane under a unit sphere, direct light, the 16 x 16 ground points as pixels) rendered by Cycles lit by N baked
suns (the default bake: fitted angles, the 512-wide estimate), on six probes that every machine has (the bundled
one and five of Blender's studio lights; PROBELIGHTS_ESTIMATE_PROBES narrows them, tests/CMakeLists.txt) and
N = 8, 16, 64, and compared with the probe's truth at those points
(its pixels integrated; Cycles' render of the world is checked to be that truth on the bundled probe). The
rendered relative RMS difference, less the renders' own noise (two seeds of each), must agree with the estimated
shadow error within a third of the rendered figure or 0.3 points, whichever is larger (issue 9). The estimate
models each Blender's sun (4.0+: a uniform cone; 3.x: a disc of radius tan(angle / 2), blender_caps.sun_profile).

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python tests/blender/test_estimate.py \\
        build/probe_lights-0.1.0-linux_x64.zip ../shared
"""
import math
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

# Each count is rendered twice (two seeds) and the mean compared with the truth: at 2 x 2048 samples the mean
# is as noisy as one render at 4096 was when the world's render was the reference: half the samples, and no
# world rendered for each probe. Cycles 3.x (no light tree) needs 2 x 4096 for that noise at 64 suns (0.2-0.6 %;
# at 2 x 2048 up to 1.1 %, 3.4.1). Those are the samples of 64 suns, whose difference is least (the bound is then
# 0.3 points) and noise most; fewer suns differ by more (the bound a third of it) and render less noisily: N suns
# take N / 32 of the samples (at N / 64, 8 suns rendered with noise up to 1.1 %, 5.3.0).
SAMPLES = int(os.environ.get("PROBELIGHTS_ESTIMATE_SAMPLES", "2048" if bpy.app.version >= (4, 0, 0) else "4096"))
STUDIOLIGHTS = tuple(os.environ.get("PROBELIGHTS_ESTIMATE_PROBES", "city.exr forest.exr interior.exr sunrise.exr studio.exr").split())
# Whose world renders are checked against their truth: the bundled probe's, or with "all" every probe's.
WORLD_CHECKED = os.environ.get("PROBELIGHTS_ESTIMATE_WORLD", "")

# The add-on's default bake (Refit on); PROBELIGHTS_ESTIMATE_REFIT=0 checks the bake without it.
REFIT = os.environ.get("PROBELIGHTS_ESTIMATE_REFIT", "1") == "1"
a = harness.args()
harness.install_addon(a.zip)


def seeds_mean(truth, samples):
    """Renders with seeds 1 and 2 at `samples`; returns their mean's relative RMS difference from `truth`
    (rms(mean - truth) / rms(truth), luminance, like the estimate) and the mean's own noise on the same scale
    (half the two renders' difference has the mean's variance, independent of the mean)."""
    scene = bpy.context.scene
    scene.cycles.samples = samples
    y = []
    for seed in (1, 2):
        scene.cycles.seed = seed
        y.append(render_scene.render()[..., :3] @ render_scene.LUM)
    scene.cycles.seed = 1
    t = truth[..., :3] @ render_scene.LUM
    scale = math.sqrt(np.mean(t ** 2))
    rms = lambda d: math.sqrt(np.mean(d ** 2)) / scale  # noqa: E731
    return rms((y[0] + y[1]) / 2 - t), rms((y[0] - y[1]) / 2)


def less_noise(rendered, noise):
    """E[rendered^2] = difference^2 + noise^2: the difference the renders measure, their noise taken out."""
    return math.sqrt(max(0.0, rendered ** 2 - noise ** 2))


# How far Cycles' render of the world may be from the probe's truth: 4.0+ renders it within noise (0.3 points,
# the tests' absolute bound); 3.x renders the bundled probe 0.33 % from it, not noise (0.01 % at 2 x 8192
# samples): there the lamps are held to the truth, which the estimate predicts, not to 3.x's world.
WORLD_BOUND = 0.003 if bpy.app.version >= (4, 0, 0) else 0.005


def check_world(probe, truth):
    """The reference is the probe's truth from its pixels (render_scene.ground_truth); Cycles' render of the world
    must be it (within WORLD_BOUND)."""
    rendered, noise = seeds_mean(truth, SAMPLES)
    difference = less_noise(rendered, noise)
    print("  %s: the world's render is %.2f %% from the probe's truth (noise %.2f %%; less noise %.2f %%)" % (
        os.path.basename(probe), 100 * rendered, 100 * noise, 100 * difference), flush=True)
    assert difference <= WORLD_BOUND, (probe, rendered, noise)


def estimate_against_render(probe, counts=(8, 16, 64), world=False):
    """The lamps' render against the probe's truth computed from its pixels (render_scene.ground_truth, what the
    estimate measures against); `world`: Cycles' render of the world checked against that truth first."""
    harness.empty_scene()
    image = bpy.data.images.load(probe)
    env = harness.env_world(image)
    # The truth is the probe's pixels: the world shows them unfiltered (Blender's default, Linear, blurs each by
    # a pixel; measured on sunrise at 64 suns, 0.65 % rendered against 0.59 % Closest, the estimate 0.33 %).
    env.node_tree.nodes["Environment Texture"].interpolation = "Closest"
    render_scene.ground_under_sphere(SAMPLES)
    truth = render_scene.ground_truth(image)
    if world or WORLD_CHECKED == "all":
        check_world(probe, truth)
    settings = bpy.context.scene.probe_lights
    worst = 0.0
    for n in counts:
        bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=n, shadows="FIT", refit=REFIT)
        estimate = settings.last_shadow_error / 100
        base = SAMPLES * min(n, 32) // 32
        for samples in (base, 4 * base):
            rendered, noise = seeds_mean(truth, samples)
            denoised = less_noise(rendered, noise)
            bound = max(denoised / 3, 0.003)
            # Where the two disagree and the noise outweighs the difference, the difference is not measured: once
            # more at 4x the samples, which halve the noise (64 suns are the noisiest; most never need it).
            if abs(estimate - denoised) <= bound or noise <= max(denoised, 0.003):
                break
        print("  %s, %2d suns: estimate %.2f %%, rendered %.2f %% (noise %.2f %% at 2 x %d samples; less noise "
              "%.2f %%)" % (os.path.basename(probe), n, 100 * estimate, 100 * rendered, 100 * noise, samples,
                            100 * denoised), flush=True)
        assert abs(estimate - denoised) <= bound, (probe, n, estimate, denoised)
        worst = max(worst, abs(estimate - denoised) / bound)
    return worst


def test_the_estimated_shadow_error_is_the_rendered_one():
    probes = [harness.BUNDLED_PROBE] + [os.path.join(harness.studiolights(a), f) for f in STUDIOLIGHTS]
    print("  Blender %s, Cycles 2 x %d samples at 64 suns, 16 x 16 ground points" % (bpy.app.version_string,
                                                                                  SAMPLES))
    worst = max(estimate_against_render(p, world=p == harness.BUNDLED_PROBE) for p in probes)
    print("  worst |estimate - rendered| / bound: %.2f" % worst)


def test_negative_samples_are_light_the_lamps_and_the_estimate_keep():
    """pmndrs_esplanade_dwab (../shared): DWAB's ringing leaves 5054 negative samples beside its sun, -6.5 % of its
    light, which Cycles 4.0+ renders (its world render is the truth with them, checked here). When the lights and
    the estimate dropped them, 16 suns rendered 10.2 % from the world-lit render against an estimate of 2.5 %;
    keeping them, the two agree (4.5.15: 2.59 % / 2.70 %). Cycles 3.x renders a world's negative pixels only in
    part (3.4.1: its world render 1.75 % from the probe's truth at the ground points, 4.5's 0.58 %, its noise;
    bench/render_vs_model.py): there the world's render is not checked, the lamps are still held to the truth."""
    probe = harness.shared_probe(a, "pmndrs_esplanade_dwab.exr")
    if probe:
        estimate_against_render(probe, counts=(16,), world=bpy.app.version >= (4, 0, 0))


harness.run([test_the_estimated_shadow_error_is_the_rendered_one,
             test_negative_samples_are_light_the_lamps_and_the_estimate_keep])
