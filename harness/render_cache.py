"""Renders remembered across runs: a render is a function of the scene's data, the Blender that renders it, the
machine's CPU (Cycles picks its kernel by the CPU's features) or GPU driver (EEVEE's), and the code that runs at
render time (the add-on's handlers and drivers). The render tests render the same scenes run after run: the
world-lit references always, the lamps whenever the core's lights did not change. render_scene.render() asks here
first and renders only on a miss, as ccache compiles only what changed.

The key is a SHA-256 over every property of every data-block a render can read (objects, meshes, materials, node
groups, lights, worlds, images' pixels, cameras, scenes with their render settings, actions and drivers, ID
properties), walked through Blender's RNA, so a change anywhere in the scene is a miss; plus the Blender build,
the CPU, and the Python files of every package with a handler or a driver function registered (the add-on). A
property that changes from run to run without changing the picture (VOLATILE) is left out.

EEVEE is remembered where nothing it reads lies outside RNA: no light probe objects (their baked light is not in
RNA) and, in EEVEE Legacy, no baked light cache; keyed also by the OpenGL driver (gpu.platform, known once EEVEE
has rendered in the process: the first EEVEE render of a process is always made). What Blender prints while it
renders is remembered with the pixels and printed again (ctest fails EEVEE tests on "Shadow buffer full").

Opt-in, for tests only (benchmarks time their renders): PROBELIGHTS_RENDER_CACHE names the folder
(tests/CMakeLists.txt sets it to ~/.cache/probelights/renders for the render tier). PROBELIGHTS_RENDER_CACHE_VERIFY=1
renders every time and fails on a remembered render that differs by more than float rounding (the key missed
something): run the render tier once so after a change to this file. Only scenes whose files are images are
remembered (not volumes or caches read from disk).
"""

import glob
import hashlib
import inspect
import os
import platform
import sys

import bpy
import numpy as np

FOLDER = os.environ.get("PROBELIGHTS_RENDER_CACHE", "")
VERIFY = os.environ.get("PROBELIGHTS_RENDER_CACHE_VERIFY", "") == "1"
# PROBELIGHTS_RENDER_CACHE_DUMP=FILE writes what each key is made of, a line a value: two runs' files diffed show
# what changes between them when renders that should be remembered are not.
DUMP = open(os.environ["PROBELIGHTS_RENDER_CACHE_DUMP"], "w") if os.environ.get("PROBELIGHTS_RENDER_CACHE_DUMP") \
    else None
LIMIT_BYTES = 1 << 30  # the oldest renders go beyond this

# The data-block kinds a render reads (bpy.data's collections; those missing in a version are skipped).
KINDS = ("scenes", "objects", "meshes", "curves", "metaballs", "lattices", "armatures", "pointclouds", "hair_curves",
         "volumes", "particles", "materials", "node_groups", "textures", "images", "lights", "lightprobes",
         "cameras", "worlds", "collections", "actions")
# Properties that differ from run to run or hold paths, not the picture (an image's pixels stand for its path),
# and the scene's tool settings (the UI's, and large).
VOLATILE = {"rna_type", "session_uid", "is_evaluated", "original", "users", "is_dirty", "bindcode", "tag",
            "is_runtime_data", "preview", "has_data", "filepath", "filepath_raw", "is_missing", "tool_settings",
            "library_weak_reference", "is_library_indirect", "pixels", "depsgraph", "display",
            # a packed image's file (Blender 3.4 writes 512 bytes of its EXR differently each time): its pixels are
            "packed_file", "packed_files",
            # what Blender derives when it evaluates the scene (from the transforms and the parents walked)
            "matrix_world", "matrix_local", "dimensions", "bound_box",
            # the add-on's timings and its report of them
            "last_ms", "last_report", "last_ms_per_lamp", "bake_ms", "click_ms"}
# A mesh's own geometry, hashed by _Walk.mesh in an order of its own, and the attributes it reads.
MESH_GEOMETRY = {"vertices", "edges", "loops", "polygons", "loop_triangles", "loop_triangle_polygons", "attributes",
                 "uv_layers", "vertex_colors", "color_attributes", "polygon_normals", "vertex_normals",
                 "corner_normals", "normals_domain", "edge_creases", "vertex_creases", "skin_vertices",
                 "vertex_paint_mask", "polygon_layers_int", "polygon_layers_float", "polygon_layers_string",
                 "vertex_layers_int", "vertex_layers_float", "vertex_layers_string", "total_vert_sel",
                 "total_edge_sel", "total_face_sel", "uv_layer_clone", "uv_layer_stencil", "uv_layer_clone_index",
                 "uv_layer_stencil_index", "attributes_active", "active_attribute_name"}
MESH_ATTRIBUTES = {"position", ".edge_verts", ".corner_vert", ".corner_edge", "sharp_face", "material_index",
                   ".select_vert", ".select_edge", ".select_poly", "UVMap"}
BIG = 32  # a collection longer than this is hashed by its numeric arrays (foreach_get), not item by item

_counts = {"renders": 0, "reused": 0, "apart": 0.0}
VERIFY_BOUND = 1e-3  # mean |difference| / mean |pixel| of a remembered render and this one


class _NotRemembered(Exception):
    pass


class _Walk:
    def __init__(self):
        self.h = hashlib.sha256()
        self.seen = {}

    def feed(self, *parts):
        for p in parts:
            self.h.update(repr(p).encode())
            self.h.update(b"\0")
            if DUMP is not None:
                DUMP.write(repr(p) + "\n")

    def id_ref(self, value, depth=0):
        if getattr(value, "is_embedded_data", False):  # a world's or material's node tree: part of its owner
            self.struct(value, depth + 1)
        else:
            self.feed("ID", type(value).__name__, value.name_full)

    def data(self, a):
        self.h.update(a.tobytes())
        if DUMP is not None:
            DUMP.write("data %s %s\n" % (a.shape, hashlib.sha256(a.tobytes()).hexdigest()[:16]))

    def array(self, coll, prop, n):
        size = int(np.prod([d for d in prop.array_dimensions if d])) if getattr(prop, "array_length", 0) else 1
        dtype = {"FLOAT": np.float32, "INT": np.int32, "BOOLEAN": bool}[prop.type]
        a = np.empty(n * size, dtype)
        try:
            coll.foreach_get(prop.identifier, a)
        except (RuntimeError, TypeError, AttributeError):
            self.feed("unread", prop.identifier)
            return
        self.feed(prop.identifier, a.shape)
        self.data(a)

    def struct(self, s, depth=0):
        key = (s.as_pointer(), s.bl_rna.identifier)  # a struct may begin where its first member does
        if key in self.seen:  # a struct reached again: name it by when it was first reached
            self.feed("seen", self.seen[key])
            return
        self.seen[key] = len(self.seen)
        self.feed(type(s).__name__)
        if depth > 40:
            self.feed("deep")
            return
        is_mesh = isinstance(s, bpy.types.Mesh)
        if is_mesh and not self.mesh(s):
            raise _NotRemembered
        for prop in s.bl_rna.properties:
            name = prop.identifier
            if name in VOLATILE or (is_mesh and name in MESH_GEOMETRY):
                continue
            try:
                value = getattr(s, name)
            except (AttributeError, RuntimeError, TypeError, ValueError):
                self.feed(name, "unreadable")
                continue
            self.feed(name)
            if prop.type == "POINTER":
                if value is None:
                    self.feed(None)
                elif isinstance(value, bpy.types.ID):
                    self.id_ref(value, depth)
                else:
                    self.struct(value, depth + 1)
            elif prop.type == "COLLECTION":
                self.collection(value, prop, depth)
            elif prop.type in ("FLOAT", "INT", "BOOLEAN") and getattr(prop, "array_length", 0) > 16:
                self.data(np.array(value, np.float32 if prop.type == "FLOAT" else np.int32).ravel())
            elif hasattr(value, "__len__") and not isinstance(value, str):
                self.feed(tuple(value) if prop.type != "ENUM" else sorted(value))
            else:
                self.feed(value)
        if isinstance(s, bpy.types.ID):
            self.id_properties(s)

    def collection(self, coll, prop, depth):
        n = len(coll)
        self.feed("items", n)
        item = prop.fixed_type
        if n > BIG and not _is_id(item):
            for p in item.properties:
                if p.type in ("FLOAT", "INT", "BOOLEAN") and p.identifier not in VOLATILE:
                    self.array(coll, p, n)
            return
        for value in coll:
            if isinstance(value, bpy.types.ID):
                self.id_ref(value, depth)
            else:
                self.struct(value, depth + 1)

    def id_properties(self, block):
        try:
            items = sorted(block.items())
        except (TypeError, AttributeError):
            return
        registered = block.bl_rna.properties  # an add-on's registered properties: walked through RNA above
        for k, v in items:
            if k in VOLATILE or k in registered:
                continue
            v = v.to_dict() if hasattr(v, "to_dict") else (v.to_list() if hasattr(v, "to_list") else v)
            self.feed("idprop", k, _steady(v))

    def mesh(self, mesh):
        """A mesh's polygons as coordinates (with their loops' UVs, material and smoothness), in an order of their
        own: Blender numbers edges and loops differently from run to run (its edge calculation is threaded), the
        picture is the same. False for a mesh with attributes beyond those (not remembered)."""
        uv_names = {layer.name for layer in mesh.uv_layers}
        for attribute in mesh.attributes:
            name = attribute.name
            if not (name in MESH_ATTRIBUTES or name in uv_names or name.startswith((".vs.", ".es.", ".pn.", ".uv"))):
                return False
        n, loops = len(mesh.polygons), len(mesh.loops)
        co = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get("co", co)
        corner = np.empty(loops, np.int32)
        mesh.loops.foreach_get("vertex_index", corner)
        values = [co.reshape(-1, 3)[corner]]
        for layer in mesh.uv_layers:
            uv = np.empty(loops * 2, np.float32)
            layer.data.foreach_get("uv", uv)
            values.append(uv.reshape(-1, 2))
        per_loop = np.concatenate(values, axis=1) if loops else np.zeros((0, 3), np.float32)
        start, total = np.empty(n, np.int32), np.empty(n, np.int32)
        material, smooth = np.empty(n, np.int32), np.empty(n, bool)
        mesh.polygons.foreach_get("loop_start", start)
        mesh.polygons.foreach_get("loop_total", total)
        mesh.polygons.foreach_get("material_index", material)
        mesh.polygons.foreach_get("use_smooth", smooth)
        rows = []
        for i in range(n):
            corners = per_loop[start[i]:start[i] + total[i]]
            first = min(range(total[i]), key=lambda k: tuple(corners[k]))  # the winding kept
            rows.append(np.concatenate([[material[i], smooth[i]], np.roll(corners, -first, axis=0).ravel()])
                        .astype(np.float32).tobytes())
        self.feed("mesh", n, loops, sorted(uv_names))
        self.data(np.frombuffer(b"".join(sorted(rows)), np.uint8))
        return True

    def image_pixels(self, image):
        if image.type == "RENDER_RESULT" or image.source not in ("FILE", "GENERATED"):
            return False
        w, h = image.size[:]
        a = np.empty(w * h * image.channels, np.float32)
        image.pixels.foreach_get(a)
        self.feed("pixels", image.name_full, w, h, image.channels)
        self.data(a)
        return True


def _steady(value):
    """An ID property's value without its VOLATILE keys at any depth: an add-on's settings opened without the
    add-on are a plain group, its timings in it."""
    if isinstance(value, dict):
        return {k: _steady(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [_steady(v) for v in value]
    return value


def _is_id(rna):
    while rna is not None:
        if rna.identifier == "ID":
            return True
        rna = rna.base
    return False


def _cpu():
    if sys.platform.startswith("linux"):
        try:
            with open("/proc/cpuinfo") as f:
                lines = [l for l in f if l.startswith(("model name", "flags"))]
            return hashlib.sha256("".join(sorted(set(lines))).encode()).hexdigest()
        except OSError:
            pass
    return os.environ.get("PROCESSOR_IDENTIFIER", platform.processor())


def _render_time_code():
    """The Python files of every package whose functions run at render time: handlers and driver functions."""
    functions = [f for name in dir(bpy.app.handlers) if not name.startswith("_")
                 for f in (getattr(bpy.app.handlers, name) if isinstance(getattr(bpy.app.handlers, name), list)
                           else [])]
    functions += [f for f in bpy.app.driver_namespace.values() if callable(f)]
    folders = set()
    for f in functions:
        try:
            path = inspect.getsourcefile(f)
        except TypeError:
            continue
        if path:
            module = sys.modules.get(getattr(f, "__module__", ""), None)
            package = getattr(module, "__package__", "") or ""
            folder = os.path.dirname(path)
            if package and "." in getattr(module, "__name__", ""):
                folder = os.path.dirname(sys.modules[package].__file__) if package in sys.modules else folder
            folders.add(folder)
    folders = tuple(sorted(folders))
    if folders not in _code_digests:  # the files do not change while the tests run
        _code_digests[folders] = _digest_of(folders)
    return _code_digests[folders]


_code_digests = {}


def _digest_of(folders):
    digest = hashlib.sha256()
    for folder in folders:
        for path in sorted(glob.glob(os.path.join(folder, "**", "*.py"), recursive=True)):
            with open(path, "rb") as f:
                digest.update(os.path.relpath(path, folder).encode() + b"\0" + f.read())
    return digest.hexdigest()


EEVEE = ("BLENDER_EEVEE", "BLENDER_EEVEE_NEXT")


_eevee_rendered = []  # whether render_scene.render() made an EEVEE render in this process


def _gpu():
    """The OpenGL driver EEVEE renders with, or None before EEVEE rendered in this process: Blender opens no
    OpenGL context in background mode until then, and asking before crashes Blender 3.4 (measured, 3.4.1)."""
    if not _eevee_rendered:
        return None
    try:
        import gpu
        return (gpu.platform.vendor_get(), gpu.platform.renderer_get(), gpu.platform.version_get())
    except (ImportError, SystemError, AttributeError):
        return None


def _engine(scene):
    """What keys the engine's render beyond the data-blocks (the GPU's driver for EEVEE), or None when its render
    is not to be remembered: EEVEE with light probes (their baked light lies outside RNA), or EEVEE Legacy with a
    baked light cache (the scene's, outside RNA too)."""
    engine = scene.render.engine
    if engine == "CYCLES":
        return (engine,)
    if engine not in EEVEE or not sys.platform.startswith("linux"):  # (printing() keeps the output on Linux)
        return None
    if any(o.type == "LIGHT_PROBE" for o in bpy.data.objects):
        return None
    info = getattr(scene.eevee, "gi_cache_info", "")
    if info and not info.startswith("No light cache"):
        return None
    gpu = _gpu()
    return None if gpu is None else (engine,) + gpu


def key(scene):
    """The render's key, or None when it is not to be remembered."""
    engine = _engine(scene) if FOLDER else None
    if engine is None:
        return None
    # What the render would change before it renders (the add-on follows the engine and the world's strength
    # there): done first, so the key is of the scene rendered and a remembered render leaves the scene as a render
    # would. Those handlers are idempotent, as Blender calls them before every frame of an animation.
    for handler in list(bpy.app.handlers.render_pre):
        handler(scene, None)
    w = _Walk()
    w.feed(bpy.app.version_string, bpy.app.build_hash, getattr(bpy.app, "build_platform", b""), sys.platform,
           platform.machine(), _cpu(), _render_time_code(), scene.name_full)
    if engine != ("CYCLES",):  # (Cycles' keys are as they were before EEVEE was remembered)
        w.feed(engine)
    try:
        for kind in KINDS:
            blocks = getattr(bpy.data, kind, None)
            if blocks is None:
                continue
            w.feed(kind, len(blocks))
            for block in blocks:
                if kind == "images":
                    w.feed(block.name_full)
                    if not w.image_pixels(block) and block.type != "RENDER_RESULT":
                        return None  # a sequence, a movie: its pixels are the frame's
                elif getattr(block, "filepath", ""):
                    return None  # a volume or a cache: what it reads is not walked
                w.struct(block)
    except _NotRemembered:
        return None
    if DUMP is not None:
        DUMP.write("KEY %s\n" % w.h.hexdigest())
        DUMP.flush()
    return w.h.hexdigest()


def _path(k):
    return os.path.join(FOLDER, k[:2], k + ".npy")


def _printed_path(k):
    return os.path.join(FOLDER, k[:2], k + ".printed")


def lookup(k):
    """The remembered pixels of key `k`, or None. What Blender printed while it made them is printed again."""
    _counts["renders"] += 1
    if k is None:
        return None
    try:
        pixels = np.load(_path(k))
        printed = b""
        if os.path.exists(_printed_path(k)):
            with open(_printed_path(k), "rb") as f:
                printed = f.read()
    except (OSError, ValueError):
        return None
    os.utime(_path(k))  # the newest are kept
    _counts["reused"] += 1
    if printed and not VERIFY:
        sys.stdout.flush()
        os.write(sys.stdout.fileno(), printed)
    return pixels


def printing(k, render):
    """Calls render(); returns what the process printed meanwhile (Blender's C code prints past Python's
    sys.stdout), which goes on to the output too. Only for a remembered EEVEE render (what a test's ctest reads
    of it), on Linux; else b"" and the output is untouched."""
    eevee = bpy.context.scene.render.engine in EEVEE
    if k is None or not sys.platform.startswith("linux") or not eevee:
        render()
        if eevee:
            _eevee_rendered.append(True)
        return b""
    import ctypes
    import tempfile
    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    sys.stderr.flush()
    libc.fflush(None)
    saved = [os.dup(1), os.dup(2)]
    with tempfile.TemporaryFile() as f:
        os.dup2(f.fileno(), 1)
        os.dup2(f.fileno(), 2)
        try:
            render()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            libc.fflush(None)
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
        f.seek(0)
        printed = f.read()
    os.write(1, printed)
    _eevee_rendered.append(True)
    return printed


def store(k, pixels, remembered=None, printed=b""):
    """Remembers `pixels` under `k` whole (written beside, then renamed), with what Blender printed making them;
    with VERIFY, `remembered` (what lookup gave) must be the same render (within VERIFY_BOUND)."""
    if k is None:
        return
    if remembered is not None:
        # Cycles repeats a render to float rounding, not bit for bit (its BVH is built from meshes whose loops
        # Blender numbers differently from run to run, and a glossy path that rounds the other way goes elsewhere):
        # up to 1.6e-4 apart in test_render.py (4.5.15). The same scene with another seed is ~3e-2 apart.
        apart = float(np.mean(np.abs(remembered - pixels)) / max(float(np.mean(np.abs(pixels))), 1e-12))
        _counts["apart"] = max(_counts["apart"], apart)
        if apart > VERIFY_BOUND:
            raise AssertionError("render cache: a remembered render is %.2g apart from this one (key %s; bound %g):"
                                 " the key misses a property" % (apart, k[:12], VERIFY_BOUND))
        return
    path = _path(k)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if printed:  # before the pixels: remembered pixels always find their output
        tmp = "%s.%d.tmp" % (_printed_path(k), os.getpid())
        with open(tmp, "wb") as f:
            f.write(printed)
        os.replace(tmp, _printed_path(k))
    tmp = "%s.%d.tmp.npy" % (path, os.getpid())
    np.save(tmp, pixels)
    os.replace(tmp, path)
    _trim()


def _trim():
    files = [(os.path.getmtime(p), os.path.getsize(p), p) for p in glob.glob(os.path.join(FOLDER, "*", "*.npy"))]
    total = sum(size for _, size, _ in files)
    for _, size, p in sorted(files):
        if total <= LIMIT_BYTES:
            break
        try:
            os.remove(p)  # the pixels first: output without pixels is never read
            if os.path.exists(p[:-len(".npy")] + ".printed"):
                os.remove(p[:-len(".npy")] + ".printed")
        except OSError:
            pass
        total -= size


def report():
    """One line: how many renders were remembered (harness.run prints it at the end)."""
    if FOLDER and _counts["renders"]:
        print("render cache: %d of %d renders remembered from an earlier run%s" % (
            _counts["reused"], _counts["renders"], " (verified: at most %.2g apart)" % _counts["apart"] if VERIFY
            else ""), flush=True)
