"""The native sampling core (_probelights), imported on first use, never when the add-on is enabled.

The add-on carries one build of _probelights per CPython ABI that supported Blenders run (3.11: Blender 3.4 to
5.0; 3.13: 5.1 and later). A Blender whose Python has none still enables the add-on; a bake then stops with one
line that names the Python versions the add-on was built for. The module's own errors (probelights.Error) become
ProbeError, the one-line problem the operators report.
"""

import glob
import os
import re
import sys

from .errors import ProbeError

_module = None
_failure = None  # the ProbeError of a failed import, kept so a panel's redraw does not retry it
KEEP_SECONDS = 60.0  # how long the core keeps its table buffers for the next bake (Blender's timers: with a window)


def built_for():
    """The Python versions the package holds a module for, e.g. ['3.11', '3.13']."""
    found = set()
    for path in glob.glob(os.path.join(os.path.dirname(__file__), "_probelights.*")):
        # Linux and macOS: .cpython-311-x86_64-linux-gnu.so, .cpython-311-darwin.so; Windows: .cp311-win_amd64.pyd
        m = re.match(r"_probelights\.(?:cpython-|cp)(\d)(\d+)-", os.path.basename(path))
        if m:
            found.add((int(m.group(1)), int(m.group(2))))
    return ["%d.%d" % v for v in sorted(found)]


def unavailable():
    """Why the module cannot be loaded here (one line), or '' when it can."""
    try:
        module()
    except ProbeError as e:
        return str(e)
    return ""


def module():
    global _module, _failure
    if _failure is not None:
        raise _failure
    if _module is None:
        try:
            from . import _probelights
        except ImportError as e:
            python = "%d.%d" % sys.version_info[:2]
            built = built_for()
            if python in built:  # the right ABI, yet it does not load (e.g. a C library too old)
                _failure = ProbeError("Probe Lights' native module does not load in this Blender: %s" %
                                      str(e).splitlines()[0])
            else:
                _failure = ProbeError("Probe Lights needs Blender with Python %s; this Blender runs Python %s" % (
                    " or ".join(built) or "(none: the package has no native module)", python))
            raise _failure from None
        _module = _probelights
    return _module


# How the panel says the options that the core names as the way past a failure (its remedy: error.h).
PANEL_REMEDIES = {"nonfinite": "set NaN/Inf pixels to Zero"}


def in_panel_words(error):
    """A module error's message, its remedy (if any) said as the panel's setting rather than the module's keyword."""
    remedy = getattr(error, "remedy", None)
    if remedy and remedy[1] in PANEL_REMEDIES:
        return "%s; %s: %s" % (error.reason, remedy[0], PANEL_REMEDIES[remedy[1]])
    return str(error)


def _call(name, *args, **kwargs):
    m = module()
    try:
        return getattr(m, name)(*args, **kwargs)
    except m.Error as e:
        raise ProbeError(in_panel_words(e)) from None
    finally:
        _keep_buffers_for_a_while()


def _release_buffers():
    if _module is not None:
        _module.release_memory()  # the table buffers the core keeps for the next bake (native/.../memory.h)


def _keep_buffers_for_a_while():
    """The core keeps its last two tables' buffers so the next bake does not map fresh memory (native memory.h);
    they are given back KEEP_SECONDS after the last bake."""
    import bpy
    if bpy.app.timers.is_registered(_release_buffers):
        bpy.app.timers.unregister(_release_buffers)
    bpy.app.timers.register(_release_buffers, first_interval=KEEP_SECONDS)


def unregister():
    import bpy
    if bpy.app.timers.is_registered(_release_buffers):
        bpy.app.timers.unregister(_release_buffers)
    _release_buffers()


def bake(pixels, **options):
    """_probelights.bake: the lights of a probe given as a float32 H x W x C array."""
    return _call("bake", pixels, **options)


def tradeoff(pixels, **options):
    """_probelights.tradeoff: one row per light count with its bake time and estimated errors."""
    return _call("tradeoff", pixels, **options)
