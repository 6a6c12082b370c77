"""The command line trusted with a whole library, unattended, as a careless user or an attacker meets it: hostile
and broken files, full and read-only disks, FIFOs, names that are not UTF-8, colliding names, Ctrl-C. Every case
ends in exit 0 with whole files, or a non-zero exit with one line on stderr; nothing of the user's is overwritten
and nothing is left half-written.

Run by ctest (cli_trust) as: python3 -m pytest tests/cli/test_trust.py with PROBELIGHTS_BIN set."""
import hashlib
import json
import math
import os
import resource
import shutil
import signal
import struct
import subprocess
import time

import pytest

BIN = os.environ.get("PROBELIGHTS_BIN", os.path.join(os.path.dirname(__file__), "..", "..", "build", "bin",
                                                     "probelights"))
PROBE = os.path.join(os.path.dirname(__file__), "..", "..", "assets", "noon_grass_1k.hdr")


def run(*args, timeout=120, memory=None, **kw):
    def limit():
        if memory:
            resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    if "stdout" not in kw:
        kw["capture_output"] = True
    return subprocess.run([BIN, *map(os.fsdecode, args)], timeout=timeout, preexec_fn=limit, **kw)


def one_line_error(p, code=2, text=""):
    err = p.stderr.decode(errors="replace")
    assert p.returncode == code and err.count("\n") == 1 and err.startswith("probelights: error: "), (
        p.returncode, err)
    assert text in err, err
    return err


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


def oiio(*args):
    subprocess.run(["oiiotool", *map(str, args)], check=True, capture_output=True)


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """Small probes made from the bundled one: 64x32 .hdr, EXR, 16-bit TIFF, 8-bit PNG."""
    d = tmp_path_factory.mktemp("small")
    oiio(PROBE, "--resize", "64x32", "-o", d / "sky.hdr")
    oiio(d / "sky.hdr", "-d", "half", "-o", d / "sky.exr")
    oiio(d / "sky.hdr", "-d", "uint16", "-o", d / "sky16.tif")
    oiio(d / "sky.hdr", "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o", d / "sky.png")  # tagged sRGB
    oiio(d / "sky.hdr", "-d", "uint8", "-o", d / "linear.png")  # tagged linear (gAMA 1.0)
    return d


@pytest.fixture
def tmpfs(tmp_path):
    """A 256 KB tmpfs, unmounted afterwards (root only)."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root")
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    p = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(mnt)], capture_output=True)
    if p.returncode != 0:  # a container without the right to mount
        pytest.skip("cannot mount a small tmpfs here: " + p.stderr.decode(errors="replace").strip())
    yield mnt
    subprocess.run(["umount", "-l", str(mnt)], check=True)


def fill(mnt):
    with open(mnt / "filler", "wb", buffering=0) as f:
        try:
            while True:
                f.write(b"\0" * 4096)
                f.flush()
        except OSError:
            pass


def leftovers(folder):
    return [n for n in os.listdir(folder) if ".part-" in n]


def load(path):
    with open(path) as f:
        return json.load(f)


# Names: nothing the command did not write is overwritten, no two results share a file.

def test_library_names_never_collide_nor_overwrite_the_users_files(tmp_path, small):
    lib = tmp_path / "lib"
    lib.mkdir()
    for name in ("sky.hdr", "sky.exr", "sky.png"):
        shutil.copy(small / name, lib / name)
    shutil.copy(small / "sky.exr", lib / "sky_2.exr")
    shutil.copy(small / "sky16.tif", lib / "summary.tif")
    shutil.copy(small / "sky16.tif", lib / "Sky.tif")  # the same name as sky on a case-insensitive disk
    (lib / "sky_3.json").write_text("the user's notes\n")
    before = {n: digest(lib / n) for n in os.listdir(lib)}
    p = run("bake", lib, "--out-dir", lib, "--previews", "--lights", "4", "-q")
    assert p.returncode == 0, p.stderr
    for n, h in before.items():
        assert digest(lib / n) == h, n + " was overwritten"
    s = load(lib / "summary.json")
    assert s["baked"] == s["probes"] == 6, s
    outputs = [r["output"] for r in s["results"]]
    assert len({o.lower() for o in outputs}) == 6 and "summary.json" not in outputs, outputs
    assert "sky_3.json" not in outputs
    sources = {load(lib / o)["source"]["path"] for o in outputs}
    assert len(sources) == 6
    for r in s["results"]:
        assert load(lib / r["output"])["source"]["path"] == r["probe"]
        assert r["preview"] not in before
    # Baked again into the same folder: its own results are replaced, under the same names.
    p = run("bake", *(str(lib / n) for n in sorted(before) if not n.endswith(".json")), "--out-dir", lib,
            "--previews", "--lights", "4", "-q")
    assert p.returncode == 0, p.stderr
    assert [r["output"] for r in load(lib / "summary.json")["results"]] == outputs
    assert not leftovers(lib)


def test_a_summary_json_of_the_users_is_refused(tmp_path, small):
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.json").write_text('{"mine": true}\n')
    one_line_error(run("bake", small / "sky.hdr", "--out-dir", out), text="not written by probelights")
    assert load(out / "summary.json") == {"mine": True}
    # A summary of an earlier version (no "generator" key) is the bake's own, and replaced.
    (out / "summary.json").write_text('{"probes": 1, "baked": 1, "failed": 0, "results": []}\n')
    assert run("bake", small / "sky.hdr", "--out-dir", out, "-q").returncode == 0
    assert load(out / "summary.json")["generator"].startswith("probelights")


@pytest.mark.parametrize("flag", ["-o", "--preview"])
def test_an_output_that_is_the_probe_is_refused(tmp_path, small, flag):
    probe = tmp_path / "sky.hdr"
    shutil.copy(small / "sky.hdr", probe)
    h = digest(probe)
    one_line_error(run("bake", probe, flag, probe), text="is the probe itself")
    link = tmp_path / "link.hdr"
    link.symlink_to(probe)
    one_line_error(run("bake", probe, flag, link), text="is the probe itself")
    one_line_error(run("sh", probe, "--bands", "2", "-o", probe), text="is the probe itself")
    assert digest(probe) == h


@pytest.mark.parametrize("args", [["-o", ""], ["--preview", ""], ["--out-dir", ""]])
def test_empty_output_names_are_refused(small, args):
    one_line_error(run("bake", small / "sky.hdr", *args), text="empty")


# Writes: whole or not at all, and a failure is a failure.

def test_a_full_disk_keeps_the_old_file_and_fails(tmpfs, small):
    old = tmpfs / "lights.json"
    old.write_text('{"old": true}\n')
    fill(tmpfs)
    one_line_error(run("bake", small / "sky.hdr", "--lights", "64", "-o", old, "-q"),
                   text="No space left on device")
    assert load(old) == {"old": True}
    one_line_error(run("bake", small / "sky.hdr", "--preview", tmpfs / "p.png", "-q"),
                   text="No space left on device")
    assert not (tmpfs / "p.png").exists()
    one_line_error(run("sh", small / "sky.hdr", "--bands", "8", "-o", tmpfs / "sh.json"))
    one_line_error(run("sample", small / "sky.hdr", "--bands", "4", "--epsilon", "0.01", "--samples",
                       "20000", "-o", tmpfs / "s.json"))
    one_line_error(run("bake", small / "sky.hdr", "--out-dir", tmpfs / "lib"),
                   text="cannot write to output directory")
    assert not leftovers(tmpfs)


def test_standard_output_to_a_full_device_fails():
    with open("/dev/full", "wb") as full:
        for args in (["bake", PROBE, "-o", "-"], ["bake", PROBE, "--lights", "2"], ["sh", PROBE, "--bands", "2"]):
            p = run(*args, stdout=full, stderr=subprocess.PIPE)
            assert p.returncode != 0 and b"standard output" in p.stderr, (args, p.returncode, p.stderr)


def test_a_read_only_disk_fails_before_work(tmpfs, small):
    subprocess.run(["mount", "-o", "remount,ro", str(tmpfs)], check=True)
    one_line_error(run("bake", small / "sky.hdr", "-o", tmpfs / "x.json"), text="Read-only file system")
    one_line_error(run("bake", small / "sky.hdr", "--out-dir", tmpfs), text="Read-only file system")


def test_ctrl_c_in_a_library_leaves_whole_files_and_a_summary(tmp_path):
    lib = tmp_path / "lib"
    lib.mkdir()
    for i in range(40):
        os.symlink(os.path.abspath(PROBE), lib / f"p{i:02}.hdr")
    out = tmp_path / "out"
    for signals in (1, 2):
        shutil.rmtree(out, ignore_errors=True)
        proc = subprocess.Popen([BIN, "bake", str(lib), "--out-dir", str(out), "--previews", "--lights",
                                 "128", "--evaluate", "-q"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        deadline = time.time() + 60
        while time.time() < deadline and not (out.exists() and any(n.endswith(".png") for n in os.listdir(out))):
            time.sleep(0.01)
        for _ in range(signals):
            proc.send_signal(signal.SIGINT)
            time.sleep(0.05)
        proc.communicate(timeout=120)
        assert proc.returncode in (130, -signal.SIGINT), proc.returncode
        assert not leftovers(out), os.listdir(out)
        for n in os.listdir(out):
            if n.endswith(".json"):
                load(out / n)
            else:
                subprocess.run(["oiiotool", "--info", str(out / n)], check=True, capture_output=True)
        if signals == 1:
            s = load(out / "summary.json")
            assert s["stopped"] == "interrupted" and 0 < s["baked"] < 40 and s["not_started"] > 0, s
            assert all((out / r["output"]).exists() for r in s["results"])


# Inputs that are not files, names that are not text.

def test_a_fifo_is_refused_not_waited_on(tmp_path, small):
    fifo = tmp_path / "f.hdr"
    os.mkfifo(fifo)
    one_line_error(run("bake", fifo, timeout=20), text="FIFO")
    shutil.copy(small / "sky.hdr", tmp_path / "a.hdr")
    p = run("bake", str(tmp_path / "*.hdr"), "--out-dir", tmp_path / "out", "-q", timeout=20)
    assert p.returncode == 3 and b"FIFO" in p.stderr, p
    assert load(tmp_path / "out" / "summary.json")["baked"] == 1


def test_devices_folders_and_link_loops_say_what_they_are(tmp_path):
    one_line_error(run("bake", "/dev/zero", timeout=20), text="device")
    one_line_error(run("bake", tmp_path), text="directory")
    (tmp_path / "loop.hdr").symlink_to(tmp_path / "loop.hdr")
    one_line_error(run("bake", tmp_path / "loop.hdr"), text="symbolic links")


def test_a_name_that_is_not_utf8_is_kept(tmp_path, small):
    name = os.fsencode(tmp_path) + b"/sky\xff\xfe.hdr"
    shutil.copy(small / "sky.hdr", name)
    out = tmp_path / "one.json"
    p = run("bake", name, "-o", out, "-q")
    assert p.returncode == 0, p.stderr
    assert load(out)["source"]["path"].endswith("sky\ufffd\ufffd.hdr")
    p = run("bake", tmp_path, "--out-dir", tmp_path / "lib", "--previews", "-q")
    assert p.returncode == 0, p.stderr
    s = load(tmp_path / "lib" / "summary.json")
    assert s["baked"] == 1 and os.path.exists(tmp_path / "lib" / s["results"][0]["output"])
    one_line_error(run("bake", os.fsencode(tmp_path) + b"/nope\xff.hdr"), text="no such file")


# Files that lie or are broken.

def test_a_header_claiming_more_pixels_than_its_bytes_is_refused_before_memory_is_taken(tmp_path):
    hdr = tmp_path / "huge.hdr"
    # Refused by OpenImageIO 3's reader (sides over 65535; a size its bytes cannot hold) or by ours (image.cpp
    # checkClaims, for readers without such checks), in one line, before the memory is taken.
    for size in (b"-Y 300000 +X 600000", b"-Y 32500 +X 65000", b"-Y 20000 +X 40000"):
        hdr.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + size + b"\n" + b"\x02\x02\x80\x00" * 50)
        for options in ((), ("--resolution", "256")):
            err = one_line_error(run("bake", hdr, *options, memory=1 << 30))
            assert "65535" in err or "claims" in err, err
    square = tmp_path / "square.hdr"
    square.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2147483647 +X 2147483647\n" + b"\0" * 64)
    one_line_error(run("bake", square, "--projection", "mirror-ball", memory=1 << 30))


def test_a_cut_tiff_is_an_error(tmp_path, small):
    data = (small / "sky16.tif").read_bytes()
    for keep in (0.001, 0.1, 0.5, 0.9):
        cut = tmp_path / f"cut{keep}.tif"
        cut.write_bytes(data[:int(len(data) * keep)])
        one_line_error(run("bake", cut), text="cannot read probe")


def test_a_data_window_inside_the_display_window_is_placed_in_it(tmp_path, small):
    crop = tmp_path / "crop.exr"
    oiio(small / "sky.exr", "--crop", "32x8+16+4", "-o", crop)
    p = run("bake", crop, "--lights", "2", "-o", tmp_path / "c.json")
    assert p.returncode == 0, p.stderr
    d = load(tmp_path / "c.json")
    assert (d["source"]["width"], d["source"]["height"]) == (64, 32)
    assert any("data window 32x8 at (16, 4)" in n["text"] for n in d["notes"]), d["notes"]
    # The same light as the full probe with everything outside the window black.
    zeroed = tmp_path / "zeroed.exr"
    oiio(crop, "--croptofull", "-o", zeroed)
    run("bake", zeroed, "--lights", "2", "-o", tmp_path / "z.json")
    z = load(tmp_path / "z.json")
    assert all(math.isclose(a, b, rel_tol=1e-9) for a, b in zip(d["total_rgb"], z["total_rgb"]))


def test_display_referred_images_are_decoded_to_linear_light(tmp_path, small):
    p = run("bake", small / "sky.png", "--lights", "2", "-o", tmp_path / "png.json")
    assert p.returncode == 0, p.stderr
    d = load(tmp_path / "png.json")
    assert any("8-bit png: sRGB values decoded to linear light" in n["text"] for n in d["notes"]), d["notes"]
    linear = tmp_path / "linear.exr"
    oiio(small / "sky.png", "--colorconvert", "sRGB", "linear", "-d", "float", "-o", linear)
    run("bake", linear, "--lights", "2", "-o", tmp_path / "lin.json")
    ref = load(tmp_path / "lin.json")["total_rgb"]
    assert all(math.isclose(a, b, rel_tol=1e-3) for a, b in zip(d["total_rgb"], ref)), (d["total_rgb"], ref)
    p = run("bake", small / "linear.png", "--lights", "2", "-o", tmp_path / "linear.json")
    assert {"kind": "reading", "text": "8-bit png: read as linear light", "detail": "the file says linear"} in \
        load(tmp_path / "linear.json")["notes"]
    p = run("bake", small / "sky16.tif", "--lights", "2", "-o", tmp_path / "tif.json")
    assert any("16-bit tiff" in n["text"] for n in load(tmp_path / "tif.json")["notes"])


def test_channels_that_are_not_colour_are_refused(tmp_path, small):
    two = tmp_path / "two.exr"
    oiio(small / "sky.exr", "--ch", "R,G", "-o", two)
    one_line_error(run("bake", two), text="are not grey and alpha")
    ya = tmp_path / "ya.exr"
    oiio(small / "sky.exr", "--ch", "Y=R,A=G", "-o", ya)
    p = run("bake", ya, "--lights", "2", "-o", tmp_path / "ya.json")
    assert p.returncode == 0 and any("read as grey" in n["text"] for n in load(tmp_path / "ya.json")["notes"])
    xyz = tmp_path / "xyz.exr"
    oiio(small / "sky.exr", "--ch", "X=R,Y=G,Z=B", "-o", xyz)
    one_line_error(run("bake", xyz), text="do not begin with R, G, B")


# Small things.

@pytest.mark.parametrize("value", ["0", "-1", "0%", "100%"])
def test_max_error_out_of_range_is_refused(small, value):
    one_line_error(run("bake", small / "sky.hdr", "--max-error", value), text="--max-error")


def test_an_unreadable_folder_says_so(tmp_path, small):
    if os.geteuid() == 0 and shutil.which("setpriv") is None:
        pytest.skip("needs setpriv to drop root")
    lib = tmp_path / "lib"
    lib.mkdir()
    shutil.copy(small / "sky.hdr", lib / "a.hdr")
    lib.chmod(0o300)
    os.chmod(tmp_path, 0o777)
    drop = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] if os.geteuid() == 0 else []
    if drop and subprocess.run([*drop, BIN, "--version"], capture_output=True).returncode != 0:
        # e.g. a clone under /root (mode 700): user nobody cannot load the build's own OpenImageIO (build/lib)
        pytest.skip("user nobody cannot run this build (its folder or build/lib is not open to other users)")
    p = subprocess.run([*drop, BIN, "bake", str(lib), "--out-dir", str(tmp_path / "o")], capture_output=True)
    one_line_error(p, text="Permission denied")


def test_sh_bands_beyond_what_finishes_are_refused(small):
    for command in (["sh", small / "sky.hdr"], ["sample", small / "sky.hdr", "--epsilon", "0.01", "--samples", "9"],
                    ["bake", small / "sky.hdr", "--method", "sh"]):
        one_line_error(run(*command, "--bands", "256", timeout=20), text="at most 64")


# Negative light: the lights are never negative and carry the probe's integral per channel.

SHARED_PMNDRS = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "hdri",
                             "pmndrs_esplanade_dwab.exr")


@pytest.mark.parametrize("source", ["unsharp", "pmndrs"])
def test_much_negative_light_keeps_the_integral(tmp_path, source):
    if source == "unsharp":  # the bundled probe over-sharpened: 60 % of its light negative
        probe = tmp_path / "unsharp.exr"
        oiio(PROBE, "--unsharp:kernel=gaussian:width=9:contrast=4", "-o", probe)
    elif os.path.exists(SHARED_PMNDRS):  # a lossy DWAB EXR's ringing, -6.5 %
        probe = SHARED_PMNDRS
    else:
        pytest.skip("../shared/hdri is not beside the repository")
    for method in ("variance", "median-cut", "sh"):
        for n in (64, 1024):
            out = tmp_path / f"{method}{n}.json"
            p = run("bake", probe, "--method", method, "--lights", str(n), "-q", "-o", out)
            assert p.returncode == 0, p.stderr
            d = load(out)
            for k in range(3):
                s = sum(light["rgb"][k] for light in d["lights"])
                assert min(light["rgb"][k] for light in d["lights"]) >= 0
                assert abs(s - d["total_rgb"][k]) <= 1e-9 * d["total_rgb"][k], (method, n, k, s, d["total_rgb"])
