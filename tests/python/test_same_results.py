"""The add-on's module gives the same lights and errors on every platform: a bake on Linux is written to a
reference file, and the same bakes of another platform's module (Windows, under Wine: tests/wine/module_tests.sh)
must equal it: the same methods, counts, messages and shapes, and every float within RELATIVE of the Linux one.
Not to the last bit: the core calls the C library's sin, cos, acos, atan2, exp and log, whose last bit differs
between glibc and Windows' UCRT (each within an ulp of the true value), and the refit's least squares carries those
differences on to ~1e-10 (measured on Windows: solid angles and directions within 4e-16 without a refit, colours
within 1.1e-10 with one).

    python3 tests/python/test_same_results.py OUT.json         writes the reference with the module on sys.path
    PROBELIGHTS_REFERENCE=OUT.json pytest test_same_results.py compares the module on sys.path with it

The bakes: the bundled probe (read by tests/python/rgbe.py, so no platform needs OpenImageIO) as the add-on bakes
it (Auto cuts, fitted sun angles, Refit with moved directions, its diffuse and shadow errors estimated), and a
heavy-tailed random probe with each method; then two bad inputs, whose messages must be the same words.
Floats are stored as float.hex: exact.
"""

import json
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rgbe import read_hdr  # noqa: E402

BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "assets", "noon_grass_1k.hdr")
ADDON_CLICK = dict(preset="blender")  # the core's recipe for the add-on's bake (request.cpp)
COLUMNS = ("direction", "rgb", "solid_angle", "angular_radius")
RELATIVE = 1e-9  # the C libraries' last bits, carried through the refit (measured: 1.1e-10)


def bakes(pl):
    """Name -> (result of the bake as exact floats) or the error's message."""
    probe = read_hdr(BUNDLED)
    # x^8 by three squarings in float64: IEEE products, the same bits on every platform (numpy's float32 power
    # is not: Windows' and Linux's builds differ in its last bit).
    x = np.random.default_rng(7).random((128, 256, 3))
    x = x * x
    x = x * x
    random = (x * x * 50).astype(np.float32)
    requests = {
        "bundled, the add-on's click": (probe, ADDON_CLICK),
        "bundled, variance 16": (probe, dict(lights=16, evaluate=True, effects="diffuse,shadow,glossy",
                                             evaluator_width=256)),
        "random, variance 24": (random, dict(method="variance", lights=24, evaluate=True, evaluator_width=128)),
        "random, median cut 24": (random, dict(method="median-cut", lights=24, evaluate=True, evaluator_width=128)),
        "random, sh 24": (random, dict(method="sh", lights=24, evaluate=True, evaluator_width=128)),
    }
    bad = np.ones((8, 16, 3), np.float32)
    bad[2, 3, 1] = np.nan
    out = {}
    for name, (pixels, options) in requests.items():
        r = pl.bake(pixels, **options)
        out[name] = {"lights." + key: exact(r["lights"][key]) for key in COLUMNS}
        out[name]["total_rgb"] = exact(r["total_rgb"])
        out[name]["evaluation"] = exact(r.get("evaluation", {}))
        out[name]["method"] = r["method"]
    for name, pixels, options in (("NaN", bad, {}), ("no lights", random, dict(lights=0))):
        try:
            pl.bake(pixels, **options)
            out["error: " + name] = "no error"
        except pl.Error as e:
            out["error: " + name] = str(e)
    return out


def exact(value):
    """Floats (also in arrays, lists and dicts) as float.hex; everything else as it is."""
    if isinstance(value, np.ndarray):
        return exact(value.tolist())
    if isinstance(value, dict):
        return {k: exact(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [exact(v) for v in value]
    if isinstance(value, float):
        return float.hex(value)
    return value


def differences(a, b, path=""):
    """Where two exact results differ: (path, relative difference or None when not numbers)."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return [(path + " keys", None)]
        return [d for k in a for d in differences(a[k], b[k], path + "/" + k)]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [(path + " length", None)]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, "%s[%d]" % (path, i))]
    if a == b:
        return []
    if isinstance(a, str) and isinstance(b, str) and a.startswith(("0x", "-0x")) and b.startswith(("0x", "-0x")):
        x, y = float.fromhex(a), float.fromhex(b)
        return [(path, abs(x - y) / max(abs(x), abs(y)))]
    return [(path, None)]


@pytest.mark.skipif(not os.environ.get("PROBELIGHTS_REFERENCE"), reason="no reference (PROBELIGHTS_REFERENCE)")
def test_the_same_lights_and_errors_as_the_reference_build():
    import _probelights as pl
    with open(os.environ["PROBELIGHTS_REFERENCE"]) as f:
        reference = json.load(f)
    found = differences(reference, bakes(pl))
    numbers = [d for _, d in found if d is not None]
    print("%s (%s, Python %d.%d): %d values differ in their last bits, at most %.2g relative" % (
        os.path.basename(pl.__file__), sys.platform, *sys.version_info[:2], len(numbers), max(numbers, default=0)))
    assert not [path for path, d in found if d is None], "not the same result: %s" % found[:10]
    assert max(numbers, default=0) <= RELATIVE, sorted(found, key=lambda f: -f[1])[:5]



def test_the_tests_reader_gives_the_pixels_openimageio_gives():
    """rgbe.py stands in for OpenImageIO where there is none: the full module's bake of the file and its bake of
    rgbe.py's pixels are the same to the last bit."""
    import _probelights as pl
    if pl.build != "full":
        pytest.skip("needs the full module (reads files)")
    a = pl.bake_file(BUNDLED, lights=16, resolution="full")
    b = pl.bake(read_hdr(BUNDLED), lights=16, resolution="full")
    for key in COLUMNS:
        assert np.array_equal(a["lights"][key], b["lights"][key]), key
    assert np.array_equal(a["total_rgb"], b["total_rgb"])


if __name__ == "__main__":
    import _probelights
    with open(sys.argv[1] + ".partial", "w") as f:
        json.dump(bakes(_probelights), f, indent=0)
    os.replace(sys.argv[1] + ".partial", sys.argv[1])
