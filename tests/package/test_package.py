"""The Python package as pip installs it (run by tests/package/run.sh inside a fresh virtual environment): the
`probelights` command and `import probelights` give the build's lights bit for bit, the version is the manifest's,
the typed stubs match the module, and the wheel's tag is what auditwheel confirms."""

import ast
import inspect
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
BUILD = os.environ["PROBELIGHTS_BUILD"]
WHEEL = os.environ["PROBELIGHTS_WHEEL"]
PROBE = os.path.join(ROOT, "assets", "noon_grass_1k.hdr")
VERSION = re.search(r'(?m)^version = "(.+)"$',
                    open(os.path.join(ROOT, "addon", "probe_lights", "blender_manifest.toml")).read()).group(1)

import probelights  # noqa: E402  (the installed package, not this tree's)


def test_the_package_is_the_installed_one():
    assert "site-packages" in probelights.__file__ and sys.prefix in probelights.__file__
    assert probelights.build == "full"


def test_the_version_is_the_manifests_everywhere():
    assert probelights.__version__ == VERSION
    out = subprocess.run(["probelights", "--version"], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "probelights " + VERSION
    assert os.path.basename(WHEEL).startswith("probelights-%s-" % VERSION)


def without_timings(text):
    data = json.loads(text)
    data.pop("timings_ms", None)
    data["source"].pop("path", None)
    return data


@pytest.mark.parametrize("options", [["--lights", "16"], ["--lights", "32", "--refit", "--evaluate"],
                                     ["--method", "median-cut", "--lights", "8", "--max-error", "0.05"]])
def test_the_installed_command_bakes_what_the_build_does(tmp_path, options):
    assert shutil.which("probelights").startswith(sys.prefix)
    ours, theirs = tmp_path / "installed.json", tmp_path / "built.json"
    subprocess.run(["probelights", "bake", PROBE, *options, "-o", str(ours)], check=True, capture_output=True)
    subprocess.run([os.path.join(BUILD, "bin", "probelights"), "bake", PROBE, *options, "-o", str(theirs)],
                   check=True, capture_output=True)
    assert without_timings(ours.read_text()) == without_timings(theirs.read_text())


def test_a_bad_input_is_one_line_and_exit_2(tmp_path):
    bad = tmp_path / "not_a_probe.exr"
    bad.write_bytes(b"not an image")
    out = subprocess.run(["probelights", "bake", str(bad)], capture_output=True, text=True)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1, out.stderr
    with pytest.raises(probelights.Error):
        probelights.bake_file(str(bad))


def test_the_command_takes_any_file_name_and_answers_as_a_program(tmp_path):
    # Arguments reach the command line inside the module as the bytes the program would get (os.fsencode).
    odd = os.path.join(os.fsencode(tmp_path), b"sky \xff\xfe.hdr")
    shutil.copy(PROBE, odd)
    out = subprocess.run([b"probelights", b"bake", odd, b"--lights", b"4", b"-o", b"-"], capture_output=True)
    assert out.returncode == 0 and len(json.loads(out.stdout)["lights"]) == 4, out.stderr
    out = subprocess.run(["probelights", "bake", PROBE, "--lights", "zero"], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.startswith("probelights: error:") and "Traceback" not in out.stderr
    out = subprocess.run(["probelights"], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.startswith("usage: probelights") and not out.stdout


def test_the_module_bakes_what_the_command_does(tmp_path):
    r = probelights.bake_file(PROBE, lights=16, refit=True, evaluate=True)
    path = tmp_path / "lights.json"
    subprocess.run(["probelights", "bake", PROBE, "--lights", "16", "--refit", "--evaluate", "-o", str(path)],
                   check=True, capture_output=True)
    lights = json.loads(path.read_text())["lights"]
    assert np.array_equal(r["lights"]["direction"], np.array([l["direction"] for l in lights]))
    assert np.array_equal(r["lights"]["rgb"], np.array([l["rgb"] for l in lights]))


def test_the_stubs_name_every_function_with_the_modules_parameters():
    import probelights._probelights as native
    stub = ast.parse(open(os.path.join(os.path.dirname(probelights.__file__), "__init__.pyi")).read())
    stubbed = {node.name: node for node in stub.body if isinstance(node, ast.FunctionDef)}
    functions = {name for name in probelights.__all__ if callable(getattr(native, name))
                 and not isinstance(getattr(native, name), type)}
    assert set(stubbed) == functions
    for name, node in stubbed.items():
        # pybind11 writes each signature as the docstring's first line: name(a: type, *, b: type = default, ...)
        first = getattr(native, name).__doc__.splitlines()[0]
        names = re.findall(r"(?:^|[(,] ?\*?,? ?)(\*{0,2}\w+)(?=: |\)| =)", first[len(name):])
        args = node.args
        stub_names = [a.arg for a in args.args] + [a.arg for a in args.kwonlyargs]
        if args.kwarg:
            stub_names.append("**" + args.kwarg.arg)
        ours = [n.lstrip("*") for n in names]
        assert [n for n in ours if n != "kwargs"] == [n for n in stub_names if n != "**options"], (name, first)
        assert ("kwargs" in ours) == ("**options" in stub_names), (name, first)
        assert ast.get_docstring(node), name


def test_the_wheel_holds_the_package_and_no_copy_of_openimageio():
    names = zipfile.ZipFile(WHEEL).namelist()
    assert "probelights/__init__.pyi" in names
    # The command is the module's (no program of ours in the wheel: no C start-up code of the build's glibc).
    assert [n for n in names if n.endswith(".so")] == [n for n in names if "/bin/" in n or n.endswith(".so")]
    assert not [n for n in names if "OpenImageIO" in n or n.endswith(".so") and "libs/" in n], names
    metadata = zipfile.ZipFile(WHEEL).read("probelights-%s.dist-info/METADATA" % VERSION).decode()
    assert "Requires-Dist: openimageio==3.2.2.0" in metadata


def test_auditwheel_confirms_the_tag_but_for_openimageio(tmp_path):
    # auditwheel (PyPI's, cached by scripts/wheel.sh) reads every ELF in the wheel: its glibc symbols allow
    # manylinux_2_28 (blender.org's floor, and the openimageio wheel's own tag) or older. It calls the wheel "linux"
    # all the same, since OpenImageIO's two libraries are the openimageio wheel's, outside this one: every other
    # library the module names is in the manylinux policy.
    assert WHEEL.endswith("-manylinux_2_28_x86_64.whl"), WHEEL
    tools = os.path.join(os.environ.get("PROBELIGHTS_CACHE", os.path.expanduser("~/.cache/probelights")),
                         "auditwheel-6.8.2", "bin")
    out = subprocess.run([os.path.join(tools, "auditwheel"), "show", WHEEL], capture_output=True, text=True,
                         env={**os.environ, "PATH": tools + os.pathsep + os.environ["PATH"]})
    text = " ".join((out.stdout + out.stderr).split())
    floor = re.search(r'constrains the platform tag to "manylinux_(\d+)_(\d+)_x86_64"', text)
    assert floor and (int(floor.group(1)), int(floor.group(2))) <= (2, 28), text
    zipfile.ZipFile(WHEEL).extractall(tmp_path)
    needed = set()
    for binary in [n for n in zipfile.ZipFile(WHEEL).namelist() if n.endswith(".so")]:
        dynamic = subprocess.run(["readelf", "-d", str(tmp_path / binary)], capture_output=True, text=True).stdout
        needed |= set(re.findall(r"\(NEEDED\)\s+Shared library: \[(.+)\]", dynamic))
    assert needed == {"libOpenImageIO.so.3.2.2", "libOpenImageIO_Util.so.3.2.2", "libc.so.6", "libm.so.6",
                      "libpthread.so.0", "ld-linux-x86-64.so.2"}, needed
