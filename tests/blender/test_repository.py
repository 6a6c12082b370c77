"""The add-on as a Blender 4.2+ user gets it from a repository: the static repository the build writes
(build/repository: Blender's server-generate over the four platforms' zips) added by its file:// URL as a remote
repository, synced, the add-on installed from it and a probe baked; then a 0.1.1 of the same add-on put into the
repository is offered as an update and installed over it, a scene baked and saved under the old version opens,
renders the same and restores; then it is uninstalled.

    tests/blender/run.sh ~/.cache/probelights/bpy-4.5.15/bin/python tests/blender/test_repository.py \
        build/probe_lights-0.1.0-linux_x64.zip ../shared
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import harness  # noqa: E402
import render_scene  # noqa: E402

ARGS = harness.args()
BUILD = os.path.dirname(os.path.abspath(ARGS.zip))
WORK = tempfile.mkdtemp(prefix="probelights-repository-")
REPO = os.path.join(WORK, "repository")  # the folder a maintainer would put on a static web server
PACKAGE = "probe_lights"
THIS_PLATFORM = {"linux": "linux-x64", "win32": "windows-x64"}[sys.platform]


def blender_ext(*arguments):
    """The running Blender's own extension tool (what `blender --command extension` runs)."""
    import bl_pkg
    tool = os.path.join(os.path.dirname(bl_pkg.__file__), "cli", "blender_ext.py")
    out = subprocess.run([sys.executable, tool, *arguments], capture_output=True, text=True)
    assert out.returncode == 0 and "error" not in (out.stdout + out.stderr).lower(), out.stdout + out.stderr
    return out.stdout


def manifest_version(text):
    return re.search(r'(?m)^version = "(.+)"$', text).group(1)


def next_version(zip_in, zip_out, version):
    """The same add-on at another version: its manifest's version and bl_info's (what a maintainer's release of
    a fix changes)."""
    major, minor, patch = (int(v) for v in version.split("."))
    with zipfile.ZipFile(zip_in) as src, zipfile.ZipFile(zip_out, "w", zipfile.ZIP_DEFLATED) as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename.endswith("/blender_manifest.toml"):
                data = re.sub(rb'(?m)^version = ".*"$', b'version = "%s"' % version.encode(), data)
            elif item.filename == PACKAGE + "/__init__.py":
                data = re.sub(rb'"version": \(\d+, \d+, \d+\)', b'"version": (%d, %d, %d)' % (major, minor, patch),
                              data)
            dst.writestr(item, data)


def url():
    """The repository folder's file:// URL, as Blender's own tool spells it (file:///Z:/... on Windows)."""
    from bl_pkg.cli import blender_ext
    return blender_ext.path_to_url(REPO)


def repo():
    """The remote repository the test added: (index, module name)."""
    for i, r in enumerate(bpy.context.preferences.extensions.repos):
        if r.use_remote_url and r.remote_url == url():
            return i, r
    raise AssertionError("the repository is not in the preferences")


def installed_manifest():
    _, r = repo()
    path = os.path.join(r.directory, PACKAGE, "blender_manifest.toml")
    return open(path).read() if os.path.exists(path) else ""


def light_objects():
    """The installed add-on's light_objects (the update installs it anew)."""
    return harness.addon_module("light_objects")


def sync():
    index, _ = repo()
    assert bpy.ops.extensions.repo_sync(repo_index=index) == {"FINISHED"}


def listing(platform=None):
    """What Blender offers of the synced index: the packages its own filter keeps for this Blender, this Python and
    `platform` (default: this machine's), as the Get Extensions list and the install do."""
    from bl_pkg import bl_extension_utils
    from bl_pkg.cli import blender_ext
    _, r = repo()
    items = json.load(open(os.path.join(r.directory, ".blender_ext", "index.json")))["data"]
    params = bl_extension_utils.PkgManifest_FilterParams(
        platform=platform or blender_ext.platform_from_this_system(), blender_version=tuple(bpy.app.version),
        python_version=tuple(sys.version_info[:3]))
    return [item for item in items if not bl_extension_utils.repository_filter_skip(item, params, print)]


def test_a_repository_installs_updates_and_uninstalls():
    index = json.load(open(os.path.join(BUILD, "repository", "index.json")))
    version = index["data"][0]["version"]
    shutil.copytree(os.path.join(BUILD, "repository"), REPO)

    # Preferences > System > Allow Online Access (a file:// repository needs none to sync; installing asks it),
    # then Get Extensions > Repositories > Add Remote Repository with the folder's URL.
    prefs = bpy.context.preferences
    prefs.system.use_online_access = True
    result = bpy.ops.preferences.extension_repo_add(name="Probe Lights", remote_url=url(), type="REMOTE")
    assert result == {"FINISHED"}, result
    index_number, r = repo()
    sync()
    # Each platform's user is offered one package, their platform's zip, of the four the index lists.
    for platform in ("linux-x64", "windows-x64", "macos-arm64", "macos-x64"):
        offered = [(p["id"], p["version"], p["platforms"]) for p in listing(platform)]
        assert offered == [(PACKAGE, version, [platform])], (platform, offered)
    assert listing()[0]["platforms"] == [THIS_PLATFORM]

    assert bpy.ops.extensions.package_install(repo_index=index_number, pkg_id=PACKAGE,
                                              enable_on_install=True) == {"FINISHED"}
    module = "bl_ext.%s.%s" % (r.module, PACKAGE)
    assert module in prefs.addons, [a.module for a in prefs.addons]
    assert manifest_version(installed_manifest()) == version
    harness.ADDON = module

    # Bake the bundled probe in the render tests' scene and save it.
    harness.empty_scene()
    world = harness.env_world(bpy.data.images.load(harness.BUNDLED_PROBE))
    before_bake = harness.tree_snapshot(world)
    render_scene.sphere_over_plane(64, 48, 16)
    assert bpy.ops.probe_lights.bake("EXEC_DEFAULT", count=8) == {"FINISHED"}
    lamps = sorted(o.name for o in light_objects().baked_lights(world))
    assert len(lamps) == 8
    first = render_scene.render()
    saved = os.path.join(WORK, "baked.blend")
    bpy.ops.wm.save_as_mainfile(filepath=saved)

    # The maintainer releases a fix: the repository now holds the next version, and the user is offered it.
    major, minor, patch = (int(v) for v in version.split("."))
    newer = "%d.%d.%d" % (major, minor, patch + 1)
    for name in os.listdir(REPO):
        if name.endswith(".zip"):
            next_version(os.path.join(REPO, name), os.path.join(REPO, name.replace(version, newer)), newer)
            os.remove(os.path.join(REPO, name))
    blender_ext("server-generate", "--repo-dir", REPO, "--html")
    sync()
    assert [(p["id"], p["version"]) for p in listing()] == [(PACKAGE, newer)]
    assert bpy.ops.extensions.package_upgrade_all() == {"FINISHED"}
    assert manifest_version(installed_manifest()) == newer
    assert module in prefs.addons

    # The scene baked and saved under the old version opens, renders the same and restores.
    bpy.ops.wm.open_mainfile(filepath=saved)
    world = bpy.context.scene.world
    assert sorted(o.name for o in light_objects().baked_lights(world)) == lamps
    again = render_scene.render()
    assert np.array_equal(first, again), float(np.abs(first - again).max())
    assert bpy.ops.probe_lights.restore() == {"FINISHED"}
    assert not light_objects().baked_lights(world)
    assert harness.tree_snapshot(world) == before_bake

    # And it uninstalls: disabled, its files gone.
    assert bpy.ops.extensions.package_uninstall(repo_index=index_number, pkg_id=PACKAGE) == {"FINISHED"}
    assert module not in prefs.addons
    assert not installed_manifest()


harness.run([test_a_repository_installs_updates_and_uninstalls])
