# Types of the probelights package for editors and type checkers. The functions are the native module's
# (native/python/module.cpp); tests/python/test_package.py holds each signature here to the module's own.
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

__version__: str
build: str
"""'full': reads files with OpenImageIO (bake_file); 'pixels': the add-on's portable build, pixels only."""
max_refit_lights: int
"""The most lights a bake with refit=True takes."""
methods: list[str]
"""Every placement method's name, as method= takes it."""
method_menu: list[tuple[str, str, str]]
"""A menu's choices of method: (name, label, what it does), the cut choices 'auto' and 'both' first."""
exporters: list[str]
"""The formats export() writes: 'gltf', 'usd', 'csv'."""
light_kinds: list[dict[str, Any]]
"""The kinds of light light_type= takes: name, label, description, fitted_angle, on_dome."""
default_distance: float
"""Metres from the origin of point lights when no distance= is given."""

class Error(ValueError):
    """A bad input or option: its message is one line, the command line's."""
    reason: str
    """The failure alone, without the remedy the message ends with."""
    remedy: tuple[str, str, list[str]] | None
    """What gets past it, (purpose, option, values), e.g. ("to read them as 0", "nonfinite", ["zero"]), or None."""

Pixels = npt.NDArray[np.float32]
Lights = dict[str, npt.NDArray[np.float64]]

class SequenceBaker:
    """Bakes the frames of an animated world, given one by one, into the same N lights each frame, each keeping
    its id. options: the sequence's (smoothness, exact_energy: the refit keeps every frame's energy exact unless
    False, frames, fit_width: the probe's width each frame is finished at, auto: 256 with exact energy, else
    512) and the bake's lights, method (variance or median-cut), centroid, resolution, horizon, sun_angles (fit,
    spread or points), sun_cones, sun_profile, refit, move_directions, evaluate, evaluator_width (the width
    evaluate's errors are judged at, 512), nonfinite; help(probelights.SequenceBaker) lists them with their
    defaults."""
    frames: int
    """How many frames were added."""
    def __init__(self, **options: Any) -> None: ...
    def add(self, pixels: Pixels, *, projection: str = "latlong", frame: int = 0) -> dict[str, Any]:
        """Bake the next frame (a float32 H x W x C array like bake()'s, every frame of one size): frame, source,
        recut, motion (radians), spread, fresh_spread, energy_shift (the refit's with exact_energy=False; else
        rounding), lights (id,
        direction, rgb, ... as numpy arrays; row k is light k in every frame), total_rgb, timings_ms, notes,
        and evaluation (diffuse, shadow) when evaluate=True."""
        ...

def bake(pixels: Pixels, *, projection: str = "latlong", **options: Any) -> dict[str, Any]:
    """Bake a probe given as a float32 H x W x C array (rows top to bottom; not copied). Returns the layout of the
    command's JSON: source, method, lights (direction (N,3), rgb (N,3), solid_angle, angular_radius,
    energy_share (N,), rect (N,4)), total_rgb, timings_ms, notes (dicts of kind 'reading', 'chosen' or
    'warning', text and detail), and evaluation when asked for. options:
    preset ('blender' or 'blender-eevee': the Blender add-on's bake, the other options changing it), lights,
    max_error, method, evaluate, effects, refit, ... (help(probelights.bake) lists them all)."""

def bake_file(path: str, *, projection: str = "auto", **options: Any) -> dict[str, Any]:
    """Read a probe with OpenImageIO and bake it: bake()'s dict, with source.path and timings_ms.load."""

def bake_files(paths: Sequence[str], *, projection: str = "auto", **options: Any) -> list[dict[str, Any]]:
    """Bake many probes (files, directories, globs) in order: bake_file()'s dicts, {'source', 'error'} for one
    that failed."""

def tradeoff(pixels: Pixels, *, projection: str = "latlong", **options: Any) -> dict[str, Any]:
    """What accuracy costs in time: one row per (method, count, resolution, refit) with its bake time and errors.
    Options: counts, methods, resolutions (lists), and preset, effects, refit, evaluator_width, centroid,
    sun_angles, sun_profile, sun_cones, nonfinite as bake() takes them (defaults: tradeoff.__doc__)."""

def evaluate(pixels: Pixels, lights: Lights, *, projection: str = "latlong", **options: Any) -> dict[str, float]:
    """The errors (relative RMS of luminance) of any lights (direction, rgb, angle) against the probe. Options:
    preset, effects (default diffuse,shadow), evaluator_width, sun_profile, sun_cones, nonfinite as bake() takes
    them (evaluate.__doc__)."""

def export(lights: Lights, format: str, *, light_type: str = "sun", distance: float = 10.0, reflections: str = "",
           residual: str = "") -> str:
    """Text of a bake's lights in a format of `exporters` ('gltf', 'usd', 'csv'); reflections, residual: a
    DomeLight's image, for a format that takes one (usd)."""

def gltf(lights: Lights, *, light_type: str = "sun", distance: float = 10.0) -> str:
    """glTF 2.0 text (KHR_lights_punctual) of a bake's lights: suns in lux or points in candela."""

def usd(lights: Lights, *, light_type: str = "sun", distance: float = 10.0, reflections: str = "",
        residual: str = "") -> str:
    """USD text (usda, UsdLux) of a bake's lights."""

def sh_project(pixels: Pixels, *, projection: str = "latlong", **options: Any) -> npt.NDArray[np.float64]:
    """Real SH coefficients (bands^2 x 3). Options: bands (required), window, irradiance, nonfinite
    (sh_project.__doc__)."""

def sh_sample(pixels: Pixels, *, projection: str = "latlong",
              **options: Any) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(directions (N,3), pdf (N,)) from the SH importance sampler of the probe's luminance. Options: bands
    (required), epsilon, samples, depth, seed, nonfinite (sh_sample.__doc__)."""

def touch_pages(buffer: Pixels) -> None:
    """Map a new float32 buffer's memory from all threads before a single-threaded writer fills it."""

def release_memory() -> None:
    """Give back the table buffers kept for the next bake."""
