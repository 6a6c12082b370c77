"""Memory across clicks: the read buffer reused only when nobody holds it, the core's tables given back."""

import bpy
import numpy as np

import harness
from addon_common import bake, light_objects


def test_the_read_buffer_is_reused_only_when_nobody_holds_it():
    """Pixels are read into a buffer kept for the next read (an 8K read into fresh memory costs 2x more), but never
    into one whose pixels somebody still holds (a running tradeoff): that read gets a buffer of its own."""
    world_image = harness.addon_module("world_image")
    img = harness.float_image("reused", np.arange(8 * 16 * 3, dtype=np.float32).reshape(8, 16, 3))
    a = world_image.image_pixels(img)
    held = a.copy()
    b = world_image.image_pixels(img)  # a is still held: b must not overwrite it
    assert b.base is not a.base and np.array_equal(a, b) and np.array_equal(a, held)
    del a
    kept = id(world_image._kept[0])  # an id, not a reference: holding the buffer would keep it from reuse
    assert id(b.base) == kept
    del b
    c = world_image.image_pixels(img)  # nobody holds the kept buffer now: reused
    assert id(c.base) == kept and np.array_equal(c, held)
    img.pixels[0] = -7.0  # bottom-left red in Blender's rows: the last row of ours
    d = world_image.image_pixels(img)
    assert id(d.base) != kept and d[-1, 0, 0] == -7.0 and np.array_equal(c, held), (d[-1, 0, 0], c[-1, 0, 0])


def test_the_cores_table_buffers_are_given_back_a_minute_after_the_last_bake():
    """The core keeps its last tables' buffers for the next bake (no fresh memory to map: 2K, 37 ms a click) and
    the add-on gives them back KEEP_SECONDS after the last bake (a timer; in background mode the test calls it)."""
    native = harness.addon_module("native")
    harness.empty_scene()
    harness.env_world(harness.float_image("kept", np.ones((64, 128, 3), np.float32)))
    bake(count=4)
    assert bpy.app.timers.is_registered(native._release_buffers)
    assert native.KEEP_SECONDS == 60.0
    native._release_buffers()  # what the timer does
    bake(count=4)  # and bakes go on after it
    assert len(light_objects.baked_lights(bpy.context.scene.world)) == 4
