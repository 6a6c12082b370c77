"""Bake animation: a world whose light changes over time, baked frame by frame into one rig of lamps that keep
their identity, their direction, colour, strength and angle keyframed on every frame.

    world --frame_source--> frame f's pixels: an image sequence's file for f (read as Blender reads the image), or
                            the world rendered at f (Sky Texture, keyframed or driven nodes, a movie)
          --native SequenceBaker.add--> the same N lights every frame, light k the same light (sequence.h: cuts
                            warm-started from the last frame's, lights matched by a minimum-cost assignment)
          --make_lights (frame 1) + keyframes--> lamp k carries light k on every frame

What the lamps already follow by drivers (the Background strength, one Mapping node's rotation) is followed the
same way here, so only the probe's pixels are baked per frame.
"""

import math
import time
from concurrent.futures import ThreadPoolExecutor

import bpy
import numpy as np
from mathutils import Matrix, Vector

from . import light_kinds, native
from .blender_caps import sun_cones, sun_profile
from .conversion import point_parameters, sun_parameters, sun_strength
from .errors import ProbeError
from .lamp_keys import ENERGY_KEY, drive_energy_by_key
from .light_objects import make_lights
from .properties import NATIVE_SUN_ANGLES, cut_method, light_count
from .bake import finish_world, world_source
from .world_graph import ProbeSource
from .world_image import WorldRender, sequence_pixels

# Lat-long width an animated world without an image sequence is rendered at, a frame: a single bake's
# (bake.RENDER_WIDTH). At 512 a Sky Texture's sun is a pixel or two, and its fitted angle and the renders of a
# sky day jumped from frame to frame (docs/results/sequences.md: 6.6 % from the world, jitter 3.2).
RENDER_WIDTH = 1024
MAX_FRAMES = 100000
# A key's interpolation, as foreach_set takes it (the enum's value: CONSTANT 0, LINEAR 1, BEZIER 2).
LINEAR = 1


def _fcurves(animation_data):
    """The F-curves an ID's action holds for that ID. From 4.4 an action is layered and may hold several IDs'
    curves, each ID's under its own slot (a lamp's object and its light data share one action): they are
    reached through the ID's slot. Before 4.4 only action.fcurves exists. 4.4 and 4.5 also keep action.fcurves,
    but it gives only the first slot's curves (measured in bpy 4.2.23, 4.5.15 and 5.3.0)."""
    action = animation_data.action if animation_data is not None else None
    if action is None:
        return []
    try:
        from bpy_extras.anim_utils import action_get_channelbag_for_slot
    except ImportError:
        return list(action.fcurves)
    bag = action_get_channelbag_for_slot(action, animation_data.action_slot)
    return list(bag.fcurves) if bag is not None else []


def animated_paths(tree, seen=None):
    """The data paths of a node tree (and the node groups in it) that keyframes or drivers change over time."""
    seen = set() if seen is None else seen
    if tree is None or tree in seen:
        return []
    seen.add(tree)
    ad = tree.animation_data
    paths = [d.data_path for d in ad.drivers] + [f.data_path for f in _fcurves(ad)] if ad is not None else []
    for node in tree.nodes:
        if node.bl_idname == "ShaderNodeGroup":
            paths += ["%s: %s" % (node.name, p) for p in animated_paths(node.node_tree, seen)]
    return paths


def _followed(source):
    """The paths the lamps of a single bake follow by drivers (the Background strength, one Mapping rotation)."""
    return {s.path_from_id("default_value") for s in (source.strength_socket, source.rotation_socket)
            if s is not None}


def _motion(world):
    """(source, kind, changing) of a world whose light changes over time: kind "files" for an image sequence, else
    "render" (keyframed or driven world nodes, a Sky Texture's, a movie: `changing` says which). ProbeError for no
    world, a world without a probe, or one that does not change over time."""
    source = world_source(world)
    image = source.image
    changing = sorted(set(animated_paths(world.node_tree)) - (_followed(source) if image else set()))
    if image is not None and image.source == "SEQUENCE" and not changing:
        return source, "files", changing
    if world.animation_data is not None and (world.animation_data.drivers or _fcurves(world.animation_data)):
        changing.append("world")
    if image is not None and image.source == "MOVIE":
        changing.append("movie")
    if not changing:
        follows = " (the lamps follow its strength and rotation)" if image is not None else ""
        raise ProbeError("world '%s' does not change over time%s: use Bake probe to lights" % (world.name, follows))
    return source, "render", changing


def world_motion(world):
    """How Bake animation gets the world's frames: "files" (an image sequence's), "render" (the world rendered at
    each frame) or None (a world it would refuse)."""
    try:
        return _motion(world)[1]
    except ProbeError:
        return None


class FrameSource:
    """Where frame f's probe comes from: an image sequence's files (read through Blender, so its colour space
    counts), or the world rendered at frame f by a panoramic Cycles camera (on a copy of the world)."""

    def __init__(self, world, render_width=None):
        self.source, self.kind, changing = _motion(world)
        image = self.source.image
        self._render = None
        self.projection = self.source.projection if image is not None else "latlong"
        if self.kind == "files":
            self.described = "image sequence '%s'" % image.name
            return
        self.described = "world rendered each frame (%s)" % ("a movie" if "movie" in changing else
                                                             "animated: " + ", ".join(changing[:2]))
        # The rendered frames carry the whole world: strength and rotation are in the pixels, not followed.
        self.source = ProbeSource(render_reason="animated")
        self._render = WorldRender(world, render_width or RENDER_WIDTH)

    def pixels(self, frame):
        """Frame `frame`'s probe, float32 H x W x C."""
        if self.kind == "render":
            return self._render.render(frame)
        return sequence_pixels(self.source.image_node, frame)

    def close(self):
        if self._render is not None:
            self._render.close()
            self._render = None


def sequence_options(scene, settings, smoothness, exact_energy=True):
    """The core's SequenceBaker options for the panel's settings: each frame finished as a single bake is (the
    angles as Shadows says, the refit of colours and directions with Refit, at the core's sequence price; the
    refit keeping every frame's energy exact unless `exact_energy` is off), its cuts by variance or median cut
    (Auto and Both cut by variance: a sequence keeps one cut)."""
    method = cut_method(settings.method)
    if method not in ("variance", "median-cut"):
        raise ProbeError("Bake animation cuts by variance or median cut: set Method to one of them")
    soft = light_kinds.kind(settings.light_type).soft
    return {"lights": light_count(settings, scene.render.engine), "method": method, "resolution": settings.resolution,
            "sun_angles": NATIVE_SUN_ANGLES[settings.shadows] if soft else "points",
            "sun_cones": sun_cones(scene.render.engine, bpy.app.version),
            "sun_profile": sun_profile(bpy.app.version), "refit": bool(settings.refit),
            "move_directions": bool(settings.refit), "nonfinite": settings.non_finite,
            "smoothness": smoothness, "exact_energy": bool(exact_energy)}


def frame_range(scene, start, end):
    """(first, last) frame to bake: the given ones, or the scene's range where 0."""
    first, last = start or scene.frame_start, end or scene.frame_end
    if last < first:
        raise ProbeError("the frame range %d-%d ends before it starts" % (first, last))
    if last - first + 1 > MAX_FRAMES:
        raise ProbeError("%d frames: Bake animation takes at most %d" % (last - first + 1, MAX_FRAMES))
    return first, last


def keyframe_lamps(lamps, frames, kind, distance):
    """Keys lamp k with light k of every frame: location and rotation (each key the last one turned by the
    shortest arc to the new direction, so between frames a sun sweeps the great circle), colour, strength (before
    the world's strength: ENERGY_KEY when the energy follows the Strength by a driver) and a sun's angle. A dark
    light keeps its direction and colour."""
    version = bpy.app.version
    numbers = [f for f, _ in frames]
    for k, obj in enumerate(lamps):
        obj.rotation_mode = "QUATERNION"
        radius = obj.location.length
        data = obj.data
        driven = data.animation_data is not None and any(d.data_path == "energy" for d in data.animation_data.drivers)
        if driven:
            drive_energy_by_key(data, ENERGY_KEY)
        keys = {"location": [], "rotation_quaternion": [], "angle": [], "color": [], "energy": []}
        last_q = last_d = last_colour = None
        for _, frame in frames:
            direction = frame["lights"]["direction"][k]
            rgb = frame["lights"]["rgb"][k]
            if kind.soft:
                d = Vector(tuple(direction)).normalized()
                if last_q is None:
                    p = sun_parameters(direction, rgb, frame["lights"]["angle"][k], version)
                    q = Matrix(p["rotation"].tolist()).to_quaternion()
                else:  # the last key turned by the shortest arc: between keys the sun sweeps the great circle
                    p = sun_strength(rgb, frame["lights"]["angle"][k], version)
                    q = last_d.rotation_difference(d) @ last_q
                last_q, last_d = q, d
                keys["location"].append(tuple(radius * d))
                keys["rotation_quaternion"].append(tuple(q))
                keys["angle"].append(p["angle"])
            else:
                p = point_parameters(direction, rgb, distance)
                keys["location"].append(p["location"])
            last_colour = p["color"] if p["energy"] > 0 or last_colour is None else last_colour
            keys["color"].append(tuple(last_colour))
            keys["energy"].append(p["energy"])
        key_values(obj, "location", numbers, keys["location"])
        if kind.soft:
            key_values(obj, "rotation_quaternion", numbers, keys["rotation_quaternion"])
            key_values(data, "angle", numbers, keys["angle"])
        key_values(data, "color", numbers, keys["color"])
        key_values(data, '["%s"]' % ENERGY_KEY if driven else "energy", numbers, keys["energy"])


def key_values(owner, path, numbers, values):
    """Keys `owner`'s property `path` with values[i] on frame numbers[i], straight between frames (sampled light:
    no overshoot). The first key is inserted as Blender inserts one (which makes the action, its slot and the
    F-curves in every version); the others are written into the F-curves whole (keyframe_insert a key at a time
    took 0.3 s of a 48-frame bake at 64 lamps). The property is left at the first frame's value."""
    values = np.asarray(values, dtype=np.float64).reshape(len(numbers), -1)
    first = values[0].tolist()
    if path.startswith('["'):
        owner[path[2:-2]] = first[0]
    else:
        setattr(owner, path, first[0] if values.shape[1] == 1 else first)
    owner.keyframe_insert(path, frame=numbers[0])
    curves = {f.array_index: f for f in _fcurves(owner.animation_data) if f.data_path == path}
    co = np.empty((len(numbers), 2), dtype=np.float64)
    co[:, 0] = numbers
    for i in range(values.shape[1]):
        curve = curves[i]
        points = curve.keyframe_points
        points.add(len(numbers) - len(points))
        co[:, 1] = values[:, i]
        points.foreach_set("co", co.ravel())
        points.foreach_set("interpolation", [LINEAR] * len(numbers))
        curve.update()


class AnimationBake:
    """A sequence bake in steps (an operator's timer runs one frame a step; Esc stops between steps): nothing in
    the scene changes until finish()."""

    def __init__(self, context, settings, smoothness=0.1, start=0, end=0, render_width=None, exact_energy=True):
        scene = context.scene
        self.settings = settings
        self.first, self.last = frame_range(scene, start, end)
        self.options = sequence_options(scene, settings, smoothness, exact_energy)
        m = native.module()
        try:
            self.baker = m.SequenceBaker(**self.options)
        except m.Error as e:
            raise ProbeError(native.in_panel_words(e)) from None
        self.frames_source = FrameSource(scene.world, render_width)
        self.warnings = []
        if settings.lamps_take == "SOURCES":
            self.warnings.append("Bake animation: the lamps take all of the light (a residual world does not move)")
        if settings.count_mode == "TOLERANCE":
            self.warnings.append("Bake animation makes the Count's %d lamps (Max error is for single bakes)"
                                 % self.options["lights"])
        self.next = self.first
        self.frames = []
        # Reading and baking overlap: wall_s is the time from the first step to the last frame baked.
        self.read_s = self.bake_s = self.wall_s = 0.0
        self._started = self._worker = self._pending = None

    @property
    def total(self):
        return self.last - self.first + 1

    def step(self):
        """Reads the next frame and sets it baking on a thread of its own while the frame after it is read (the
        core lets go of Python while it bakes); True when every frame is baked."""
        t0 = time.perf_counter()
        if self._started is None:
            self._started = t0
        pixels = self.frames_source.pixels(self.next)
        self.read_s += time.perf_counter() - t0
        self._collect()
        if self._worker is None:
            self._worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="probe_lights_bake")
        self._pending = (self.next, self._worker.submit(self._bake_frame, pixels, self.next))
        self.next += 1
        if self.next > self.last:
            self._collect()
            self.wall_s = time.perf_counter() - self._started
            return True
        return False

    def _bake_frame(self, pixels, number):
        return self.baker.add(pixels, projection=self.frames_source.projection, frame=number)

    def _collect(self):
        """Waits for the frame baking, if any, and keeps it."""
        if self._pending is None:
            return
        number, future = self._pending
        self._pending = None
        m = native.module()
        try:
            frame = future.result()
        except m.Error as e:
            raise ProbeError("frame %d: %s" % (number, native.in_panel_words(e))) from None
        # The core's own time (the thread's would count its wait for Python's lock, held between the modal
        # operator's steps).
        self.bake_s += sum(frame["timings_ms"].values()) / 1000
        self.frames.append((number, frame))

    def close(self):
        """Waits for the frame baking (a frame's bake cannot be stopped half-way), then lets go of the thread and
        of what the frames were read or rendered with."""
        if self._worker is not None:
            self._worker.shutdown(wait=True)
            self._worker = None
        self._pending = None
        self.frames_source.close()

    def finish(self, context):
        """Makes the lamps from the first frame and keys every frame; returns the summary."""
        self.close()
        scene, settings = context.scene, self.settings
        t0 = time.perf_counter()
        kind = light_kinds.kind(settings.light_type)
        source = self.frames_source.source
        lamps = make_lights(scene, scene.world, self.frames[0][1], source, settings.light_type, settings.distance,
                            lights_diffuse=settings.replace_diffuse, lights_glossy=settings.replace_reflections)
        keyframe_lamps(lamps, self.frames, kind, settings.distance)
        notes, warnings = finish_world(context, settings, lamps, source, residual=None)
        # The core's warnings (a refit past its limit, ...), each once however many frames gave it.
        said = {n["text"] for _, f in self.frames for n in f["notes"] if n["kind"] == "warning"}
        warnings = self.warnings + sorted(said) + warnings
        keys_s = time.perf_counter() - t0
        motion = [f["motion"] for _, f in self.frames[1:]]
        recut = sum(1 for _, f in self.frames[1:] if f["recut"])
        return {"count": len(lamps), "frames": len(self.frames), "source": self.frames_source.described,
                "first": self.first, "last": self.last, "recut": recut,
                "motion_deg": math.degrees(float(np.mean(motion))) if motion else 0.0,
                "read_s": self.read_s, "bake_s": self.bake_s, "wall_s": self.wall_s, "keys_s": keys_s,
                "notes": notes,
                "warnings": warnings}


def report_line(summary):
    s = summary
    # Reading a frame and baking the one before it overlap: the time is the wall's, not the stages' sum.
    return ("Baked frames %d-%d of %s into %d lights in %.2f s (%s %.2f s beside bake %.2f s, keys %.2f s); lamps "
            "move %.1f degrees a frame, %d of %d frames cut afresh" % (
                s["first"], s["last"], s["source"], s["count"], s["wall_s"] + s["keys_s"],
                "render" if "rendered" in s["source"] else "read", s["read_s"], s["bake_s"], s["keys_s"],
                s["motion_deg"], s["recut"], s["frames"]))

