"""Drives Blender for the tests (tests/blender/) and the benchmarks (bench/): install the add-on from its zip into a fresh profile (as a new user
would), build test worlds, and a tiny runner that prints one line per test and 'N passed, N failed'.

Run a test file alone, in Debian's Blender or in a bpy module's Python (scripts/bpy-env.sh makes one):
  tests/blender/run.sh blender tests/blender/test_addon.py build/probe_lights-0.1.0-linux_x64.zip ../shared
  tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python tests/blender/test_addon.py \
      build/probe_lights-0.1.0-linux_x64.zip ../shared
"""

import argparse
import glob
import importlib
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
    p.add_argument("--studiolights", default="", help="default: the running Blender's own studio lights")
    p.add_argument("--save", default="", help="folder to save pictures in (docs pictures)")
    p.add_argument("--size", default="", help="WIDTHxHEIGHTxSAMPLES for the render test (docs pictures)")
    p.add_argument("--only", default="", help="run only these tests (names, comma-separated)")
    p.add_argument("--skip", default="", help="leave these tests out (names, comma-separated), saying so")
    return p.parse_args(argv)


ADDON = "probe_lights"  # the add-on's module name once installed (install_addon sets it)


BUNDLED_PROBE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "noon_grass_1k.hdr")


def bench_argv():
    """The arguments of a bench over every probe: (the zip, the ../shared folder or "", the other arguments)."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    zip_path = argv[argv.index("--zip") + 1]
    shared = argv[argv.index("--shared") + 1] if "--shared" in argv else ""
    rest = [a for i, a in enumerate(argv) if not a.startswith("--") and (i == 0 or not argv[i - 1].startswith("--"))]
    return zip_path, shared, rest


def bench_option(name, default):
    """A bench's `name VALUE` option (e.g. --engine eevee), or `default`."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return argv[argv.index(name) + 1] if name in argv else default


def bench_args(samples=256):
    """The arguments of the bench/bench_*.py scripts: the zip, then optionally a probe and a sample count."""
    zip_path, _, rest = bench_argv()
    return zip_path, (rest[0] if rest else BUNDLED_PROBE), (int(rest[1]) if len(rest) > 1 else samples)


def bench_probes(shared, studio_lights=True):
    """The probes a bench runs over: the bundled one, ../shared/hdri's (`shared`, "" for none) and, with
    `studio_lights`, the running Blender's own 8 studio lights: 15 with ../shared."""
    probes = [BUNDLED_PROBE]
    if shared:
        probes += [p for p in sorted(glob.glob(os.path.join(shared, "hdri", "*"))) if p.endswith((".hdr", ".exr"))
                   and os.path.basename(p) != os.path.basename(BUNDLED_PROBE)]
    if studio_lights:
        probes += sorted(glob.glob(os.path.join(blender_studiolights(), "*.exr")))
    return probes


def named_probes(probes, names):
    """The probes a bench was asked for: `names`, a comma list of file names without their extension ("" or "all":
    every one)."""
    if not names or names == "all":
        return probes
    wanted = names.split(",")
    return [p for p in probes if os.path.splitext(os.path.basename(p))[0] in wanted]


def blender_studiolights():
    """The folder of the running Blender's own lat-long studio lights (8 CC0 .exr, shipped with every Blender)."""
    return bpy.utils.system_resource("DATAFILES", path="studiolights/world")


def studiolights(a):
    """The studio lights' folder the tests were given (--studiolights), or the running Blender's own."""
    return a.studiolights or blender_studiolights()


def shared_probe(a, name, fallback=None):
    """A probe from ../shared/hdri; when ../shared is absent, `fallback` (or None), saying it was skipped."""
    path = os.path.join(a.shared, "hdri", name) if a.shared else ""
    if path and os.path.exists(path):
        return path
    instead = ", using %s" % os.path.basename(fallback) if fallback else ""
    print("  skipped: ../shared not found (%s)%s" % (name, instead))
    return fallback


def install_addon(zip_path):
    """Installs and enables the add-on from its zip as a user would, in a fresh profile: Blender 4.2+ through the
    extension system's Install from Disk (into the user_default repository), older Blenders as a legacy add-on.
    Returns the add-on's module."""
    global ADDON
    if not os.environ.get("BLENDER_USER_SCRIPTS"):
        raise SystemExit("set BLENDER_USER_SCRIPTS to a fresh folder: the tests install the add-on there")
    path = os.path.abspath(zip_path)
    if bpy.app.version >= (4, 2, 0):
        result = bpy.ops.extensions.package_install_files(filepath=path, repo="user_default",
                                                          enable_on_install=True)
        assert result == {"FINISHED"}, result
        ADDON = "bl_ext.user_default.probe_lights"
    else:
        bpy.ops.preferences.addon_install(filepath=path, overwrite=True)
        bpy.ops.preferences.addon_enable(module="probe_lights")
        ADDON = "probe_lights"
    assert ADDON in bpy.context.preferences.addons, "the add-on is not enabled: %s" % ADDON
    print("installed %s in Blender %s (Python %d.%d)" % (ADDON, bpy.app.version_string, *sys.version_info[:2]),
          flush=True)
    return importlib.import_module(ADDON)


def addon_module(name):
    """One of the add-on's modules (e.g. 'light_objects'), wherever the install put the package."""
    return importlib.import_module(ADDON + "." + name)


def native():
    """The add-on's own _probelights (the portable build it carries)."""
    return addon_module("native").module()


def empty_scene():
    """The current scene emptied of objects, and no other worlds, images, lights, collections or node groups: a
    clean stage for each test (reading factory settings would also disable the add-on)."""
    for collection in (bpy.data.objects, bpy.data.lights, bpy.data.cameras, bpy.data.meshes, bpy.data.materials,
                       bpy.data.collections, bpy.data.node_groups, bpy.data.images, bpy.data.actions):
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
    use_nodes(world)
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


def use_nodes(world):
    """Blender before 5.0 renders a world's nodes only when asked; 5.0 always does (World.use_nodes deprecated)."""
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = True


def sky_world(elevation_deg=35.0, rotation_deg=0.0):
    """A world lit by a physical Sky Texture (rendered by the add-on: it has no image to read)."""
    world = bpy.data.worlds.new("sky")
    bpy.context.scene.world = world
    use_nodes(world)
    sky = world.node_tree.nodes.new("ShaderNodeTexSky")
    sky_type(sky)
    sky.sun_elevation = math.radians(elevation_deg)
    sky.sun_rotation = math.radians(rotation_deg)
    world.node_tree.links.new(sky.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
    return world


def sky_type(sky, physical=True):
    """Sky Texture types by version: 5.0 split Nishita into single and multiple scattering."""
    names = [item.identifier for item in sky.bl_rna.properties["sky_type"].enum_items]
    sky.sky_type = "NISHITA" if "NISHITA" in names else "MULTIPLE_SCATTERING" if physical else "PREETHAM"


def eevee_engine():
    """EEVEE's engine name: BLENDER_EEVEE (3.x Legacy, and 5.0+), BLENDER_EEVEE_NEXT (4.2 to 4.5)."""
    names = [e.identifier for e in bpy.types.RenderSettings.bl_rna.properties["engine"].enum_items]
    return "BLENDER_EEVEE_NEXT" if "BLENDER_EEVEE_NEXT" in names else "BLENDER_EEVEE"


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
    visibility = tuple(getattr(world.cycles_visibility, ray) for ray in ("camera", "diffuse", "glossy", "transmission",
                                                                     "scatter", "shadow"))
    return (world.use_nodes if bpy.app.version < (5, 0, 0) else True), nodes, links, visibility


def angle_deg(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return math.degrees(math.acos(np.clip(np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b), -1, 1)))


def run(tests):
    only = [name for name in args().only.split(",") if name]
    skip = [name for name in args().skip.split(",") if name]
    unknown = set(only + skip) - {test.__name__ for test in tests}
    if unknown:
        raise SystemExit("no such test: %s" % ", ".join(sorted(unknown)))
    for name in skip:
        print("SKIP %s (left out by --skip)" % name, flush=True)
    passed = failed = 0
    for test in [t for t in tests if (not only or t.__name__ in only) and t.__name__ not in skip]:
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
    if "render_cache" in sys.modules:
        sys.modules["render_cache"].report()
    if bpy.app.background and getattr(bpy.app, "binary_path", "") == "":
        # bpy as a module: after wm.open_mainfile and an EEVEE render (test_eevee.py), bpy 4.5's teardown at
        # interpreter exit hung under Xvfb (the tests had passed and printed). Nothing is left to save: leave now.
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(1 if failed else 0)
    if failed:
        sys.exit(1)
