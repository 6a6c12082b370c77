"""The probe's pixels: read from a Blender image, or rendered from the world with a panoramic Cycles camera."""

import math
import os
import tempfile

import bpy
import numpy as np

from .conversion import srgb_to_linear
from .errors import ProbeError

LINEAR_SPACES = {"Linear", "Linear Rec.709", "Non-Color", "Raw", "Linear CIE-XYZ E"}


def image_pixels(image):
    """The image's pixels as float32 H x W x C, rows top to bottom (a flipped view, no copy beyond Blender's own).

    Blender's pixels are used, never the file on disk, so packed and generated images and unsaved edits count."""
    width, height = image.size[:]
    if width == 0 or height == 0:
        raise ProbeError("world image '%s' has no pixels (is its file missing?)" % image.name)
    channels = image.channels
    buf = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(buf)
    pixels = buf.reshape(height, width, channels)[::-1]  # Blender stores the bottom row first
    space = image.colorspace_settings.name
    if not image.is_float and space == "sRGB":
        pixels = srgb_to_linear(pixels)
    elif space not in LINEAR_SPACES and space != "sRGB":
        raise ProbeError("world image '%s' is in colour space '%s'; use Linear or sRGB" % (image.name, space))
    return pixels


def render_world(world, width=1024, samples=16):
    """Renders `world` to a lat-long float image with a Cycles panoramic camera in a temporary empty scene.

    The camera at the origin with rotation (90, 0, -90) degrees maps its equirectangular image exactly onto the
    lat-long convention (checked by tests/blender/test_world.py with a single bright pixel)."""
    height = max(1, width // 2)
    scene = bpy.data.scenes.new("probe_lights world render")
    cam_data = bpy.data.cameras.new("probe_lights panorama")
    cam = bpy.data.objects.new("probe_lights panorama", cam_data)
    fd, path = tempfile.mkstemp(suffix=".exr", prefix="probe_lights_world_")
    os.close(fd)
    image = None
    try:
        scene.world = world
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
        r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
        r.film_transparent = False
        r.use_compositing = False
        r.use_sequencer = False
        r.image_settings.file_format = "OPEN_EXR"
        r.image_settings.color_depth = "32"
        r.filepath = path
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False
        scene.cycles.device = "CPU"
        bpy.ops.render.render(write_still=True, scene=scene.name)
        image = bpy.data.images.load(path)
        pixels = np.empty(width * height * image.channels, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        return np.ascontiguousarray(pixels.reshape(height, width, image.channels)[::-1])
    finally:
        if image is not None:
            bpy.data.images.remove(image)
        bpy.data.objects.remove(cam)
        bpy.data.cameras.remove(cam_data)
        bpy.data.scenes.remove(scene)
        try:
            os.remove(path)
        except OSError:
            pass
