"""The probe's pixels: read from a Blender image, or rendered from the world with a panoramic Cycles camera."""

import math
import os
import sys
import tempfile

import bpy
import numpy as np

from . import native
from .conversion import srgb_to_linear
from .errors import ProbeError
from .world_graph import sequence_number, sequence_path

LINEAR_SPACES = {"Linear", "Linear Rec.709", "Non-Color", "Raw", "Linear CIE-XYZ E"}
GIL_HOLD_SECONDS = 1.0  # Python's thread switch interval while the world's render job runs (WorldRender.start)
KEEP_SECONDS = 60.0  # how long the read buffer is kept after a read (Blender's timers: only with a window)

_kept = []  # at most one float32 buffer, for the next read of an image of the same size


def _without_huge_pages(allocate):
    """Runs allocate() with NumPy's huge-page advice off: the first read into a huge-page buffer waits for the
    kernel's first huge pages of the process, several times a read into a plain one (docs/decisions.md)."""
    try:
        from numpy._core import multiarray
    except ImportError:  # NumPy 1.x
        from numpy.core import multiarray
    switch = getattr(multiarray, "_set_madvise_hugepage", None)
    if switch is None:
        return allocate()
    before = switch(False)
    try:
        return allocate()
    finally:
        switch(before)


def _release():
    _kept.clear()


def read_buffer(size):
    """A float32 buffer of `size` values to read pixels into: the one kept from the last read when nobody holds it
    any more (a running tradeoff holds its pixels: then a new one), else a new one. Kept KEEP_SECONDS after use."""
    for buf in _kept:
        if buf.size == size and sys.getrefcount(buf) <= 3:  # _kept, the loop variable and getrefcount's argument
            break
    else:
        _kept.clear()  # the old buffer goes first: never two of them alive for this module
        buf = _without_huge_pages(lambda: np.empty(size, dtype=np.float32))
        # Blender's foreach_get fills it on one thread; the kernel maps the fresh pages in parallel first.
        native.module().touch_pages(buf)
        _kept.append(buf)
    if bpy.app.timers.is_registered(_release):
        bpy.app.timers.unregister(_release)
    bpy.app.timers.register(_release, first_interval=KEEP_SECONDS)
    return buf


def unregister():
    _release()
    if bpy.app.timers.is_registered(_release):
        bpy.app.timers.unregister(_release)


def image_pixels(image):
    """The image's pixels as float32 H x W x C, rows top to bottom (a flipped view, no copy beyond Blender's own).

    Blender's pixels are used, never the file on disk, so packed and generated images and unsaved edits count."""
    width, height = image.size[:]
    if width == 0 or height == 0:
        raise ProbeError("world image '%s' has no pixels (is its file missing?)" % image.name)
    channels = image.channels
    buf = read_buffer(width * height * channels)
    image.pixels.foreach_get(buf)
    pixels = buf.reshape(height, width, channels)[::-1]  # Blender stores the bottom row first
    space = image.colorspace_settings.name
    if not image.is_float and space == "sRGB":
        pixels = srgb_to_linear(pixels)
    elif space not in LINEAR_SPACES and space != "sRGB":
        raise ProbeError("world image '%s' is in colour space '%s'; use Linear or sRGB" % (image.name, space))
    return pixels


class WorldRender:
    """Renders `world` (a copy of it, without the add-on's mix) to a lat-long float image with a Cycles panoramic
    camera in a temporary empty scene: blocking (render()), or as Blender's render job (start(): the status bar
    shows its progress and Esc cancels it; poll state()). close() removes everything it made.

    The camera at the origin with rotation (90, 0, -90) degrees maps its equirectangular image exactly onto the
    lat-long convention (checked by tests/blender/test_addon.py against the image read directly)."""

    def __init__(self, world, width=1024, samples=16):
        from .world_mix import remove_mix
        self.width, self.height = width, max(1, width // 2)
        self.world = world.copy()
        remove_mix(self.world)  # a re-bake sees the world as the user made it
        self.scene = bpy.data.scenes.new("probe_lights world render")
        self.cam_data = bpy.data.cameras.new("probe_lights panorama")
        self.cam = bpy.data.objects.new("probe_lights panorama", self.cam_data)
        fd, self.path = tempfile.mkstemp(suffix=".exr", prefix="probe_lights_world_")
        os.close(fd)
        self._state = "ready"
        self._user_scene = self._user_frame = None
        self._display = None
        self._switch = None
        scene, cam_data, cam = self.scene, self.cam_data, self.cam
        scene.world = self.world
        cam_data.type = "PANO"
        if hasattr(cam_data, "panorama_type"):  # Blender 4.0+
            cam_data.panorama_type = "EQUIRECTANGULAR"
        else:
            cam_data.cycles.panorama_type = "EQUIRECTANGULAR"
        cam.rotation_euler = (math.pi / 2, 0.0, -math.pi / 2)
        scene.collection.objects.link(cam)
        scene.camera = cam
        r = scene.render
        r.engine = "CYCLES"
        r.resolution_x, r.resolution_y, r.resolution_percentage = self.width, self.height, 100
        r.film_transparent = False
        r.use_compositing = False
        r.use_sequencer = False
        r.image_settings.file_format = "OPEN_EXR"
        r.image_settings.color_depth = "32"
        r.filepath = self.path
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False
        scene.cycles.device = "CPU"

    def render(self, frame=None):
        """Renders now (blocking) and returns the pixels; of scene frame `frame` when given (the world's keyframes
        and drivers are evaluated there)."""
        if frame is not None:
            # Cycles evaluates the world's keyframes at the frame of the scene in the context, not at the render
            # scene's (bpy 4.5.15, 5.3.0): both are set, the context scene's put back by close().
            user = bpy.context.scene
            if self._user_frame is None and user != self.scene:
                self._user_scene, self._user_frame = user, user.frame_current
            user.frame_current = self.scene.frame_current = frame
        bpy.ops.render.render(write_still=True, scene=self.scene.name)
        self._state = "done"
        return self.pixels()

    def start(self, context):
        """Starts Blender's render job (needs a window). The render view does not open: Blender's display
        preference is set to none while the job runs and put back by close().

        While the job runs, Python's thread switch interval is long (put back by close()). Blender keeps one flag
        for "Python may write data now": each Python callback saves it, sets its own and puts the saved value back.
        Cycles' callbacks run in the render thread; with Python's default 5 ms interval, one can take the GIL in
        the middle of an interface draw of the main thread (writes off), save that, and put it back after the
        draw has ended: from then on, as a rule for the rest of the session, no script outside an operator may
        change data ("can't modify blend data in this state (drawing/rendering)"). Seen in CI after this job, and
        reproduced with slow interface draws; with the long interval it never happened (docs/decisions.md), as
        the GIL then changes hands only between callbacks, where the flag is clear. Slow draws are what a loaded
        machine makes of ordinary ones."""
        bpy.app.handlers.render_complete.append(self._complete)
        bpy.app.handlers.render_cancel.append(self._cancel)
        view = context.preferences.view
        self._display = view.render_display_type
        view.render_display_type = "NONE"
        self._switch = sys.getswitchinterval()
        sys.setswitchinterval(max(self._switch, GIL_HOLD_SECONDS))
        self._state = "running"
        result = bpy.ops.render.render("INVOKE_DEFAULT", write_still=True, scene=self.scene.name)
        if "RUNNING_MODAL" not in result:
            self._state = "cancelled"

    def _complete(self, scene, *args):
        if scene == self.scene:
            self._state = "done"

    def _cancel(self, scene, *args):
        if scene == self.scene:
            self._state = "cancelled"

    def state(self):
        """'ready', 'running', 'done' or 'cancelled'."""
        return self._state

    def pixels(self):
        image = bpy.data.images.load(self.path)
        try:
            w, h = image.size[:]
            pixels = np.empty(w * h * image.channels, dtype=np.float32)
            image.pixels.foreach_get(pixels)
            return np.ascontiguousarray(pixels.reshape(h, w, image.channels)[::-1])
        finally:
            bpy.data.images.remove(image)

    def close(self):
        if self._user_frame is not None:
            try:
                self._user_scene.frame_set(self._user_frame)
            except ReferenceError:
                pass
            self._user_frame = None
        for handlers, f in ((bpy.app.handlers.render_complete, self._complete),
                            (bpy.app.handlers.render_cancel, self._cancel)):
            if f in handlers:
                handlers.remove(f)
        if self._display is not None:
            bpy.context.preferences.view.render_display_type = self._display
            self._display = None
        if self._switch is not None:
            sys.setswitchinterval(self._switch)
            self._switch = None
        for remove, item in ((bpy.data.objects.remove, self.cam), (bpy.data.cameras.remove, self.cam_data),
                             (bpy.data.scenes.remove, self.scene), (bpy.data.worlds.remove, self.world)):
            try:
                remove(item)
            except ReferenceError:
                pass
        try:
            os.remove(self.path)
        except OSError:
            pass


def render_world(world, width=1024, samples=16):
    """The world's pixels, rendered now (blocking): see WorldRender."""
    job = WorldRender(world, width, samples)
    try:
        return job.render()
    finally:
        job.close()


def sequence_pixels(node, frame):
    """The pixels an Environment Texture whose image is a sequence shows at scene frame `frame`: its file for that
    frame (world_graph.sequence_number, sequence_path), read through Blender in the sequence's colour space."""
    image, user = node.image, node.image_user
    number = sequence_number(frame, user.frame_start, user.frame_duration, user.frame_offset, user.use_cyclic)
    path = sequence_path(bpy.path.abspath(image.filepath, library=image.library), number or 0)
    if number is None or path is None:
        raise ProbeError("image sequence '%s' has no frames (set Frames on its Environment Texture)" % image.name)
    if not os.path.isfile(path):
        raise ProbeError("frame %d: image sequence '%s' has no file %s" % (frame, image.name, path))
    frame_image = bpy.data.images.load(path, check_existing=False)
    try:
        frame_image.colorspace_settings.name = image.colorspace_settings.name
        return np.array(image_pixels(frame_image))
    finally:
        bpy.data.images.remove(frame_image)
