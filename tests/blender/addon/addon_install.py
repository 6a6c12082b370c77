"""Installed as a user installs it: another platform's zip refused with the installed one kept, and the panel drawn
at its default widths."""

import glob
import os
import sys

import bpy

import harness
from addon_common import ARGS, bake


class RecordingLayout:
    """Stands in for a panel's layout in background mode (no window): records labels, props and operators."""

    def __init__(self, log):
        self.log, self.enabled, self.scale_y = log, True, 1.0

    def _child(self, *args, **kwargs):
        return RecordingLayout(self.log)

    column = row = box = split = _child

    def label(self, text="", icon="NONE"):
        self.log.append(("label", text))

    def prop(self, data, name, **kwargs):
        assert hasattr(data, name), name
        self.log.append(("prop", name))

    def operator(self, idname, **kwargs):
        module, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, module), name), idname
        self.log.append(("operator", idname))
        return type("Props", (), {})()


def test_another_platforms_zip_is_refused_and_the_installed_one_kept():
    """Each zip names its one platform (addon/package.cmake): Blender 4.2+ refuses another platform's zip, and the
    add-on already installed stays as it was, enabled, with its own modules."""
    if bpy.app.version < (4, 2, 0):
        print("  skipped: Blender %s installs legacy add-ons, which name no platform" % bpy.app.version_string)
        return
    here = "windows_x64" if sys.platform == "win32" else "linux_x64"
    other = "linux_x64" if here == "windows_x64" else "windows_x64"
    wrong = ARGS.zip.replace("-%s.zip" % here, "-%s.zip" % other)
    if wrong == ARGS.zip or not os.path.exists(wrong):
        print("  skipped: no %s zip beside %s" % (other, ARGS.zip))
        return
    package = os.path.dirname(harness.addon_module("native").__file__)
    modules = lambda: sorted(os.path.basename(m) for m in glob.glob(os.path.join(package, "_probelights.*")))  # noqa
    before = modules()
    bpy.ops.extensions.package_install_files(filepath=wrong, repo="user_default", enable_on_install=True)
    assert harness.ADDON in bpy.context.preferences.addons
    assert modules() == before and before, (before, modules())
    print("  %s refused by Blender %s; %s kept" % (os.path.basename(wrong), bpy.app.version_string, here))


def test_panel_draws_at_default_width_in_this_blender():
    """The panel's drawing code in this Blender (fonts, preferences, operators it names), as the World properties
    editor at its default width would call it, after a bake with warnings and a tradeoff: every line fits. In Cycles
    and EEVEE Next the Tradeoff's rows carry the measured render time, in EEVEE Legacy not."""
    harness.empty_scene()
    scene = bpy.context.scene
    harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    scene.cycles.sample_clamp_indirect = 10.0
    if hasattr(scene.cycles, "use_light_tree"):
        scene.cycles.use_light_tree = False
    bake(count=128)
    assert bpy.ops.probe_lights.tradeoff() == {"FINISHED"}
    ui = harness.addon_module("ui")
    for region_type, width in (("WINDOW", 303), ("UI", 229)):
        log = []
        region = type("Region", (), {"type": region_type, "width": width})()
        context = type("Context", (), {"scene": scene, "region": region, "preferences": bpy.context.preferences})()
        ui.draw_panel(RecordingLayout(log), context)
        labels = [text for kind, text in log if kind == "label"]
        assert ("operator", "probe_lights.bake") in log and ("operator", "probe_lights.cycles_settings") in log
        assert any("Error: diffuse" in t for t in labels) and len(labels) > 20, labels
        assert not ui.OVERFLOW, (region_type, ui.OVERFLOW)
        # In Cycles the Tradeoff shows each count's render time as measured (render_cost.json): 7 multiples in
        # the Properties editor (the sidebar shows them where they fit).
        multiples = [t for t in labels if t.endswith("x") and t[:-1].replace(".", "").isdigit()]
        assert len(multiples) == 7 or region_type == "UI", labels
    # EEVEE Next's render times were measured too (4.2+); EEVEE Legacy's not: no column. Count by Engine names
    # its count in a line that fits.
    scene.render.engine = harness.eevee_engine()
    scene.probe_lights.count_mode = "ENGINE"
    for region_type, width in (("UI", 229), ("WINDOW", 303)):
        region = type("Region", (), {"type": region_type, "width": width})()
        context = type("Context", (), {"scene": scene, "region": region, "preferences": bpy.context.preferences})()
        log = []
        ui.draw_panel(RecordingLayout(log), context)
        assert not ui.OVERFLOW, (region_type, ui.OVERFLOW)
        labels = [t for kind, t in log if kind == "label"]
        assert any(t.startswith("%d lights: " % harness.addon_module("render_cost").default_count(
            scene.render.engine, bpy.app.version)[0]) for t in labels), labels
    eevee = [t for t in labels if t.endswith("x") and t[:-1].replace(".", "").isdigit()]
    measured = harness.addon_module("render_cost").engine_of(scene.render.engine, bpy.app.version) is not None
    assert len(eevee) == (7 if measured else 0), (measured, eevee)
    scene.render.engine = "CYCLES"
    scene.probe_lights.count_mode = "COUNT"
    print("  panel drawn at 303 and 229 px: %d labels, none cut; Cycles render times %s; EEVEE's %s" % (
        len(labels), " ".join(multiples), " ".join(eevee) or "not measured"))
