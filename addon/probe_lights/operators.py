"""Operators: pass the panel's settings to bake.py and report what happened, on one line plus one WARNING report
per warning."""

import time

import bpy

from . import cycles_settings, eevee_settings, native, probe_volumes
from .animation import AnimationBake, frame_range, world_motion
from .bake import RENDER_WIDTH, bake_world, needs_render, report_lines, restore_world, world_probe
from .blender_caps import has_eevee_next, preset, sun_profile
from .errors import ProbeError
from .modal_steps import ModalSteps
from .properties import SETTING_NAMES, bake_settings, cut_method, from_panel, given_count
from .world_image import WorldRender

TRADEOFF_COUNTS = [4, 8, 16, 32, 64, 128, 256]
LAMP_MS = 0.3  # making one lamp with its drivers: a first guess, until a bake has timed it


class PROBE_LIGHTS_OT_bake(bpy.types.Operator):
    """Turn the world's light into lamps that light the scene the same way; the world keeps only what it still shows"""

    bl_idname = "probe_lights.bake"
    bl_label = "Bake probe to lights"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = bake_settings()

    def invoke(self, context, event):
        # From a button: start from the panel's settings, except what the caller set explicitly.
        from_panel(self, context.scene.probe_lights)
        world = context.scene.world
        if world is None or context.window is None or not needs_render(world):
            return self.execute(context)
        # A world that has to be rendered first (Sky Texture, ...): Blender's render job, with its progress in the
        # status bar and Esc to cancel; the bake follows when it completes.
        self._render = WorldRender(world, RENDER_WIDTH)
        self._started = time.perf_counter()
        self._render.start(context)
        if self._render.state() != "running":
            self._render.close()
            self.report({"ERROR"}, "could not start rendering the world")
            return {"CANCELLED"}
        self._timer = context.window_manager.event_timer_add(0.1, window=context.window)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC" and event.value == "PRESS":
            # Blender's own Esc stops the render job; the bake is called off whether or not it did.
            self._called_off = True
            return {"RUNNING_MODAL"}
        state = self._render.state()
        # "done" comes from render_complete, before Blender has ended its render job: until it has, nothing may
        # change data (the render's scene is still in use), so the bake waits for the job's end.
        if state == "running" or (hasattr(bpy.app, "is_job_running") and bpy.app.is_job_running("RENDER")):
            return {"PASS_THROUGH"}
        context.window_manager.event_timer_remove(self._timer)
        try:
            if state != "done" or getattr(self, "_called_off", False):
                self.report({"WARNING"}, "Bake cancelled while rendering the world: nothing changed")
                return {"CANCELLED"}
            pixels = self._render.pixels()
        finally:
            self._render.close()
        return self._bake(context, pixels, 1000 * (time.perf_counter() - self._started))

    def execute(self, context):
        return self._bake(context)

    def _bake(self, context, rendered=None, render_ms=0.0):
        given_count(self)
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            summary = bake_world(context, self, progress=lambda f: wm.progress_update(int(100 * f)),
                                 rendered=rendered, render_ms=render_ms)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        settings = context.scene.probe_lights
        for name in SETTING_NAMES:
            setattr(settings, name, getattr(self, name))
        settings.last_count = summary["count"]
        settings.last_energy = summary["energy"]
        settings.last_ms = summary["ms"]
        settings.last_source = summary["source"]
        settings.last_notes = "\n".join(summary["notes"])
        settings.last_warnings = "\n".join(summary["warnings"])
        settings.last_diffuse_error = summary["diffuse_error"]
        settings.last_shadow_error = summary["shadow_error"]
        if summary["count"]:
            settings.last_ms_per_lamp = summary["timings"]["lamps"] / summary["count"]
        for kind, text in report_lines(summary):
            self.report({kind}, text)
        settings.last_report = text
        return {"FINISHED"}


class PROBE_LIGHTS_OT_tradeoff(ModalSteps, bpy.types.Operator):
    """Measure what accuracy costs: bake the world with 4 to 256 lights (with and without the refit) and show each
    count's time for a whole click and estimated diffuse and shadow error; nothing in the scene changes. Esc stops"""

    bl_idname = "probe_lights.tradeoff"
    bl_label = "Measure tradeoff"
    bl_options = {"REGISTER"}

    def _start(self, context):
        settings = context.scene.probe_lights
        start = time.perf_counter()
        self._probe = world_probe(context.scene.world)
        self._probe_ms = 1000 * (time.perf_counter() - start)
        self._lamp_ms = settings.last_ms_per_lamp or LAMP_MS
        self._method = cut_method(settings.method)  # the tradeoff measures one cut a count
        self._done = 0
        settings.tradeoff.clear()
        settings.tradeoff_method = self._method
        settings.tradeoff_source = self._probe[2]
        settings.tradeoff_frames = 0

    def _step(self, context):
        """Measures the next count; True when all are done."""
        n = TRADEOFF_COUNTS[self._done]
        pixels, projection = self._probe[0], self._probe[1]
        # Each row made and judged as the bake makes them (the core's preset for this engine), at one count.
        rows = native.tradeoff(pixels, projection=projection, counts=[n], methods=[self._method],
                               resolutions=["auto"], preset=preset(context.scene.render.engine, bpy.app.version),
                               sun_profile=sun_profile(bpy.app.version))["rows"]
        for i in range(len(rows["lights"])):
            row = context.scene.probe_lights.tradeoff.add()
            row.lights, row.refit, row.bake_ms = int(rows["lights"][i]), bool(rows["refit"][i]), rows["bake_ms"][i]
            row.click_ms = self._probe_ms + row.bake_ms + row.lights * self._lamp_ms
            row.diffuse, row.shadow = rows["diffuse"][i], rows["shadow"][i]
        self._done += 1
        return self._done == len(TRADEOFF_COUNTS)

    def _finish(self, context, stopped=False):
        if not stopped:
            self._measure_animation(context)
        self.report({"INFO"}, "Measured %d light counts of %s%s" % (
            self._done, self._probe[2], " (stopped)" if stopped else ""))

    def _measure_animation(self, context):
        """For a world that changes over time, what Bake animation would cost at the panel's count: the scene's
        frame read (or rendered) beside its bake, timed on the current frame as Bake animation makes it."""
        scene, settings = context.scene, context.scene.probe_lights
        if world_motion(scene.world) is None:
            return
        frame = scene.frame_current
        try:
            first, last = frame_range(scene, 0, 0)
            bake = AnimationBake(context, settings, start=frame, end=frame)
        except ProbeError:
            return  # (a range, count or method Bake animation refuses: it says why when clicked)
        try:
            bake.step()
        except ProbeError:
            return
        finally:
            bake.close()
        settings.tradeoff_frames, settings.tradeoff_frame_lights = last - first + 1, bake.options["lights"]
        settings.tradeoff_frame_read_ms = 1000 * bake.read_s
        settings.tradeoff_frame_bake_ms = 1000 * bake.bake_s
        settings.tradeoff_frames_rendered = bake.frames_source.kind == "render"

    def execute(self, context):
        try:
            self._start(context)
            while not self._step(context):
                pass
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self._finish(context)
        return {"FINISHED"}

    def invoke(self, context, event):
        try:
            self._start(context)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return self._start_steps(context, len(TRADEOFF_COUNTS))

    def _status_text(self):
        return "Measuring tradeoff: %d of %d light counts done (Esc stops)" % (self._done, len(TRADEOFF_COUNTS))

    def modal(self, context, event):
        if event.type == "ESC":
            self._end(context)
            self._finish(context, stopped=True)
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            done = self._step(context)
        except ProbeError as e:
            self._end(context)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self._show_progress(context, self._done)
        if done:
            self._end(context)
            self._finish(context)
            return {"FINISHED"}
        return {"RUNNING_MODAL"}


class PROBE_LIGHTS_OT_set_count(bpy.types.Operator):
    """Use this many lights"""

    bl_idname = "probe_lights.set_count"
    bl_label = "Use this count"
    bl_options = {"REGISTER", "UNDO", "INTERNAL"}
    count: bpy.props.IntProperty(min=1, max=4096)

    def execute(self, context):
        settings = context.scene.probe_lights
        settings.count = self.count
        settings.count_mode = "COUNT"
        return {"FINISHED"}


class PROBE_LIGHTS_OT_restore(bpy.types.Operator):
    """Remove a world's baked lights and bring the world back exactly as it was before the bake (and the Cycles
    settings the add-on set, once no baked world is left)"""

    bl_idname = "probe_lights.restore"
    bl_label = "Restore world"
    bl_options = {"REGISTER", "UNDO"}
    world: bpy.props.StringProperty(name="World", description="The world to restore (default: the scene's)")

    def execute(self, context):
        scene = context.scene
        world = bpy.data.worlds.get(self.world) if self.world else scene.world
        if world is None:
            self.report({"ERROR"}, "no world named '%s'" % self.world if self.world else "the scene has no world")
            return {"CANCELLED"}
        done = restore_world(scene, world)
        if world == scene.world:
            scene.probe_lights.last_count = 0
            scene.probe_lights.last_warnings = scene.probe_lights.last_notes = ""
        if not done:
            self.report({"INFO"}, "Nothing to restore: world '%s' was not baked" % world.name)
        else:
            self.report({"INFO"}, done[0].upper() + done[1:])
        return {"FINISHED"}


class PROBE_LIGHTS_OT_cycles_settings(bpy.types.Operator):
    """Set what the baked lamps need in Cycles: indirect clamp 0 (the default of 10 darkens their bounce light) and
    the light tree where Blender has one; Restore world puts the old values back"""

    bl_idname = "probe_lights.cycles_settings"
    bl_label = "Use Cycles settings for lamps"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        changed = cycles_settings.apply(context.scene)
        if changed:
            self.report({"INFO"}, "Cycles: set %s (Restore world puts them back)" % ", ".join(
                {"sample_clamp_indirect": "indirect clamp 0", "use_light_tree": "light tree on"}[c] for c in changed))
        else:
            self.report({"INFO"}, "Cycles settings already suit the lamps")
        return {"FINISHED"}


class PROBE_LIGHTS_OT_eevee_settings(bpy.types.Operator):
    """Give EEVEE's shadow pool room for every baked sun (a full pool drops shadows at random): the smallest pool
    that holds them, at half or a quarter shadow resolution if even the largest cannot; Restore world puts the old
    values back"""

    bl_idname = "probe_lights.eevee_settings"
    bl_label = "Fit EEVEE shadows to the lamps"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        changed = eevee_settings.apply(context.scene)
        if changed:
            self.report({"INFO"}, "EEVEE: set %s (Restore world puts them back)" % eevee_settings.describe(changed))
        else:
            self.report({"INFO"}, "EEVEE's shadow pool already holds the lamps")
        return {"FINISHED"}


class PROBE_LIGHTS_OT_eevee_ray_tracing(bpy.types.Operator):
    """Turn on EEVEE's ray tracing and, where something in the scene reflects, add a light probe sphere around it:
    its Fast GI bounces the lamps' light from what is on screen (up to Blender 5.1 closest to Cycles alone, from
    5.2 with a light probe volume), the sphere reflects the lit scene where the screen cannot; Restore world takes
    both back"""

    bl_idname = "probe_lights.eevee_ray_tracing"
    bl_label = "Use EEVEE ray tracing and reflections"
    bl_options = {"REGISTER", "UNDO"}

    ray_tracing: bpy.props.BoolProperty(
        name="Ray tracing", default=True, options={"SKIP_SAVE"},
        description="Turn on EEVEE's ray tracing too (off: the light probe sphere alone)")

    @classmethod
    def poll(cls, context):
        return context.scene is not None and eevee_settings.eevee_next(context.scene)

    def execute(self, context):
        scene = context.scene
        done = ["ray tracing on"] if self.ray_tracing and eevee_settings.use_ray_tracing(scene) else []
        nothing = ""
        if probe_volumes.wants_sphere(scene):  # (so the scene has objects for fit_sphere)
            probe_volumes.fit_sphere(scene)
            done.append("a light probe sphere around the scene")
        elif not probe_volumes.sphere_probes(scene):  # it would change nothing and slow the render
            nothing = "no light probe sphere: nothing in the scene reflects"
        if done:
            self.report({"INFO"}, "EEVEE: %s (Restore world takes it back)%s" % (
                " and ".join(done), "; " + nothing if nothing else ""))
        else:
            self.report({"INFO"}, "EEVEE: ray tracing on; %s" % (nothing or "a light probe sphere already"))
        return {"FINISHED"}


class PROBE_LIGHTS_OT_bake_light_probes(bpy.types.Operator):
    """Bake EEVEE's light probe volumes with the baked suns: the shadow pool made room for the bake, and past what
    the largest holds, the bake sees the brightest suns carrying the others' light; all put back after"""

    bl_idname = "probe_lights.bake_light_probes"
    bl_label = "Bake light probes with the lamps"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        scene = context.scene
        return (has_eevee_next(bpy.app.version) and scene is not None  # EEVEE Next's bake
                and bool(probe_volumes.volume_probes(scene) or probe_volumes.offer(scene)))

    def execute(self, context):
        scene = context.scene
        fitted = None
        if not probe_volumes.volume_probes(scene):  # none yet: one around the scene (Restore removes it)
            try:
                fitted = probe_volumes.fit_volume(scene)
            except ValueError as e:
                self.report({"ERROR"}, str(e))
                return {"CANCELLED"}
        start = time.perf_counter()
        try:
            suns, seen = probe_volumes.bake(context)
        except RuntimeError as e:
            if fitted is not None:  # a failed bake leaves the scene as it was
                probe_volumes.remove_fitted(fitted)
            self.report({"ERROR"}, "Light probe bake failed: %s" % str(e).strip().splitlines()[-1])
            return {"CANCELLED"}
        seconds = time.perf_counter() - start
        probe_volumes.remember(scene, seconds)
        merged = " (as %d for their shadows in the bake)" % seen if seen < suns else ""
        added = "Added a light probe volume around the scene and baked it" if fitted else (
            "Baked %d light probe volumes" % len(probe_volumes.volume_probes(scene)))
        self.report({"INFO"}, "%s with %d suns%s in %.1f s" % (added, suns, merged, seconds))
        return {"FINISHED"}


classes = (PROBE_LIGHTS_OT_bake, PROBE_LIGHTS_OT_restore, PROBE_LIGHTS_OT_tradeoff, PROBE_LIGHTS_OT_set_count,
           PROBE_LIGHTS_OT_cycles_settings, PROBE_LIGHTS_OT_eevee_settings, PROBE_LIGHTS_OT_eevee_ray_tracing,
           PROBE_LIGHTS_OT_bake_light_probes)
