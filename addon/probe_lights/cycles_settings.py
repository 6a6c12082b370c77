"""Cycles settings the baked lamps need, offered and reversible.

Cycles' default indirect clamp (10) cuts the bright bounce paths a sun makes, so bounce light under baked suns
renders darker than under the world; Blender 4.0+ picks among many lamps with its light tree (3.x has none: many
lamps get noisy, render_cost.py). The panel says which of the scene's settings cost the lamps light or noise
(cycles_clamp.json, written by bench/bench_cycles_settings.py; docs/results/renders.md) and offers one click that
sets them; the values it replaced are kept on the scene and put back by Restore world (when no baked world of the
scene is left).
"""

import json
import os

import bpy

from .remembered import put_back, set_remembering
from .render_cost import nearest_version

BEFORE_KEY = "probe_lights_cycles_before"  # on the scene: the settings the offer replaced


def _load(path=os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycles_clamp.json")):
    """cycles_clamp.json as {(major, minor, patch): darkening %}, the worst of the version's probes."""
    with open(path, encoding="utf-8") as f:
        versions = json.load(f)["versions"]
    return {tuple(int(p) for p in version.split(".")): max(m["darkening"] for m in probes.values())
            for version, probes in versions.items()}


# How much darker 64 suns render with the default indirect clamp than without, per measured version. Without a
# light tree (3.x) lamps are picked uniformly and the clamp cuts the rare, bright samples of a strong sun.
DARKENING = _load()
MATTERS = 0.5  # percent: a darkening below this is not worth a word


def _wanted(scene):
    """{setting: value} for what the lamps need that the scene does not have: no indirect clamp, and the light tree
    where the version has one."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None:
        return {}
    wanted = {}
    if cycles.sample_clamp_indirect > 0:
        wanted["sample_clamp_indirect"] = 0.0
    if hasattr(cycles, "use_light_tree") and not cycles.use_light_tree:
        wanted["use_light_tree"] = True
    return wanted


def advice(scene, lamps):
    """One line on what the scene's Cycles settings cost the baked lamps in this version, or '' when they cost
    nothing measurable."""
    if scene.render.engine != "CYCLES" or lamps < 2:
        return ""
    wanted = _wanted(scene)
    darkening = DARKENING[nearest_version(DARKENING, bpy.app.version)]
    parts = []
    if "sample_clamp_indirect" in wanted and darkening >= MATTERS:
        parts.append("the indirect clamp (%g) darkens the lamps' bounce light" % scene.cycles.sample_clamp_indirect)
    if "use_light_tree" in wanted:
        parts.append("the light tree is off, so many lamps render noisily")
    return "Cycles: " + "; ".join(parts) if parts else ""


def noise_note(scene, lamps):
    """Cycles without a light tree (3.x) samples many lamps noisily, which no setting cures: one line, or ''."""
    cycles = getattr(scene, "cycles", None)
    if scene.render.engine != "CYCLES" or cycles is None or hasattr(cycles, "use_light_tree") or lamps < 32:
        return ""
    return "Cycles %d.%d has no light tree: many lamps render noisily; use fewer or more samples" % bpy.app.version[:2]


def apply(scene):
    """Sets what the lamps need, remembering what it replaced (once: a second click keeps the first values)."""
    wanted = _wanted(scene)
    set_remembering(scene, BEFORE_KEY, scene.cycles, wanted)
    return sorted(wanted)


def restore(scene):
    """Puts back what apply() replaced. Returns the names restored."""
    return put_back(scene, BEFORE_KEY, scene.cycles,
                    lambda name, value: bool(value) if name == "use_light_tree" else float(value))
