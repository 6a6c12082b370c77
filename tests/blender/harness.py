"""Shared by the Blender background tests: install the add-on from its zip into a fresh profile (as a new user
would), build test worlds, and a tiny runner that prints one line per test and 'N passed, N failed'.

Run a test file alone:
  BLENDER_USER_SCRIPTS=$(mktemp -d) blender -b --factory-startup -noaudio --python-exit-code 1 \
      --python tests/blender/test_addon.py -- --zip build/probe_lights.zip --shared ../shared
"""

import argparse
import math
import os
import sys
import time
import traceback

import bpy
import numpy as np


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--zip", required=True)
    p.add_argument("--shared", default="")
    p.add_argument("--studiolights", default="/usr/share/blender/datafiles/studiolights/world")
    p.add_argument("--save", default="", help="folder to save pictures in (README images)")
    p.add_argument("--size", default="", help="WIDTHxHEIGHTxSAMPLES for the render test (README images)")
    return p.parse_args(argv)


def install_addon(zip_path):
    """Installs and enables the add-on from its zip; returns the module."""
    if not os.environ.get("BLENDER_USER_SCRIPTS"):
        raise SystemExit("set BLENDER_USER_SCRIPTS to a fresh folder: the tests install the add-on there")
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    bpy.ops.preferences.addon_enable(module="probe_lights")
    import probe_lights
    return probe_lights


def empty_scene():
    """The current scene emptied of objects, and no other worlds, images, lights, collections or node groups: a
    clean stage for each test (reading factory settings would also disable the add-on)."""
    for collection in (bpy.data.objects, bpy.data.lights, bpy.data.cameras, bpy.data.meshes, bpy.data.materials,
                       bpy.data.collections, bpy.data.node_groups, bpy.data.images):
        for item in list(collection):
            if getattr(item, "type", "") != "RENDER_RESULT":
                collection.remove(item)
    scene = bpy.context.scene
    for world in list(bpy.data.worlds):
        bpy.data.worlds.remove(world)
    scene.world = None
    scene.render.engine = "CYCLES"
    scene.cycles.use_denoising = False
    scene.cycles.device = "CPU"
    return scene


def env_world(image, projection="EQUIRECTANGULAR", strength=1.0, rotation=None, name="probe world"):
    """World: [Texture Coordinate -> Mapping(rotation) ->] Environment Texture -> Background -> Output."""
    world = bpy.data.worlds.new(name)
    bpy.context.scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = strength
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    env.projection = projection
    nt.links.new(env.outputs["Color"], bg.inputs["Color"])
    if rotation is not None:
        coords = nt.nodes.new("ShaderNodeTexCoord")
        mapping = nt.nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = rotation
        nt.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        nt.links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    return world


def float_image(name, pixels_top_down):
    """A packed float image from an H x W x 3 or 4 array given top row first."""
    a = np.asarray(pixels_top_down, dtype=np.float32)
    h, w = a.shape[:2]
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., : a.shape[2]] = a[..., :4]
    img = bpy.data.images.new(name, w, h, float_buffer=True)
    img.pixels.foreach_set(rgba[::-1].ravel())
    img.update()
    img.pack()
    return img


def tree_snapshot(world):
    """Everything about a world's node tree that a restore must bring back."""
    nt = world.node_tree
    nodes = {}
    for n in nt.nodes:
        values = []
        for s in n.inputs:
            v = getattr(s, "default_value", None)
            try:
                v = tuple(round(float(c), 6) for c in v)
            except TypeError:
                v = round(float(v), 6) if isinstance(v, (int, float)) else None
            values.append((s.identifier, v))
        nodes[n.name] = (n.bl_idname, tuple(round(c, 3) for c in n.location), tuple(values))
    links = sorted((l.from_node.name, l.from_socket.identifier, l.to_node.name, l.to_socket.identifier)
                   for l in nt.links)
    return world.use_nodes, nodes, links


def angle_deg(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return math.degrees(math.acos(np.clip(np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b), -1, 1)))


def run(tests):
    passed = failed = 0
    for test in tests:
        start = time.perf_counter()
        try:
            test()
            passed += 1
            print("PASS %s (%.1f s)" % (test.__name__, time.perf_counter() - start), flush=True)
        except Exception:
            failed += 1
            print("FAIL %s" % test.__name__, flush=True)
            traceback.print_exc()
    print("%d passed, %d failed" % (passed, failed), flush=True)
    if failed:
        sys.exit(1)
