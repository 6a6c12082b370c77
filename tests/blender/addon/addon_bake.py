"""Baking as a user clicks it: every probe and method, the estimate and the count it picks, the tradeoff,
bad worlds and files refused with a one-line report."""

import math
import os

import bpy
import numpy as np

import harness
from addon_common import _probelights, bake, bright_spot_world, brightest, expect_report, irradiance, latlong_direction, light_objects, LUM, real_probes, sun_direction


def test_register_unregister():
    assert hasattr(bpy.types.Scene, "probe_lights") and hasattr(bpy.ops.probe_lights, "bake")
    bpy.ops.preferences.addon_disable(module=harness.ADDON)
    assert not hasattr(bpy.types.Scene, "probe_lights")
    assert not hasattr(bpy.types, "PROBE_LIGHTS_PT_world")
    bpy.ops.preferences.addon_enable(module=harness.ADDON)
    assert hasattr(bpy.types.Scene, "probe_lights") and hasattr(bpy.types, "PROBE_LIGHTS_PT_world")


def test_real_probes_bake_with_their_energy():
    for path in real_probes():
        harness.empty_scene()
        image = bpy.data.images.load(path)
        harness.env_world(image, strength=1.5)
        lights = bake(count=16, refit=False)  # the regions' sums; the refit moves them (its note says how much)
        assert len(lights) == 16, (path, len(lights))
        # Reference: the same pixels Blender holds, through the add-on's own module.
        pixels = np.empty(image.size[0] * image.size[1] * image.channels, np.float32)
        image.pixels.foreach_get(pixels)
        pixels = pixels.reshape(image.size[1], image.size[0], image.channels)[::-1]
        reference = _probelights.bake(pixels, lights=1)["total_rgb"]
        total = sum(irradiance(o) for o in lights)
        rel = np.abs(total - 1.5 * reference) / (1.5 * reference)
        assert rel.max() < 1e-5, (path, total, reference)
        for o in lights:
            assert o.data.type == "SUN" and 0 <= o.data.angle <= math.pi and o.data.energy >= 0
        print("  %-32s 16 suns, energy matches to %.1e, brightest %.0f%%" % (
            os.path.basename(path), rel.max(), 100 * max(irradiance(o) @ LUM for o in lights) / (total @ LUM)))


def test_every_method_bakes():
    harness.empty_scene()
    bright_spot_world((40, 20))
    for method in ("auto", "both", "variance", "median-cut", "sh"):
        lights = bake(count=6, method=method)
        assert len(lights) == 6, (method, len(lights))
        assert harness.angle_deg(sun_direction(brightest(lights)), latlong_direction(40, 20, 128, 64)) < 0.5, method


def test_auto_fits_both_cuts_up_to_16_lights():
    """Auto (the default) fits variance and median cut up to 16 lights and keeps the better, says which in the
    notes; above 16 it starts both and fits the better alone; Both cuts fits both at any count; a tolerance
    never does either."""
    harness.empty_scene()
    bright_spot_world((40, 20))
    settings = bpy.context.scene.probe_lights
    assert settings.bl_rna.properties["method"].default == "auto"
    for method, count, note in (("auto", 16, "both cuts fitted:"), ("auto", 17, "both cuts started:"),
                                ("both", 24, "both cuts fitted:"), ("variance", 8, None)):
        bake(count=count, method=method)
        said = [n for n in ("both cuts fitted:", "both cuts started:") if n in settings.last_notes]
        assert said == ([note] if note else []), (method, count, settings.last_notes)
        assert "both cuts" not in settings.last_warnings, settings.last_warnings
    bake(method="both", count_mode="TOLERANCE", max_error=5.0)
    assert "both cuts" not in settings.last_notes and "auto count" in settings.last_notes, settings.last_notes


def test_estimated_errors_and_count_by_tolerance():
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    settings = bpy.context.scene.probe_lights
    bake(count=16)
    assert 0 < settings.last_diffuse_error < 10 and 0 < settings.last_shadow_error < 20, (
        settings.last_diffuse_error, settings.last_shadow_error)
    lights = bake(count_mode="TOLERANCE", max_error=1.5)
    assert settings.last_diffuse_error <= 1.5 and settings.last_shadow_error <= 1.5
    assert "auto count" in settings.last_notes, settings.last_notes
    print("  1.5 %% tolerance: %d lights, diffuse %.2f %%, shadow %.2f %%" % (
        len(lights), settings.last_diffuse_error, settings.last_shadow_error))
    refit = bake(count=16, refit=True)
    assert len(refit) == 16
    # Refit is the default, and the results say where the strengths went (a wide sun gives a facing surface more
    # light than its strength, so they sum to less than the world's); a count past what it takes bakes without
    # it, saying so.
    assert bpy.context.scene.probe_lights.bl_rna.properties["refit"].default is True
    bake(count=16)
    assert 85.0 < settings.last_energy < 100.0, settings.last_energy
    many = bake(count=300)
    assert len(many) == 300, len(many)
    assert "the refit takes at most 256 lights: 300 lights baked without it" in settings.last_warnings, \
        settings.last_warnings


def test_more_suns_than_pay_off_are_reported_with_this_versions_measurements():
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    settings = bpy.context.scene.probe_lights
    render_cost = harness.addon_module("render_cost")
    best = render_cost.sweet_spot(bpy.app.version)
    bake(count=best)
    assert "no closer in Cycles" not in settings.last_notes + settings.last_warnings, settings.last_notes
    bake(count=2 * best)
    if not hasattr(bpy.context.scene.cycles, "use_light_tree"):
        # Cycles 3.x: the warning that many lamps render noisily says it, once.
        assert "no light tree" in settings.last_warnings, settings.last_warnings
        assert "More than" not in settings.last_notes, settings.last_notes
        return
    measured = render_cost.measured_version(bpy.app.version)
    assert "More than %d suns" % best in settings.last_notes, settings.last_notes
    assert "no closer in Cycles %d.%d" % measured[:2] in settings.last_notes, settings.last_notes
    assert "no closer" not in settings.last_warnings, settings.last_warnings  # a note, not a warning
    note = [n for n in settings.last_notes.split("\n") if "no closer in Cycles" in n][0]
    print("  note at %d suns: %s" % (2 * best, note))


def test_the_default_count_follows_the_engine():
    """Count by Engine (the default): a bake makes the count past which more render no closer in the scene's
    engine and this Blender (render_cost.json); a script's explicit count wins over it; an engine nothing was
    measured in (EEVEE Legacy, Workbench) gets 64."""
    harness.empty_scene()
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene, render_cost = bpy.context.scene, harness.addon_module("render_cost")
    settings = scene.probe_lights
    assert settings.bl_rna.properties["count_mode"].default == "ENGINE"
    settings.count_mode = "ENGINE"  # (an earlier test's count left it at Count)
    engines = ["CYCLES", harness.eevee_engine(), "BLENDER_WORKBENCH"]
    for engine in engines:
        scene.render.engine = engine
        count, why = render_cost.default_count(engine, bpy.app.version)
        assert len(bake()) == count == settings.last_count, (engine, count)
        assert settings.count_mode == "ENGINE"
        print("  %s: %d lamps (%s)" % (engine, count, why))
        if render_cost.engine_of(engine, bpy.app.version) is None:
            assert count == 64 and why == "renders in this engine not measured", (engine, why)
        else:
            assert "no closer" not in settings.last_notes, settings.last_notes  # never past its own advice
    assert render_cost.default_count("CYCLES", bpy.app.version)[0] == 32  # (Cycles' sweet spot in every version)
    assert len(bake(count=12)) == 12 and settings.count_mode == "COUNT"  # a script's count wins
    scene.render.engine = "CYCLES"
    settings.count_mode = "ENGINE"
    assert len(bake(light_type="POINT")) == 64  # the point lamps' renders were not measured
    settings.light_type = "SUN"
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}  # EEVEE's settings the EEVEE bake fitted put back


def test_tradeoff_in_the_panel():
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    before = harness.tree_snapshot(world)
    assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    rows = bpy.context.scene.probe_lights.tradeoff
    plain = {r.lights: r.diffuse for r in rows if not r.refit}
    assert sorted(plain) == [4, 8, 16, 32, 64, 128, 256] and plain[256] < plain[4]
    for r in rows:  # a click's time counts reading the world and making the lamps, not only the bake
        assert r.click_ms > r.bake_ms > 0, (r.lights, r.click_ms, r.bake_ms)
    assert harness.tree_snapshot(world) == before and not light_objects.baked_lights(bpy.context.scene.world)
    assert bpy.ops.probe_lights.set_count(count=32) == {"FINISHED"}
    assert bpy.context.scene.probe_lights.count == 32
    print("  tradeoff: " + ", ".join("%d: %.2f %%" % (n, 100 * e) for n, e in sorted(plain.items())))


def test_tolerance_never_backfires():
    """A tolerance no count meets: the count with the lowest error found, said in the report, never more lights
    than a count that did better. The probe is log-normal noise (sigma 3, 256 x 128): its shadows stay above the
    smallest tolerance (0.05 %) up to the most lights tried, 1024 (0.16 % measured); a real probe meets it."""
    harness.empty_scene()
    rng = np.random.default_rng(1)
    noise = np.exp(3 * rng.standard_normal((128, 256, 1))).repeat(3, 2)
    harness.env_world(harness.float_image("noise", noise))
    settings = bpy.context.scene.probe_lights
    lamps = bake(count_mode="TOLERANCE", max_error=0.05)
    worst = max(settings.last_diffuse_error, settings.last_shadow_error)
    assert "no count met the tolerance" in settings.last_report, settings.last_report
    assert "no count met the tolerance" in settings.last_warnings
    n = len(lamps)
    for m in (8, 16, 32, 64, 128):
        bake(count=m)
        other = max(settings.last_diffuse_error, settings.last_shadow_error)
        assert not (m < n and other < worst - 1e-6), (m, other, n, worst)
    print("  tolerance 0.05 %%: %d lights, worst error %.2f %%" % (n, worst))


def test_bad_worlds_are_one_line_reports():
    harness.empty_scene()
    bpy.context.scene.world = None
    expect_report("the scene has no world")
    world = harness.env_world(None)
    expect_report("has no image")
    missing = bpy.data.images.new("missing", 4, 4, float_buffer=True)
    missing.source = "FILE"
    missing.filepath = "/nonexistent/probe.exr"
    missing.reload()
    world.node_tree.nodes["Environment Texture"].image = missing
    before = harness.tree_snapshot(world)
    expect_report("is its file missing?")
    assert harness.tree_snapshot(world) == before, "a failed bake leaves the world alone"
    nan = np.ones((8, 16, 3), np.float32)
    nan[2, 3, 1] = np.nan
    world.node_tree.nodes["Environment Texture"].image = harness.float_image("nan", nan)
    expect_report("1 NaN/Inf samples, first at pixel (3, 2); to read them as 0: set NaN/Inf pixels to Zero")
    assert not light_objects.baked_lights(bpy.context.scene.world)


def test_inputs_that_are_not_what_they_claim():
    harness.empty_scene()
    settings = bpy.context.scene.probe_lights
    harness.env_world(harness.float_image("wide", np.ones((200, 300, 3), np.float32)))
    bake(count=4)
    assert "is 300x200, not 2:1" in settings.last_warnings, settings.last_warnings
    nan = np.ones((8, 16, 3), np.float32)
    nan[2, 3, 1] = np.inf
    harness.env_world(harness.float_image("nan", nan))
    bake(count=4, non_finite="zero")
    assert "read 1 NaN/Inf samples as 0" in settings.last_warnings, settings.last_warnings
