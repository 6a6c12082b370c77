"""The add-on as Blender's extension platform takes it: every platform's zip passes Blender's own validator, the
oldest supported Blender's (4.2 LTS) and the newest's (addon/extension-tools; scripts/blender-ext.sh caches the
tool), a zip the validator should refuse is refused, and build/repository is the static repository Blender's
server-generate makes of the four zips (what Blender downloads: its index and the zips it names, hash for hash)."""

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(ROOT, "build"))
MANIFEST = os.path.join(ROOT, "addon", "probe_lights", "blender_manifest.toml")
VERSION = re.search(r'^version = "(.+)"', open(MANIFEST).read(), re.M).group(1)
PLATFORMS = ["linux-x64", "windows-x64", "macos-arm64", "macos-x64"]
TOOLS = dict(line.split()[:2] for line in open(os.path.join(ROOT, "addon", "extension-tools"))
             if line.strip() and not line.startswith("#"))


def zip_path(platform):
    return os.path.join(BUILD, "probe_lights-%s-%s.zip" % (VERSION, platform.replace("-", "_")))


def tool(which):
    """The folder of Blender's blender_ext.py and tags.py of the pinned version (cached by the test command)."""
    out = subprocess.run(["bash", os.path.join(ROOT, "scripts", "blender-ext.sh"), TOOLS[which]],
                         capture_output=True, text=True)
    if out.returncode:
        pytest.skip("Blender's extension tool %s is not to be had: %s" % (TOOLS[which], out.stderr.strip()))
    return out.stdout.strip()


def validate(which, path):
    """Blender's validator as `blender --command extension validate` runs it (Blender's tags enforced)."""
    folder = tool(which)
    out = subprocess.run([sys.executable, os.path.join(folder, "blender_ext.py"), "validate", path,
                          "--valid-tags", os.path.join(folder, "tags.py")], capture_output=True, text=True)
    return out.returncode, (out.stdout + out.stderr).strip()


@pytest.mark.parametrize("which", ["oldest", "newest"])
@pytest.mark.parametrize("platform", PLATFORMS)
def test_every_zip_passes_blenders_validator(which, platform):
    path = zip_path(platform)
    if not os.path.exists(path):
        pytest.skip("%s not built (PROBELIGHTS_PLATFORMS)" % os.path.basename(path))
    code, text = validate(which, path)
    assert code == 0 and "success" in text.lower(), "Blender %s's validator: %s" % (TOOLS[which], text)


@pytest.mark.parametrize("which", ["oldest", "newest"])
def test_the_validator_refuses_what_extensions_blender_org_would(which, tmp_path):
    # The control: the zip as it was before the permission's text was shortened (67 characters, over the 64 the
    # platform allows). If the validator did not run, or ran without its rules, this would pass.
    path = zip_path("linux-x64")
    if not os.path.exists(path):
        pytest.skip("no Linux zip")
    bad = tmp_path / os.path.basename(path)
    with zipfile.ZipFile(path) as src, zipfile.ZipFile(bad, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename.endswith("blender_manifest.toml"):
                data = re.sub(rb'(?m)^files = ".*"$',
                              b'files = "Writes a temporary render of the world when it has no image to read"', data)
            dst.writestr(item, data)
    code, text = validate(which, str(bad))
    assert code != 0 and "64 characters" in text, text


def test_the_repository_lists_each_platform_s_zip_once():
    folder = os.path.join(BUILD, "repository")
    if not os.path.exists(os.path.join(folder, "index.json")):
        pytest.skip("no build/repository")
    index = json.load(open(os.path.join(folder, "index.json")))
    items = index["data"]
    assert sorted(p for item in items for p in item["platforms"]) == sorted(PLATFORMS)
    for item in items:
        assert item["id"] == "probe_lights" and item["version"] == VERSION and len(item["platforms"]) == 1
        archive = os.path.join(folder, item["archive_url"].removeprefix("./"))
        data = open(archive, "rb").read()
        assert item["archive_size"] == len(data)
        assert item["archive_hash"] == "sha256:" + hashlib.sha256(data).hexdigest()
        assert open(archive, "rb").read() == open(zip_path(item["platforms"][0]), "rb").read()
    assert "probe_lights" in open(os.path.join(folder, "index.html")).read()
