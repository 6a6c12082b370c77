"""probelights: turn an HDR light probe (a world's environment map) into a few sun or point lights that light a
scene the way the probe does, each carrying exactly the energy of its region of the sphere.

    import probelights
    r = probelights.bake_file("sky.exr", lights=16, evaluate=True)   # read with OpenImageIO
    r["lights"]["direction"], r["lights"]["rgb"], r["evaluation"]
    r = probelights.bake(pixels, lights=64)      # a float32 H x W x C array, rows top to bottom
    probelights.gltf(r["lights"]), probelights.usd(r["lights"])   # or export(r["lights"], "csv"): exporters
    baker = probelights.SequenceBaker(lights=16)  # an animated world's frames, one by one: the same 16 lights
    baker.add(frame_pixels, frame=1)              # each frame, each keeping its id

Directions are in Blender's world frame (Z up, right-handed); a light's rgb is the sum of L dOmega over its
region (a sun's irradiance in W/m^2). Errors raise probelights.Error (a ValueError) with a one-line message, the
command line's. The same core runs as the `probelights` command and inside the Blender add-on.

The native module is loaded on first use (the `probelights` command does not need it to start).
"""

__all__ = ["Error", "SequenceBaker", "bake", "bake_file", "bake_files", "build", "default_distance", "evaluate", "export", "exporters",
           "gltf", "light_kinds", "max_refit_lights", "method_menu", "methods", "release_memory", "sh_project",
           "sh_sample", "touch_pages", "tradeoff", "usd", "__version__"]


def __getattr__(name):
    if name in __all__:
        from . import _probelights
        globals().update({n: getattr(_probelights, n) for n in __all__})  # loaded once: later lookups are plain
        return globals()[name]
    raise AttributeError("module 'probelights' has no attribute %r" % name)


def __dir__():
    return sorted(set(globals()) | set(__all__))
