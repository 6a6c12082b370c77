"""The add-on installs on Blender 4.2+ as an extension: blender_manifest.toml has what the extension system requires
and agrees with bl_info (which Blender 3.4 reads)."""

import ast
import os
import tomllib

ADDON = os.path.join(os.path.dirname(__file__), "..", "..", "addon", "probe_lights")


def bl_info():
    tree = ast.parse(open(os.path.join(ADDON, "__init__.py")).read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "bl_info" for t in node.targets):
            return ast.literal_eval(node.value)
    raise AssertionError("no bl_info")


def test_manifest_has_the_required_fields_and_matches_bl_info():
    m = tomllib.load(open(os.path.join(ADDON, "blender_manifest.toml"), "rb"))
    for key in ("schema_version", "id", "version", "name", "tagline", "maintainer", "type", "blender_version_min",
                "license"):
        assert key in m, key
    assert m["type"] == "add-on" and m["id"] == os.path.basename(os.path.normpath(ADDON))
    assert len(m["tagline"]) <= 64 and not m["tagline"].endswith(".")
    assert tuple(int(v) for v in m["blender_version_min"].split(".")) >= (4, 2, 0)
    assert all(lic.startswith("SPDX:") for lic in m["license"])
    assert m["platforms"] == ["linux-x64"]  # the package holds a native module
    info = bl_info()
    assert tuple(int(v) for v in m["version"].split(".")) == info["version"]
    assert info["name"] == m["name"] and info["blender"] <= (3, 4, 0)


def test_the_panel_offers_the_cores_methods_and_light_kinds():
    # The add-on registers before its native module loads (a Blender without a build for its Python still
    # enables it), so it reads its menus from core_tables.json, which scripts/addon_tables.py writes from the
    # core's tables (methodMenu, cut_choice.h; lightKinds, light_export.h): a new method or kind fails here until
    # the file is written again.
    import json
    import _probelights as pl
    written = json.load(open(os.path.join(ADDON, "core_tables.json")))
    again = "core_tables.json is not the core's: PYTHONPATH=build/python python3 scripts/addon_tables.py"
    assert [tuple(m) for m in written["methods"]] == list(pl.method_menu), again
    assert written["light_kinds"] == pl.light_kinds and written["default_distance"] == pl.default_distance, again
    offered = [m[0] for m in written["methods"]]
    assert offered[:2] == ["auto", "both"] and offered[2:] == list(pl.methods)
    import light_kinds  # the add-on's (conftest.py puts its folder on the path)
    assert [k.id for k in light_kinds.KINDS] == [k["name"].upper() for k in pl.light_kinds]
    assert light_kinds.DEFAULT_DISTANCE == pl.default_distance


def test_one_version_everywhere():
    # Written once, in the manifest: pyproject.toml's regex reads it for the Python package, CMake for the
    # command, the modules and the zips' names; bl_info (which Blender 3.4 reads as a literal) must agree.
    import re
    import subprocess
    import _probelights as pl
    root = os.path.join(ADDON, "..", "..")
    version = tomllib.load(open(os.path.join(ADDON, "blender_manifest.toml"), "rb"))["version"]
    project = tomllib.load(open(os.path.join(root, "pyproject.toml"), "rb"))
    rule = project["tool"]["scikit-build"]["metadata"]["version"]
    assert "version" in project["project"]["dynamic"]
    assert os.path.normpath(os.path.join(root, rule["input"])) == os.path.normpath(
        os.path.join(ADDON, "blender_manifest.toml"))
    assert re.search(rule["regex"], open(os.path.join(root, rule["input"])).read()).group("value") == version
    assert pl.__version__ == version
    build = os.environ.get("PROBELIGHTS_BUILD", os.path.join(root, "build"))
    out = subprocess.run([os.path.join(build, "bin", "probelights"), "--version"], capture_output=True, text=True)
    assert out.stdout.strip() == "probelights " + version
    assert ".".join(str(v) for v in bl_info()["version"]) == version
    assert os.path.exists(os.path.join(build, "probe_lights-%s-linux_x64.zip" % version))
