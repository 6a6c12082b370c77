"""The add-on with Blender's interface up (run under Xvfb by run.sh --ui): the Bake button's path (invoke), undo,
the panel and the sidebar drawn at their default widths with nothing cut off, and screenshots of them (saved with
--save)."""

import os
import sys
import time
import traceback

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402

ARGS = harness.args()


def window_override():
    """The first window as context (looked up afresh: an undo reloads the data the old references point to)."""
    return bpy.context.temp_override(window=bpy.context.window_manager.windows[0])


def setup_world():
    from probe_lights import light_objects  # noqa: F401
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    image = bpy.data.images.load(harness.BUNDLED_PROBE)
    world = bpy.context.scene.world
    nt = world.node_tree
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    nt.links.new(env.outputs["Color"], nt.nodes["Background"].inputs["Color"])
    bpy.ops.ed.undo_push(message="set up the world")
    return world


def test_button_bake_then_undo():
    from probe_lights import light_objects
    world = setup_world()
    before = harness.tree_snapshot(world)
    bpy.context.scene.probe_lights.count_mode = "COUNT"  # (the default counts by the engine)
    bpy.context.scene.probe_lights.count = 12
    with window_override():
        # As the Bake button calls it: invoke, and an undo step pushed (Python calls push none by default).
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True) == {"FINISHED"}
    assert len(light_objects.baked_lights(bpy.context.scene.world)) == 12  # the panel's count
    with window_override():
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True, count=5) == {"FINISHED"}
    assert len(light_objects.baked_lights(bpy.context.scene.world)) == 5  # an explicit count wins
    for i in range(2):
        with window_override():
            assert bpy.ops.ed.undo() == {"FINISHED"}, "undo %d" % (i + 1)
        yield  # let Blender's event loop run between undo steps, as between a user's key presses
    yield
    scene = bpy.context.scene
    assert not light_objects.baked_lights(scene.world)
    assert harness.tree_snapshot(scene.world) == before
    with window_override():
        assert bpy.ops.ed.redo() == {"FINISHED"}
    yield
    assert len(light_objects.baked_lights(bpy.context.scene.world)) == 12


def _screenshot(win, area, name):
    if ARGS.save:
        with bpy.context.temp_override(window=win, area=area):
            bpy.ops.screen.screenshot_area(filepath=os.path.join(os.path.abspath(ARGS.save), name))


def _drawn(area, region_type="WINDOW"):
    """Redraws `area` with the panel's draw wrapped: returns (calls, errors, lines that did not fit)."""
    from probe_lights import ui
    original, calls, errors = ui.draw_panel, [], []

    def checked(layout, context):
        try:
            original(layout, context)
            calls.append((context.region.width, list(ui.OVERFLOW)))
        except Exception:
            errors.append(traceback.format_exc())
            raise

    ui.draw_panel = checked
    return original, calls, errors


def writable():
    """Whether a script may change data now (not while Blender is drawing or finishing a render)."""
    render = bpy.context.scene.render
    try:
        render.resolution_percentage = render.resolution_percentage  # an RNA write, checked like an operator's
        return True
    except (AttributeError, RuntimeError, TypeError):
        return False


def _slow_header(self, context):
    """A header draw that holds the GIL for 8 ms, as a busy interface's draws do on a loaded machine: with Python's
    default switch interval, the render thread's Cycles callbacks take the GIL in the middle of it and scripts are
    locked out after the render (see WorldRender.start): without the add-on's long interval this test failed 3 runs
    in 3, with it passed 5 in 5."""
    t = time.perf_counter()
    while time.perf_counter() - t < 0.008:
        pass


SLOW_HEADERS = (bpy.types.STATUSBAR_HT_header, bpy.types.VIEW3D_HT_header, bpy.types.TOPBAR_HT_upper_bar)


def test_a_rendered_world_bakes_as_a_render_job_that_escape_cancels():
    """A Sky Texture world is rendered by Blender's render job (progress in the status bar, the interface live);
    Esc cancels it and nothing changes; left alone, the bake follows the render, and scripts may still change data
    afterwards, even with slow interface draws during the render."""
    for header in SLOW_HEADERS:
        header.append(_slow_header)
    try:
        yield from _rendered_world_bake()
    finally:
        for header in SLOW_HEADERS:
            header.remove(_slow_header)


def _rendered_world_bake():
    from probe_lights import light_objects
    win = bpy.context.window_manager.windows[0]
    switch = sys.getswitchinterval()
    previous = bpy.context.scene.world
    world = harness.sky_world()
    before = harness.tree_snapshot(world)
    scenes = len(bpy.data.scenes)
    with window_override():
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True, count=8) == {"RUNNING_MODAL"}
    yield
    win.event_simulate(type="ESC", value="PRESS")
    win.event_simulate(type="ESC", value="RELEASE")
    for _ in range(40):
        yield
        if len(bpy.data.scenes) == scenes:
            break
    world = bpy.context.scene.world
    assert len(bpy.data.scenes) == scenes, "the render's scene is left over"
    assert not light_objects.baked_lights(world), "the bake went on after Esc"
    assert harness.tree_snapshot(world) == before, (harness.tree_snapshot(world), before)
    assert bpy.context.preferences.view.render_display_type != "NONE", "the display preference was not put back"
    with window_override():
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True, count=8) == {"RUNNING_MODAL"}
    for _ in range(200):
        yield
        if light_objects.baked_lights(bpy.context.scene.world):
            break
    world = bpy.context.scene.world
    assert len(light_objects.baked_lights(world)) == 8, "the bake did not follow the render"
    assert bpy.context.scene.probe_lights.last_source.startswith("rendered world")
    assert len(bpy.data.scenes) == scenes
    print("  rendered world: cancelled by Esc, then baked in %.0f ms" % bpy.context.scene.probe_lights.last_ms)
    # Scripts (this test runs from a timer, like many add-ons) may change data again at once: CI once saw "can't
    # modify blend data in this state (drawing/rendering)" here for good, Blender's write flag left set by a Cycles
    # callback that took the GIL mid-draw (WorldRender.start).
    waited = 0
    while not writable():
        assert waited < 25, "scripts may not change data 5 s after the render (Blender's write flag is stuck)"
        waited += 1
        yield
    print("  data writable again %d event-loop steps after the lamps came" % waited)
    assert sys.getswitchinterval() == switch, "Python's switch interval was not put back"
    bpy.ops.probe_lights.restore()
    bpy.context.scene.world = previous


def test_tradeoff_shows_progress_and_stops_on_escape():
    """From the button the tradeoff runs one light count per step (the interface stays live, the status bar says
    how far it is) and Esc stops it, keeping the counts measured so far."""
    win = bpy.context.window_manager.windows[0]
    settings = bpy.context.scene.probe_lights
    with window_override():
        assert bpy.ops.probe_lights.tradeoff("INVOKE_DEFAULT") == {"RUNNING_MODAL"}
    for _ in range(50):
        yield
        if len({r.lights for r in settings.tradeoff}) >= 2:
            break
    measured = len({r.lights for r in settings.tradeoff})
    assert 2 <= measured < 7, measured
    win.event_simulate(type="ESC", value="PRESS")
    win.event_simulate(type="ESC", value="RELEASE")
    for _ in range(5):
        yield
    stopped = len({r.lights for r in settings.tradeoff})
    for _ in range(5):
        yield
    assert len({r.lights for r in settings.tradeoff}) == stopped < 7, "Esc did not stop the tradeoff"
    print("  tradeoff stopped by Esc after %d of 7 light counts" % stopped)
    with window_override():
        assert bpy.ops.probe_lights.tradeoff("INVOKE_DEFAULT") == {"RUNNING_MODAL"}
    for _ in range(100):
        yield
        if len({r.lights for r in settings.tradeoff}) == 7:
            break
    assert len({r.lights for r in settings.tradeoff}) == 7


def test_bake_animation_shows_progress_and_escape_changes_nothing():
    """From the button Bake animation bakes a frame a step and Esc stops it with nothing changed; left alone it
    keys the lamps on every frame."""
    import tempfile
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
    from rgbe import write_hdr
    from probe_lights import light_objects
    import numpy as np
    win = bpy.context.window_manager.windows[0]
    folder = tempfile.mkdtemp()
    for f in range(1, 13):
        a = np.full((32, 64, 3), 0.05, np.float32)
        a[10, 4 * f] = 500.0
        write_hdr(os.path.join(folder, "sky_%04d.hdr" % f), a)
    world = setup_world()
    env = world.node_tree.nodes["Background"].inputs["Color"].links[0].from_node
    env.image = bpy.data.images.load(os.path.join(folder, "sky_0001.hdr"))
    env.image.source = "SEQUENCE"
    env.image_user.frame_duration, env.image_user.use_cyclic = 12, True
    with window_override():  # 2000 frames of the cyclic sequence: Esc comes long before the end
        assert bpy.ops.probe_lights.bake_animation("INVOKE_DEFAULT", frame_start=1, frame_end=2000,
                                                   count=4) == {"RUNNING_MODAL"}
    yield
    win.event_simulate(type="ESC", value="PRESS")
    win.event_simulate(type="ESC", value="RELEASE")
    for _ in range(10):
        yield
    assert not light_objects.baked_lights(world) and not bpy.data.actions, "Esc did not stop Bake animation"
    with window_override():
        assert bpy.ops.probe_lights.bake_animation("INVOKE_DEFAULT", frame_start=1, frame_end=12,
                                                   count=4) == {"RUNNING_MODAL"}
    for _ in range(50):
        yield
        if light_objects.baked_lights(world):
            break
    lamps = light_objects.baked_lights(world)
    assert len(lamps) == 4 and all(o.animation_data.action is not None for o in lamps)
    print("  Bake animation stopped by Esc, then keyed 4 lamps: %s" % bpy.context.scene.probe_lights.last_report)
    bpy.ops.probe_lights.restore()


def test_panel_fits_the_default_width():
    """The World properties panel, in the default layout's Properties editor at its default width, after a bake
    with warnings and a tradeoff: no line, button or number is cut off (every label is measured in the interface
    font against the region; buttons have short labels). The screenshot is saved with --save."""
    from probe_lights import ui
    win = bpy.context.window_manager.windows[0]
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.sample_clamp_indirect = 10.0  # Blender's default: the panel shows the Cycles offer
    with window_override():
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True, count=128) == {"FINISHED"}
    yield
    area = next(a for a in win.screen.areas if a.type == "PROPERTIES")
    area.spaces[0].context = "WORLD"
    original, calls, errors = _drawn(area)
    try:
        for _ in range(3):
            area.tag_redraw()
            yield
        with bpy.context.temp_override(window=win, area=area):
            bpy.ops.wm.redraw_timer(type="DRAW_WIN_SWAP", iterations=1)
        yield
    finally:
        ui.draw_panel = original
    assert not errors, errors[0]
    assert calls, "the World properties panel was never drawn"
    width, overflow = calls[-1]
    print("  Properties editor: %d px wide (window %d px), %d lines cut" % (width, win.width, len(overflow)))
    assert not overflow, overflow
    assert scene.probe_lights.last_warnings, "the bake had warnings to show"
    if ARGS.save:
        # Scrolled down to the panel (the editor shows the world's other panels above it), as a user would.
        region = next(r for r in area.regions if r.type == "WINDOW")
        x, y = region.x + region.width // 2, region.y + region.height // 2
        win.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        for _ in range(12):
            win.event_simulate(type="WHEELDOWNMOUSE", value="PRESS", x=x, y=y)
            yield
        _screenshot(win, area, "panel.png")


def test_sidebar_fits_its_default_width():
    from probe_lights import ui
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    area.spaces[0].show_region_ui = True
    yield
    region = next(r for r in area.regions if r.type == "UI")
    # A tradeoff row as wide as a slow machine makes it (an 11376 ms click, a 3-digit count, 2-digit errors: a
    # loaded CI machine measured such a click and its time did not fit the column).
    settings = bpy.context.scene.probe_lights
    slow = settings.tradeoff.add()
    slow.lights, slow.refit, slow.click_ms, slow.diffuse, slow.shadow = 999, settings.refit, 113760.0, 0.1234, 0.5678
    original, calls, errors = _drawn(area, "UI")
    try:
        # The sidebar shows one tab at a time: click the Probe Lights tab as a user would (tabs run down the
        # sidebar's right edge; the test tries each until the panel draws).
        for y in range(region.y + region.height - 30, region.y + 30, -25):
            if calls:
                break
            x = region.x + region.width - 8
            win.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
            win.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
            win.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x, y=y)
            area.tag_redraw()
            yield
            yield
    finally:
        ui.draw_panel = original
        settings.tradeoff.remove(len(settings.tradeoff) - 1)
    assert not errors, errors[0]
    assert calls, "the sidebar's Probe Lights tab never drew"
    width, overflow = calls[-1]
    print("  sidebar: %d px wide, %d lines cut" % (width, len(overflow)))
    _screenshot(win, area, "sidebar.png")
    assert not overflow, overflow


def steps():
    """Runs the tests one event-loop step at a time: a test may `yield` to let Blender process events."""
    passed = failed = 0
    # A fresh profile opens with the first-run splash over the window; Escape closes it, as a user would.
    win = bpy.context.window_manager.windows[0]
    win.event_simulate(type="ESC", value="PRESS")
    win.event_simulate(type="ESC", value="RELEASE")
    yield
    harness.install_addon(ARGS.zip)
    for test in (test_button_bake_then_undo, test_a_rendered_world_bakes_as_a_render_job_that_escape_cancels,
                 test_tradeoff_shows_progress_and_stops_on_escape,
                 test_bake_animation_shows_progress_and_escape_changes_nothing, test_panel_fits_the_default_width, test_sidebar_fits_its_default_width):
        try:
            result = test()
            if result is not None:
                for _ in result:
                    yield
            passed += 1
            print("PASS %s" % test.__name__, flush=True)
        except Exception:
            failed += 1
            print("FAIL %s" % test.__name__, flush=True)
            traceback.print_exc()
    print("%d passed, %d failed" % (passed, failed), flush=True)
    os._exit(1 if failed else 0)


def tick(runner=steps()):
    try:
        next(runner)
    except Exception:
        traceback.print_exc()
        os._exit(1)
    return 0.2


bpy.app.timers.register(tick, first_interval=0.5)
