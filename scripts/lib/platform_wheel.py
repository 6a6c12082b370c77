"""Writes the Python package's wheel for Windows or macOS around a module built by the zig sub-build
(scripts/wheel_platform.sh) and the .dist-info that pyproject.toml's backend writes (scikit-build-core's
prepare_metadata_for_build_wheel, run there: the Linux wheels' METADATA, entry point and licence, made by the same
code); only WHEEL's tag is this platform's.
    platform_wheel.py MODULE DIST_INFO TAG OUT_DIR      -> prints the wheel's path
TAG is a wheel tag, e.g. cp311-cp311-win_amd64 or cp313-cp313-macosx_11_0_arm64. The wheel is written whole
(a temporary name, then renamed)."""

import base64
import hashlib
import os
import re
import sys
import zipfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def main(module, dist_info, tag, out_dir):
    if not os.path.isfile(os.path.join(dist_info, "METADATA")):
        sys.exit("platform_wheel.py: no METADATA in '%s'" % dist_info)
    info = os.path.basename(dist_info.rstrip("/"))
    name = info.split("-")[0]
    version = info[len(name) + 1:-len(".dist-info")]
    files = []  # (name in the wheel, bytes)
    package = os.path.join(ROOT, "python", name)
    for entry in sorted(os.listdir(package)):
        if re.fullmatch(r"[\w.]+\.(py|pyi|typed)", entry):
            with open(os.path.join(package, entry), "rb") as f:
                files.append(("%s/%s" % (name, entry), f.read()))
    with open(module, "rb") as f:
        files.append(("%s/%s" % (name, os.path.basename(module)), f.read()))
    for folder, _, names in sorted(os.walk(dist_info)):
        for entry in sorted(names):
            path = os.path.join(folder, entry)
            inside = info + "/" + os.path.relpath(path, dist_info).replace(os.sep, "/")
            with open(path, "rb") as f:
                data = f.read()
            if entry == "WHEEL" and folder == dist_info:
                data = re.sub(rb"(?m)^Tag: .*$", b"Tag: " + tag.encode(), data)
            if entry != "RECORD":
                files.append((inside, data))

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
    if len(sys.argv) != 5:
        sys.exit("usage: platform_wheel.py MODULE DIST_INFO TAG OUT_DIR")
    main(*sys.argv[1:])
