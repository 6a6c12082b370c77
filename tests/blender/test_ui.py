"""The add-on with Blender's interface up (run under Xvfb by run.sh --ui): the Bake button's path (invoke), undo,
the panel drawing in World properties, and a screenshot of it (saved with --save)."""

import os
import sys
import traceback

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
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
    bpy.context.scene.probe_lights.count = 12
    with window_override():
        # As the Bake button calls it: invoke, and an undo step pushed (Python calls push none by default).
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True) == {"FINISHED"}
    assert len(light_objects.baked_lights(bpy.context.scene)) == 12  # the panel's count
    with window_override():
        assert bpy.ops.probe_lights.bake("INVOKE_DEFAULT", True, count=5) == {"FINISHED"}
    assert len(light_objects.baked_lights(bpy.context.scene)) == 5  # an explicit count wins
    for i in range(2):
        with window_override():
            assert bpy.ops.ed.undo() == {"FINISHED"}, "undo %d" % (i + 1)
        yield  # let Blender's event loop run between undo steps, as between a user's key presses
    yield
    scene = bpy.context.scene
    assert not light_objects.baked_lights(scene)
    assert harness.tree_snapshot(scene.world) == before
    with window_override():
        assert bpy.ops.ed.redo() == {"FINISHED"}
    yield
    assert len(light_objects.baked_lights(bpy.context.scene)) == 12


def test_panel_draws_in_world_properties():
    win = bpy.context.window_manager.windows[0]
    bpy.ops.probe_lights.tradeoff()  # so the picture shows the accuracy-vs-time table too
    # The largest area (the 3D view) becomes a Properties editor on the World tab: wide enough to read the panel.
    area = max(win.screen.areas, key=lambda a: a.width * a.height)
    area.type = "PROPERTIES"
    yield
    area.spaces[0].context = "WORLD"
    from probe_lights import ui
    original, calls, errors = ui.draw_panel, [], []

    def checked(layout, context):
        calls.append(1)
        try:
            original(layout, context)
        except Exception:
            errors.append(traceback.format_exc())
            raise

    ui.draw_panel = checked
    try:
        area.tag_redraw()
        for _ in range(3):
            yield  # the editor redraws in the event loop
        with bpy.context.temp_override(window=win, area=area):
            bpy.ops.wm.redraw_timer(type="DRAW_WIN_SWAP", iterations=1)
        yield
    finally:
        ui.draw_panel = original
    assert calls, "the World properties panel was never drawn"
    assert not errors, errors[0]
    if ARGS.save:
        with bpy.context.temp_override(window=win, area=area):
            bpy.ops.screen.screenshot_area(filepath=os.path.join(os.path.abspath(ARGS.save), "panel.png"))


def steps():
    """Runs the tests one event-loop step at a time: a test may `yield` to let Blender process events."""
    passed = failed = 0
    # A fresh profile opens with the first-run splash over the window; Escape closes it, as a user would.
    win = bpy.context.window_manager.windows[0]
    win.event_simulate(type="ESC", value="PRESS")
    win.event_simulate(type="ESC", value="RELEASE")
    yield
    harness.install_addon(ARGS.zip)
    for test in (test_button_bake_then_undo, test_panel_draws_in_world_properties):
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
