"""The Bake animation operator: the panel's bake settings over a frame range, one frame a step (progress in the
status bar, Esc stops with nothing changed); the lamps are made and keyed once every frame is baked."""

import bpy

from .animation import AnimationBake, report_line
from .errors import ProbeError
from .modal_steps import ModalSteps
from .properties import SETTING_NAMES, bake_settings, from_panel, given_count


class PROBE_LIGHTS_OT_bake_animation(ModalSteps, bpy.types.Operator):
    """Bake a world that changes over time (an image sequence, an animated sky, keyframed world nodes) frame by
    frame into lamps that keep their identity, keyframed on every frame of the scene's range. Esc stops"""

    bl_idname = "probe_lights.bake_animation"
    bl_label = "Bake animation"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = {
        **bake_settings(),
        "smoothness": bpy.props.FloatProperty(
            name="Smoothness", default=0.1, min=0.0, max=100.0,
            description="How much more error a frame may keep to keep its lamps still: 0 cuts every frame anew, "
                        "more keeps the last frame's cuts longer"),
        "exact_energy": bpy.props.BoolProperty(
            name="Exact energy", default=True,
            description="Every frame's lamps carry exactly its world's light, so brightness follows the world. Off: "
                        "Refit may trade a few percent of it for closer shading and shadows, as a single bake does"),
        "frame_start": bpy.props.IntProperty(name="Start", default=0, description="First frame (0: the scene's)"),
        "frame_end": bpy.props.IntProperty(name="End", default=0, description="Last frame (0: the scene's)"),
    }

    def _begin(self, context):
        given_count(self)
        self._bake = AnimationBake(context, self, self.smoothness, self.frame_start, self.frame_end,
                                   exact_energy=self.exact_energy)

    def execute(self, context):
        try:
            self._begin(context)
            try:
                while not self._bake.step():
                    pass
            except ProbeError:
                self._bake.close()
                raise
            return self._finish(context)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}

    def invoke(self, context, event):
        from_panel(self, context.scene.probe_lights)
        if context.window is None:
            return self.execute(context)
        try:
            self._begin(context)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return self._start_steps(context, self._bake.total)

    def _status_text(self):
        return "Baking animation: %d of %d frames (Esc stops, nothing changes)" % (len(self._bake.frames),
                                                                                 self._bake.total)

    def modal(self, context, event):
        if event.type == "ESC":
            self._end(context)
            self._bake.close()
            self.report({"WARNING"}, "Bake animation stopped after %d of %d frames: nothing changed" % (
                len(self._bake.frames), self._bake.total))
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            done = self._bake.step()
        except ProbeError as e:
            self._end(context)
            self._bake.close()
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self._show_progress(context, len(self._bake.frames))
        if not done:
            return {"RUNNING_MODAL"}
        self._end(context)
        try:
            return self._finish(context)
        except ProbeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}

    def _finish(self, context):
        summary = self._bake.finish(context)
        settings = context.scene.probe_lights
        for name in SETTING_NAMES:
            setattr(settings, name, getattr(self, name))
        settings.last_count = summary["count"]
        settings.last_source = summary["source"]
        settings.last_notes = "\n".join(summary["notes"])
        settings.last_warnings = "\n".join(summary["warnings"])
        settings.last_diffuse_error = settings.last_shadow_error = -1.0
        line = report_line(summary)
        for w in summary["warnings"]:
            self.report({"WARNING"}, w)
        self.report({"WARNING"} if summary["warnings"] else {"INFO"}, line)
        settings.last_report = line
        return {"FINISHED"}


classes = (PROBE_LIGHTS_OT_bake_animation,)
