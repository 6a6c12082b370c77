"""The Python package as pip installs it on Windows (run under Wine by tests/wine/package_tests.sh, in a fresh
embeddable CPython where pip installed the win_amd64 wheel and what it needs): the `probelights` command and
`import probelights` read probes through the openimageio wheel and give the Linux build's lights within the C
libraries' last bits (docs/platforms.md), write whole files over old ones, draw plots with text, expand a library's
wildcards (Windows' shells leave them), and answer a bad input in one line."""

import json
import os
import re
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

ROOT = os.environ["PROBELIGHTS_REPO"]
REFERENCE = os.environ["PROBELIGHTS_REFERENCE"]
WHEEL = os.environ["PROBELIGHTS_WHEEL"]
PROBE = os.path.join(ROOT, "assets", "noon_grass_1k.hdr")
COMMAND = os.path.join(sys.prefix, "Scripts", "probelights.exe")
VERSION = re.search(r'(?m)^version = "(.+)"$',
                    open(os.path.join(ROOT, "addon", "probe_lights", "blender_manifest.toml")).read()).group(1)

import probelights  # noqa: E402  (the installed package)


def run(*args, **kw):
    return subprocess.run([COMMAND, *map(str, args)], capture_output=True, **kw)


def close(a, b, rel=1e-9):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a.shape == b.shape and np.all(np.abs(a - b) <= rel * np.maximum(np.abs(b), 1e-12))


def test_the_package_is_the_installed_one_and_its_version_the_manifests():
    assert os.path.normcase(sys.prefix) in os.path.normcase(probelights.__file__)
    assert probelights.build == "full" and probelights.__version__ == VERSION
    assert os.path.basename(WHEEL) == "probelights-%s-cp%d%d-cp%d%d-win_amd64.whl" % ((VERSION,) + sys.version_info[:2] * 2)
    out = run("--version", text=True, check=True).stdout
    assert out.strip() == "probelights " + VERSION
    metadata = zipfile.ZipFile(WHEEL).read("probelights-%s.dist-info/METADATA" % VERSION).decode()
    assert "Requires-Dist: openimageio==" in metadata


@pytest.mark.parametrize("name, options", [("16", ["--lights", "16"]),
                                           ("32_refit", ["--lights", "32", "--refit", "--evaluate"])])
def test_the_installed_command_bakes_the_linux_builds_lights(tmp_path, name, options):
    out = tmp_path / "lights.json"
    p = run("bake", PROBE, *options, "-q", "-o", out)
    assert p.returncode == 0, p.stderr
    ours, theirs = json.loads(out.read_text()), json.load(open(os.path.join(REFERENCE, name + ".json")))
    assert ours["notes"] == theirs["notes"]
    assert len(ours["lights"]) == len(theirs["lights"])
    for key in ("direction", "rgb"):
        assert close([l[key] for l in ours["lights"]], [l[key] for l in theirs["lights"]]), key
    if theirs.get("evaluation"):
        for key, value in theirs["evaluation"].items():
            assert close(ours["evaluation"][key], value, 1e-6) if isinstance(value, float) else \
                ours["evaluation"][key] == value, key


def test_the_module_bakes_what_the_command_does(tmp_path):
    r = probelights.bake_file(PROBE, lights=16)
    out = tmp_path / "lights.json"
    run("bake", PROBE, "--lights", "16", "-q", "-o", out, check=True)
    lights = json.loads(out.read_text())["lights"]
    assert np.array_equal(r["lights"]["rgb"], np.array([l["rgb"] for l in lights]))
    assert np.array_equal(r["lights"]["direction"], np.array([l["direction"] for l in lights]))


def test_a_file_written_again_is_replaced_whole(tmp_path):
    # MoveFileEx replaces the old file; C's rename would refuse it on Windows.
    out = tmp_path / "lights.json"
    for count in (4, 8):
        p = run("bake", PROBE, "--lights", count, "-q", "-o", out)
        assert p.returncode == 0, p.stderr
        assert len(json.loads(out.read_text())["lights"]) == count
    assert sorted(os.listdir(tmp_path)) == ["lights.json"]  # no temporary left


def test_a_tradeoff_plot_is_drawn_with_its_text(tmp_path):
    import OpenImageIO as oiio
    plot = tmp_path / "tradeoff.png"
    p = run("tradeoff", PROBE, "--counts", "4,16", "--methods", "variance", "--plot", plot, "-o", tmp_path / "t.json")
    assert p.returncode == 0, p.stderr
    pixels = oiio.ImageBuf(str(plot)).get_pixels(oiio.FLOAT)
    assert pixels.shape == (640, 960, 3)
    # The title's black letters on the white margin above the plot (OpenImageIO's own font here).
    assert pixels[5:45, 80:500].min() < 0.2


def test_a_library_pattern_is_expanded_by_the_command(tmp_path):
    for name in ("a.hdr", "b.hdr", "c.txt"):
        shutil.copy(PROBE, tmp_path / name)
    p = run("bake", str(tmp_path / "*.hdr"), "--lights", "4", "--out-dir", tmp_path / "out", "-q")
    assert p.returncode == 0, p.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["baked"] == 2 and sorted(os.listdir(tmp_path / "out")) == ["a.json", "b.json", "summary.json"]


def test_a_bad_input_is_one_line_and_exit_2(tmp_path):
    bad = tmp_path / "not_a_probe.exr"
    bad.write_bytes(b"not an image")
    for args in (["bake", bad], ["bake", tmp_path / "missing.hdr"], ["bake", PROBE, "--lights", "zero"]):
        p = run(*args, text=True)
        assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
        assert p.stderr.startswith("probelights: error:") and "Traceback" not in p.stderr
    with pytest.raises(probelights.Error):
        probelights.bake_file(str(bad))
