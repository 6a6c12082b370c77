"""Writes the Python package's wheel for Windows or macOS around a module built by the zig sub-build
(scripts/wheel_platform.sh), with the metadata pyproject.toml gives the Linux wheels (scikit-build-core writes
those): the same METADATA, entry point and licence; the version is the add-on manifest's.
    platform_wheel.py MODULE TAG OUT_DIR      -> prints the wheel's path
TAG is a wheel tag, e.g. cp311-cp311-win_amd64 or cp313-cp313-macosx_11_0_arm64. The wheel is written whole
(a temporary name, then renamed)."""

import base64
import hashlib
import os
import re
import sys
import tomllib
import zipfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def metadata(project, version, readme):
    lines = ["Metadata-Version: 2.4", "Name: " + project["name"], "Version: " + version,
             "Summary: " + project["description"], "Keywords: " + ",".join(project["keywords"])]
    lines += ["Author: " + a["name"] for a in project["authors"]]
    lines += ["License-Expression: " + project["license"]]
    lines += ["License-File: " + f for f in project["license-files"]]
    lines += ["Classifier: " + c for c in project["classifiers"]]
    lines += ["Requires-Python: " + project["requires-python"]]
    lines += ["Requires-Dist: " + d for d in project["dependencies"]]
    lines += ["Description-Content-Type: text/markdown", "", readme]
    return "\n".join(lines)


def main(module, tag, out_dir):
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        project = tomllib.load(f)["project"]
    with open(os.path.join(ROOT, "addon", "probe_lights", "blender_manifest.toml"), "rb") as f:
        version = tomllib.load(f)["version"]
    with open(os.path.join(ROOT, project["readme"]), encoding="utf-8") as f:
        readme = f.read()
    name = project["name"]
    info = "%s-%s.dist-info" % (name, version)
    files = []  # (name in the wheel, bytes)
    package = os.path.join(ROOT, "python", name)
    for entry in sorted(os.listdir(package)):
        if re.fullmatch(r"[\w.]+\.(py|pyi|typed)", entry):
            with open(os.path.join(package, entry), "rb") as f:
                files.append(("%s/%s" % (name, entry), f.read()))
    with open(module, "rb") as f:
        files.append(("%s/%s" % (name, os.path.basename(module)), f.read()))
    files.append((info + "/METADATA", metadata(project, version, readme).encode()))
    files.append((info + "/WHEEL", ("Wheel-Version: 1.0\nGenerator: probelights platform_wheel.py\n"
                                    "Root-Is-Purelib: false\nTag: %s\n\n" % tag).encode()))
    scripts = "".join("%s = %s\n" % kv for kv in project["scripts"].items())
    files.append((info + "/entry_points.txt", ("[console_scripts]\n" + scripts + "\n").encode()))
    for lic in project["license-files"]:
        with open(os.path.join(ROOT, lic), "rb") as f:
            files.append((info + "/licenses/" + lic, f.read()))

    def digest(data):
        return "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()

    record = "".join("%s,%s,%d\n" % (n, digest(d), len(d)) for n, d in files) + info + "/RECORD,,\n"
    files.append((info + "/RECORD", record.encode()))
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "%s-%s-%s.whl" % (name, version, tag))
    partial = path + ".partial"
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as z:
        for n, d in files:
            i = zipfile.ZipInfo(n, date_time=(2020, 1, 1, 0, 0, 0))  # the same bytes from the same build
            i.external_attr = (0o755 if n.endswith((".pyd", ".so")) else 0o644) << 16
            i.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(i, d)
    os.replace(partial, path)
    print(path)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: platform_wheel.py MODULE TAG OUT_DIR")
    main(*sys.argv[1:])
