"""The add-on's native modules load in any supported Blender: one per CPython ABI, linking nothing but libc, libm,
libpthread and the loader (a blender.org build has no OpenImageIO of Debian's, and maybe an older libstdc++), and
needing no newer glibc than measured; and a Blender without a matching module gets one line, not a traceback."""

import importlib
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
ADDON_SOURCE = os.path.join(os.path.dirname(__file__), "..", "..", "addon", "probe_lights")
ALLOWED = {"libc.so.6", "libm.so.6", "libpthread.so.0", "ld-linux-x86-64.so.2"}
GLIBC_CEILING = (2, 28)  # blender.org's Blender needs 2.28; measured 2.18 (native/python/glibc_compat.cpp)


def zipped_modules():
    with zipfile.ZipFile(os.path.join(BUILD, "probe_lights-0.1.0-linux_x64.zip")) as z:
        names = z.namelist()
    assert "probe_lights/blender_manifest.toml" in names and "probe_lights/__init__.py" in names
    return [n for n in names if re.match(r"probe_lights/_probelights\.cpython-\d+-x86_64-linux-gnu\.so$", n)]


def test_the_zip_holds_a_module_for_each_blender_python():
    abis = sorted(re.search(r"cpython-(\d+)", n).group(1) for n in zipped_modules())
    assert abis == ["311", "313"], abis  # Blender 3.4 to 5.0; 5.1 and later


@pytest.mark.parametrize("name", ["311", "313"])
def test_needed_libraries_and_glibc(name):
    path = os.path.join(BUILD, "addon", "probe_lights", "_probelights.cpython-%s-x86_64-linux-gnu.so" % name)
    if not os.path.exists(path):
        pytest.skip("no module for cpython-%s in this build" % name)
    dynamic = subprocess.run(["readelf", "-d", "-W", path], check=True, capture_output=True, text=True).stdout
    needed = set(re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", dynamic))
    assert needed and needed <= ALLOWED, needed - ALLOWED
    symbols = subprocess.run(["readelf", "-V", "-W", path], check=True, capture_output=True, text=True).stdout
    versions = {tuple(int(v) for v in m.split(".")) for m in re.findall(r"GLIBC_(\d+\.\d+(?:\.\d+)?)", symbols)}
    assert max(versions) <= GLIBC_CEILING, max(versions)


def test_a_blender_without_a_matching_module_gets_one_line(tmp_path):
    """native.py in a package whose only module is for another Python: the bake's error names both versions."""
    package = tmp_path / "fake_addon"
    package.mkdir()
    for name in ("native.py", "errors.py"):
        shutil.copy(os.path.join(ADDON_SOURCE, name), package / name)
    (package / "__init__.py").write_text("")
    (package / "_probelights.cpython-399-x86_64-linux-gnu.so").write_bytes(b"")
    sys.path.insert(0, str(tmp_path))
    try:
        native = importlib.import_module("fake_addon.native")
        errors = importlib.import_module("fake_addon.errors")
        assert native.built_for() == ["3.99"]
        with pytest.raises(errors.ProbeError) as e:
            native.bake(None)
        message = str(e.value)
        assert "\n" not in message
        running = "%d.%d" % sys.version_info[:2]
        assert message == "Probe Lights needs Blender with Python 3.99; this Blender runs Python " + running
        assert native.unavailable() == message  # the panel's line; the failed import is not retried
    finally:
        sys.path.remove(str(tmp_path))


def test_the_portable_build_bakes_exactly_what_the_full_one_does():
    """The add-on's module (core on std::thread) and the full module (core on OpenImageIO's pool) are two builds of
    one core: the same pixels give bit-identical lights, errors included."""
    here = "%d%d" % sys.version_info[:2]
    path = os.path.join(BUILD, "addon", "probe_lights", "_probelights.cpython-%s-x86_64-linux-gnu.so" % here)
    if not os.path.exists(path):
        pytest.skip("no portable module for this Python (cpython-%s)" % here)
    import _probelights as full  # first: loading the portable one under the same name must not shadow it

    spec = importlib.util.spec_from_file_location("_probelights", path)
    portable = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(portable)
    sys.modules["_probelights"] = full
    assert portable.build == "pixels" and full.build == "full" and not hasattr(portable, "bake_file")
    rng = np.random.default_rng(7)
    image = (rng.random((128, 256, 3), dtype=np.float32) ** 8 * 50).astype(np.float32)
    for method in ("variance", "median-cut", "sh"):
        a = full.bake(image, method=method, lights=24, evaluate=True, effects="diffuse,shadow", evaluator_width=128)
        b = portable.bake(image, method=method, lights=24, evaluate=True, effects="diffuse,shadow",
                          evaluator_width=128)
        for key in ("direction", "rgb", "solid_angle", "angular_radius"):
            assert np.array_equal(a["lights"][key], b["lights"][key]), (method, key)
        assert np.array_equal(a["total_rgb"], b["total_rgb"])
        assert a["evaluation"] == b["evaluation"], method
    # C++ exceptions still unwind through the portable module (its unwinder finds frames via glibc_compat.cpp).
    bad = np.ones((8, 16, 3), np.float32)
    bad[2, 3, 1] = np.nan
    for _ in range(3):
        with pytest.raises(portable.Error, match="1 NaN/Inf samples"):
            portable.bake(bad)
        with pytest.raises(portable.Error, match="at least 1"):
            portable.bake(image, lights=0)
