"""The _probelights module from plain Python (the system Python Blender runs): arrays in, numpy arrays out."""

import json
import math
import os
import threading

import numpy as np
import pytest

import _probelights as pl

# The add-on's module (build "pixels": every platform's, tests/wine/ runs Windows') has no file reading; the full
# module (build/python) and the CLI run on Linux.
full_only = pytest.mark.skipif(pl.build != "full", reason="reads files or runs the CLI: the full module's")


def test_uniform_probe_total_is_four_pi_l():
    a = np.full((64, 128, 3), (0.5, 1.0, 2.0), np.float32)
    r = pl.bake(a, lights=8)
    assert r["lights"]["direction"].shape == (8, 3) and r["lights"]["rgb"].shape == (8, 3) and r["lights"]["rect"].shape == (8, 4)
    assert np.allclose(r["lights"]["rgb"].sum(axis=0), 4 * math.pi * np.array([0.5, 1.0, 2.0]), rtol=1e-10)
    assert np.allclose(r["total_rgb"], r["lights"]["rgb"].sum(axis=0), rtol=1e-12)
    assert np.allclose(np.linalg.norm(r["lights"]["direction"], axis=1), 1.0)
    assert r["lights"]["energy_share"].sum() == pytest.approx(1.0)


def test_flipped_and_strided_views_are_read_in_place():
    rng = np.random.default_rng(3)
    a = rng.random((32, 64, 4), dtype=np.float32)
    flipped = a[::-1]  # Blender's rows are bottom-up: the add-on passes this view
    r1 = pl.bake(np.ascontiguousarray(flipped), lights=5)
    r2 = pl.bake(flipped, lights=5)
    assert np.array_equal(r1["lights"]["rgb"], r2["lights"]["rgb"]) and np.array_equal(r1["lights"]["direction"], r2["lights"]["direction"])
    # Alpha is ignored; a grey H x W array is replicated.
    r3 = pl.bake(np.ascontiguousarray(a[..., :3]), lights=5)
    r4 = pl.bake(a, lights=5)
    assert np.array_equal(r3["lights"]["rgb"], r4["lights"]["rgb"])
    grey = pl.bake(a[..., 0].copy(), lights=3)
    assert np.allclose(grey["lights"]["rgb"][:, 0], grey["lights"]["rgb"][:, 1])


def test_broadcast_views_are_read_as_the_arrays_they_show():
    """A stride of 0 (np.broadcast_to) repeats a row or a pixel: read as the array it shows, never past it."""
    row = np.random.default_rng(4).random((1, 128, 3), dtype=np.float32)
    shown = np.broadcast_to(row, (64, 128, 3))
    r1 = pl.bake(shown, lights=6)
    r2 = pl.bake(np.ascontiguousarray(shown), lights=6)
    assert np.array_equal(r1["lights"]["rgb"], r2["lights"]["rgb"])
    pixel = np.broadcast_to(np.ones((1, 1, 3), np.float32), (64, 128, 3))
    assert list(pl.bake(pixel, lights=4)["total_rgb"]) == pytest.approx([4 * math.pi] * 3, rel=1e-9)


def test_other_dtypes_are_converted():
    r = pl.bake(np.ones((8, 16, 3), np.float64), lights=2)
    assert r["lights"]["rgb"].sum() == pytest.approx(3 * 4 * math.pi)


def test_lat_long_convention():
    a = np.zeros((32, 64, 3), np.float32)
    a[15, 16] = 10.0  # a quarter from the left, just above the horizon: +Y
    d = pl.bake(a, lights=1)["lights"]["direction"][0]
    assert d[1] > 0.99


@pytest.mark.parametrize("kwargs, message", [
    ({"lights": 0}, "at least 1"),
    ({"method": "magic"}, "unknown method"),
    ({"projection": "cube"}, "unknown projection"),
    ({"resolution": "huge"}, "unknown resolution"),
    ({"nonfinite": "maybe"}, "non-finite policy"),
    ({"method": "sh", "cuts": "both"}, "both cuts are variance and median cut"),
    ({"method": "sh", "cuts": "auto"}, "both cuts are variance and median cut"),
    ({"cuts": "both", "max_error": 0.05}, "both cuts take a light count"),
    ({"cuts": "all"}, "unknown cuts 'all': use one, both or auto"),
])
def test_bad_requests_raise_with_the_cores_message(kwargs, message):
    with pytest.raises(pl.Error, match=message):
        pl.bake(np.ones((8, 16, 3), np.float32), **kwargs)
    assert issubclass(pl.Error, ValueError)


@full_only
@pytest.mark.parametrize("cuts, lights, said", [("both", 8, "fitted"), ("auto", 8, "fitted"), ("auto", 20, "started")])
def test_both_cuts_keep_one_cut_and_say_which(bundled_probe, cuts, lights, said):
    kw = dict(lights=lights, centroid="energy2", effects="diffuse,shadow", refit=True, move_directions=True,
              evaluator_width=128)
    r = pl.bake_file(bundled_probe, cuts=cuts, **kw)
    assert r["method"] in ("variance", "median-cut")
    note = [n for n in r["notes"] if n["kind"] == "chosen"]
    assert note and note[0]["text"] == "both cuts %s: %s kept" % (said, r["method"]), r["notes"]
    alone = pl.bake_file(bundled_probe, method=r["method"], **kw)
    assert np.array_equal(r["lights"]["rgb"], alone["lights"]["rgb"])
    assert r["evaluation"]["shadow"] == alone["evaluation"]["shadow"]


def test_bad_pixels():
    a = np.ones((8, 16, 3), np.float32)
    a[2, 3, 0] = np.nan
    with pytest.raises(pl.Error, match=r"1 NaN/Inf samples, first at pixel \(3, 2\)") as raised:
        pl.bake(a)
    # The way past it in the module's words, and typed for a shell that words it its own way (the add-on).
    assert str(raised.value).endswith("; to read them as 0: nonfinite='zero'"), raised.value
    assert raised.value.remedy == ("to read them as 0", "nonfinite", ["zero"])
    assert str(raised.value) == raised.value.reason + "; to read them as 0: nonfinite='zero'"
    r = pl.bake(a, nonfinite="zero", lights=2)
    assert np.isfinite(r["lights"]["rgb"]).all() and r["source"]["non_finite_samples"] == 1
    with pytest.raises(pl.Error, match="H x W"):
        pl.bake(np.ones(10, np.float32))
    with pytest.raises(pl.Error, match="empty"):
        pl.bake(np.ones((0, 0, 3), np.float32))


@full_only
def test_bake_files_needs_a_path():
    with pytest.raises(pl.Error, match="at least one path"):
        pl.bake_files([])


@full_only
def test_bake_file_errors(tmp_path):
    with pytest.raises(pl.Error, match="no such file"):
        pl.bake_file(str(tmp_path / "missing.exr"))
    (tmp_path / "junk.hdr").write_text("not an image")
    with pytest.raises(pl.Error, match="cannot read probe"):
        pl.bake_file(str(tmp_path / "junk.hdr"))


@full_only
def test_paths_are_what_the_file_system_has(tmp_path, bundled_probe):
    """pathlib paths and bytes are taken; a name that is not UTF-8 comes back as os.fsdecode has it (the same
    file again) and loses no result; a FIFO is refused, not waited on; a NUL is refused, not cut."""
    import pathlib
    import shutil
    small = tmp_path / "sky.hdr"
    shutil.copy(bundled_probe, small)
    assert pl.bake_file(pathlib.Path(small), lights=2)["source"]["path"] == str(small)
    odd = os.fsencode(tmp_path) + b"/odd\xff.hdr"
    shutil.copy(bundled_probe, odd)
    r = pl.bake_file(odd, lights=2)
    assert os.fsencode(r["source"]["path"]) == odd
    results = pl.bake_files([tmp_path], lights=2)
    assert len(results) == 2 and all("error" not in r for r in results)
    assert {os.fsencode(r["source"]["path"]) for r in results} == {odd, os.fsencode(small)}
    assert len(pl.bake_files(pathlib.Path(tmp_path), lights=2)) == 2  # one path alone is a list of one
    os.mkfifo(tmp_path / "f.hdr")
    with pytest.raises(pl.Error, match="FIFO"):
        pl.bake_file(tmp_path / "f.hdr")
    with pytest.raises(pl.Error, match="NUL"):
        pl.bake_file(str(small) + "\0.exr")
    with pytest.raises(pl.Error, match="no such file") as e:
        pl.bake_file(os.fsdecode(odd) + ".missing")
    assert os.fsdecode(odd) in str(e.value)


@full_only
def test_max_error_below_zero_is_refused(bundled_probe):
    with pytest.raises(pl.Error, match="max_error"):
        pl.bake_file(bundled_probe, max_error=-1)


@full_only
def test_bake_file_on_the_bundled_probe(bundled_probe):
    r = pl.bake_file(bundled_probe, lights=16)
    assert r["source"]["width"] == 1024 and r["source"]["projection"] == "latlong"
    assert len(r["lights"]["rgb"]) == 16 and r["source"]["path"] == bundled_probe
    assert r["notes"][0] == {"kind": "reading", "text": "projection: lat-long", "detail": "auto: the image is 2:1"}
    assert set(r["timings_ms"]) == {"load", "tables", "partition", "lights"} and r["timings_ms"]["load"] > 0


@full_only
def test_bake_file_reads_band_by_band_into_a_coarse_grid(bundled_probe):
    """With nothing asked but the lights, on a grid coarser than the image, bake_file and bake_files read the
    file band by band into the grid (never whole) and give the lights of a whole load (evaluate=True needs the
    pixels, so that bake loads it whole)."""
    banded = pl.bake_file(bundled_probe, lights=20, resolution="256")
    whole = pl.bake_file(bundled_probe, lights=20, resolution="256", evaluate=True)
    library = pl.bake_files([bundled_probe], lights=20, resolution="256")[0]
    assert any("band by band" in n["text"] for n in banded["notes"])
    assert not any("band by band" in n["text"] for n in whole["notes"])
    for r in (banded, library):
        for column in ("rgb", "direction", "rect", "solid_angle", "angular_radius", "angle"):
            assert np.array_equal(r["lights"][column], whole["lights"][column]), column
        assert np.array_equal(r["total_rgb"], whole["total_rgb"])


def test_touch_pages_maps_a_fresh_buffer_that_stays_usable():
    buf = np.empty(3 * 1024 * 1024 + 5, np.float32)  # not a whole number of pages
    assert pl.touch_pages(buf) is None
    buf[:] = 2.0
    assert float(buf.sum()) == 2.0 * buf.size


def key_paths(value, prefix=""):
    """Every key path of a result: nested objects by name, a table (the JSON's list of rows, the module's dict
    of columns) by its columns."""
    if isinstance(value, list) and value and isinstance(value[0], dict):
        value = {k: None for row in value for k in row}
    if not isinstance(value, dict):
        return {prefix}
    return {p for k, v in value.items() for p in key_paths(v, prefix + "." + k if prefix else k)}


@full_only
@pytest.mark.parametrize("method", ["variance", "sh"])
def test_the_module_and_the_cli_give_one_layout(bundled_probe, tmp_path, method):
    """The module's dict and the CLI's JSON come from the core's one result layout (result_layout.h): the same
    keys, nested the same way, and the same values."""
    import json
    import subprocess
    cli = os.path.join(os.environ.get("PROBELIGHTS_BUILD", "build"), "bin", "probelights")
    out = tmp_path / "r.json"
    subprocess.run([cli, "bake", bundled_probe, "--method", method, "--max-error", "2%", "--effects",
                    "diffuse,shadow", "--refit", "-q", "-o", str(out)], check=True)
    document = json.loads(out.read_text())
    r = pl.bake_file(bundled_probe, method=method, max_error=0.02, effects="diffuse,shadow", refit=True)
    assert key_paths(r) == key_paths(document)
    assert r["evaluation"]["auto_count"]["lights"] == document["evaluation"]["auto_count"]["lights"]
    assert np.allclose(r["lights"]["rgb"], [row["rgb"] for row in document["lights"]], rtol=1e-12)
    assert list(r["evaluation"]["auto_count"]["tried"]["lights"]) == [
        row["lights"] for row in document["evaluation"]["auto_count"]["tried"]]


def test_the_gil_is_released_and_results_are_deterministic():
    a = np.random.default_rng(5).random((256, 512, 3), dtype=np.float32)
    reference = pl.bake(a, lights=33)
    results = [None] * 4

    def work(i):
        results[i] = pl.bake(a, lights=33)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r["lights"]["rgb"], reference["lights"]["rgb"])


def test_sh_project_white_furnace_and_irradiance():
    a = np.full((128, 256, 3), 1.5, np.float32)
    c = pl.sh_project(a, bands=5)
    assert c.shape == (25, 3)
    assert c[0, 0] == pytest.approx(2 * math.sqrt(math.pi) * 1.5, rel=1e-12)
    assert np.abs(c[1:]).max() < 1e-9
    e = pl.sh_project(a, bands=3, irradiance=True)
    assert e[0, 0] * 0.5 / math.sqrt(math.pi) == pytest.approx(math.pi * 1.5, rel=1e-12)  # E = pi L everywhere


def test_sh_sample_and_sh_bake(bundled_probe):
    a = np.zeros((64, 128, 3), np.float32) + 0.1
    a[10, 30] = 500.0
    d, p = pl.sh_sample(a, bands=6, epsilon=0.01, samples=500, seed=7)
    assert d.shape == (500, 3) and p.shape == (500,) and (p > 0).all()
    assert np.allclose(np.linalg.norm(d, axis=1), 1)
    d2, p2 = pl.sh_sample(a, bands=6, epsilon=0.01, samples=500, seed=7)
    assert np.array_equal(d, d2) and np.array_equal(p, p2)
    r = pl.bake(a, method="sh", lights=8, bands=6)
    assert len(r["lights"]["rgb"]) == 8 and np.allclose(r["lights"]["rgb"].sum(0), r["total_rgb"], rtol=1e-12)
    with pytest.raises(pl.Error, match="epsilon"):
        pl.sh_sample(a, bands=4, epsilon=0.7)


@full_only
def test_the_module_and_the_cli_give_one_tradeoff_layout(bundled_probe, tmp_path):
    import json
    import subprocess
    cli = os.path.join(os.environ.get("PROBELIGHTS_BUILD", "build"), "bin", "probelights")
    out = tmp_path / "t.json"
    subprocess.run([cli, "tradeoff", bundled_probe, "--counts", "4", "--methods", "variance,sh", "-o", str(out)],
                   check=True, stdout=subprocess.DEVNULL)
    document = json.loads(out.read_text())
    a = np.zeros((64, 128, 3), np.float32) + 0.2
    r = pl.tradeoff(a, counts=[4], methods=["variance", "sh"], evaluator_width=64)
    assert key_paths(r) == key_paths(document)
    # One grid by default in both, from the core's table (full and 256 px; the SH method cuts on none: "-").
    assert r["rows"]["resolution"] == [row["resolution"] for row in document["rows"]] == [
        "full", "full", "256", "256", "-", "-"]


def test_tradeoff_rows(bundled_probe):
    import numpy as np
    a = np.zeros((64, 128, 3), np.float32) + 0.2
    a[12, 40] = 3000.0
    rows = pl.tradeoff(a, counts=[4, 16], methods=["variance"], resolutions=["auto"], evaluator_width=128)["rows"]
    assert list(zip(rows["lights"], rows["refit"])) == [(4, False), (4, True), (16, False), (16, True)]
    plain = {n: e for n, e, refit in zip(rows["lights"], rows["diffuse"], rows["refit"]) if not refit}
    assert plain[16] < plain[4] and (rows["bake_ms"] > 0).all() and (rows["shadow"] >= 0).all()
    assert rows["method"] == ["variance"] * 4 and rows["resolution"] == ["auto"] * 4
    with pytest.raises(pl.Error, match="at least 1"):
        pl.tradeoff(a, counts=[0])
    # numpy's numbers as Python's (numpy 2 writes np.float64(0.05) for repr: it was refused).
    plain = pl.bake(a, lights=8, max_error=0.05, effects="diffuse,shadow")
    numpy = pl.bake(a, lights=np.int32(8), max_error=np.float64(0.05), effects=np.str_("diffuse,shadow"))
    assert (plain["lights"]["rgb"] == numpy["lights"]["rgb"]).all()
    # Any sequence of counts: a numpy array, a range, a tuple.
    for counts in (np.array([4, 16]), range(4, 17, 12), (4, 16)):
        again = pl.tradeoff(a, counts=counts, methods=["variance"], resolutions=["auto"], evaluator_width=128)
        assert list(again["rows"]["lights"]) == [4, 4, 16, 16], counts
    for bad, message in (({"lights": 4}, "unknown option 'lights'"), ({"counts": []}, "empty list"),
                         ({"counts": [[4]]}, "list in a list"), ({"methods": ["nope"]}, "nope"),
                         ({"resolutions": "tiny"}, "tiny")):
        with pytest.raises(pl.Error, match=message):
            pl.tradeoff(a, **bad)


def test_a_tradeoff_row_is_the_bake_its_preset_makes(bundled_probe):
    """preset= makes and judges each row as that recipe's bake (the add-on's tradeoff asks for its bake's preset):
    the refit row of one cut at 16 lights has the errors of bake(preset=..., cuts='one') at 16; without the refit
    the row is the bake without it. (Beside refit rows, a plain row's angles are fitted on the refit's denser
    ground points: 1e-4 of its error apart.)"""
    import numpy as np
    a = np.zeros((64, 128, 3), np.float32) + 0.2
    a[12, 40] = 3000.0
    grid = dict(counts=[16], methods=["variance"], resolutions=["auto"])
    for preset in ("blender", "blender-eevee"):
        refit_rows = pl.tradeoff(a, preset=preset, **grid)["rows"]
        plain_rows = pl.tradeoff(a, preset=preset, refit=False, **grid)["rows"]
        refit = pl.bake(a, preset=preset, lights=16, cuts="one")["evaluation"]
        plain = pl.bake(a, preset=preset, lights=16, cuts="one", refit=False)["evaluation"]
        assert list(refit_rows["refit"]) == [False, True] and list(plain_rows["refit"]) == [False]
        for effect in ("diffuse", "shadow"):
            assert refit_rows[effect][1] == pytest.approx(refit[effect], rel=1e-12), (preset, effect)
            assert plain_rows[effect][0] == pytest.approx(plain[effect], rel=1e-12), (preset, effect)


@full_only
def test_bake_files_bakes_a_library_and_reports_a_bad_probe(bundled_probe, tmp_path):
    """A folder and a file: each result equals bake_file's, a probe that cannot be read is reported and the rest
    go on."""
    import shutil
    library = tmp_path / "library"
    library.mkdir()
    shutil.copy(bundled_probe, library / "a.hdr")
    (library / "broken.hdr").write_text("junk")
    results = pl.bake_files([str(library), bundled_probe], lights=12, evaluate=True, effects="diffuse,shadow")
    assert [os.path.basename(r["source"]["path"]) for r in results] == ["a.hdr", "broken.hdr", "noon_grass_1k.hdr"]
    assert "cannot read probe" in results[1]["error"]
    single = pl.bake_file(bundled_probe, lights=12, evaluate=True, effects="diffuse,shadow")
    for r in (results[0], results[2]):
        assert np.array_equal(r["lights"]["rgb"], single["lights"]["rgb"])
        assert r["evaluation"] == single["evaluation"]


def test_gltf_of_a_bake_in_glTFs_frame_and_units():
    # A probe with one bright cell: its light's direction and irradiance, as glTF carries them.
    pixels = np.full((64, 128, 3), 0.01, np.float32)
    pixels[20, 90] = (400, 300, 200)
    r = pl.bake(pixels, lights=4)
    doc = json.loads(pl.gltf(r["lights"]))
    lights, nodes = doc["extensions"]["KHR_lights_punctual"]["lights"], doc["nodes"]
    assert doc["asset"]["version"] == "2.0" and len(lights) == len(nodes) == 4
    brightest = int(np.argmax(r["lights"]["rgb"].max(axis=1)))
    light, node = lights[brightest], nodes[brightest]
    rgb, d = r["lights"]["rgb"][brightest], r["lights"]["direction"][brightest]
    assert light["type"] == "directional" and max(light["color"]) == 1.0
    assert light["intensity"] == pytest.approx(rgb.max() * 683) and light["color"] == pytest.approx(rgb / rgb.max())
    # glTF's -Z (where a light shines) turned to point from the light to the origin; Blender (x, y, z) = glTF
    # (x, -z, y).
    x, y, z, w = node["rotation"]
    local_z = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    assert local_z == pytest.approx([d[0], d[2], -d[1]], abs=1e-12)
    assert light["extras"]["angle"] == pytest.approx(r["lights"]["angle"][brightest])
    points = json.loads(pl.gltf(r["lights"], light_type="point", distance=5))
    p = points["extensions"]["KHR_lights_punctual"]["lights"][brightest]
    assert p["type"] == "point" and p["intensity"] == pytest.approx(rgb.max() * 25 * 683)
    assert points["nodes"][brightest]["translation"] == pytest.approx(5 * np.array([d[0], d[2], -d[1]]))


@pytest.mark.parametrize("kwargs, message", [
    ({"light_type": "spot"}, "light_type takes sun or point"),
    ({"distance": 0}, "distance takes metres above 0"),
    ({"distance": float("nan")}, "distance takes metres above 0"),
])
def test_gltf_bad_requests(kwargs, message):
    r = pl.bake(np.ones((8, 16, 3), np.float32), lights=2)
    with pytest.raises(pl.Error, match=message):
        pl.gltf(r["lights"], **kwargs)
    with pytest.raises(pl.Error, match="no 'rgb'"):
        pl.gltf({"direction": r["lights"]["direction"]})


def test_export_writes_every_registered_format_and_the_named_ones_are_its():
    r = pl.bake(np.ones((8, 16, 3), np.float32), lights=2)
    assert pl.exporters == ["gltf", "usd", "csv"]
    for name in pl.exporters:
        for kind in pl.light_kinds:
            assert "%s_001" % kind["name"] in pl.export(r["lights"], name, light_type=kind["name"])
    assert pl.gltf(r["lights"], light_type="point") == pl.export(r["lights"], "gltf", light_type="point")
    assert pl.usd(r["lights"], reflections="./sky.hdr") == pl.export(r["lights"], "usd", reflections="./sky.hdr")
    rows = pl.export(r["lights"], "csv", light_type="point", distance=pl.default_distance).splitlines()
    assert rows[0] == "name,type,x,y,z,r,g,b,angle_deg,solid_angle_sr" and len(rows) == 3
    # A point's intensity E d^2 (W/sr) gives the origin the irradiance E, the sun's rgb.
    assert float(rows[1].split(",")[5]) == pytest.approx(r["lights"]["rgb"][0][0] * pl.default_distance ** 2)
    with pytest.raises(pl.Error, match="unknown format 'fbx': use gltf, usd or csv"):
        pl.export(r["lights"], "fbx")
    with pytest.raises(pl.Error, match="gltf has no dome"):
        pl.export(r["lights"], "gltf", reflections="./sky.hdr")
    assert [k["name"] for k in pl.light_kinds] == ["sun", "point"]
    assert [k["on_dome"] for k in pl.light_kinds] == [True, False]


def test_evaluate_gives_a_bakes_own_errors_and_measures_any_lights(bundled_probe):
    from rgbe import read_hdr
    pixels = read_hdr(bundled_probe)
    r = pl.bake(pixels, lights=16, evaluate=True, effects="diffuse,shadow,glossy", evaluator_width=512)
    got = pl.evaluate(pixels, r["lights"], effects="diffuse,shadow,glossy", evaluator_width=512)
    for effect in ("diffuse", "shadow", "glossy"):
        assert got[effect] == pytest.approx(r["evaluation"][effect], rel=1e-12)
    assert set(pl.evaluate(pixels, r["lights"], evaluator_width=512)) == {"diffuse", "shadow"}
    # Someone else's lights: the same lights mirrored below the horizon are far off; directions need not be unit.
    turned = dict(r["lights"], direction=r["lights"]["direction"] * [3.0, 3.0, -3.0])
    worse = pl.evaluate(pixels, turned, evaluator_width=512)
    assert worse["shadow"] > 5 * got["shadow"] and worse["diffuse"] > 5 * got["diffuse"]
    points = {"direction": r["lights"]["direction"], "rgb": r["lights"]["rgb"]}  # no angle: point directions
    assert pl.evaluate(pixels, points, evaluator_width=512)["shadow"] != got["shadow"]
    # Judged by a bake's preset: the add-on's bake and its estimate.
    eevee = pl.bake(pixels, lights=16, preset="blender-eevee")
    judged = pl.evaluate(pixels, eevee["lights"], preset="blender-eevee")
    assert judged == pytest.approx({k: eevee["evaluation"][k] for k in ("diffuse", "shadow")}, rel=1e-12)
    with pytest.raises(pl.Error, match="unknown option 'method': the options are projection, preset, effects"):
        pl.evaluate(pixels, r["lights"], method="sh")


@pytest.mark.parametrize("change, message", [
    (lambda l: l["direction"].__setitem__(0, 0.0), "light 0 has no direction"),
    (lambda l: l["rgb"].__setitem__((1, 0), np.nan), "light 1 has an rgb that is not finite"),
    (lambda l: l["angle"].__setitem__(1, 4.0), r"light 1 has an angle outside \[0, pi\]"),
    (lambda l: l.__setitem__("rgb", l["rgb"][:1]), "lights' columns differ in length"),
    (lambda l: l.pop("direction"), "lights has no 'direction'"),
])
def test_evaluate_refuses_bad_lights_in_one_line(change, message):
    pixels = np.ones((8, 16, 3), np.float32)
    lights = {k: np.array(v, dtype=float) for k, v in pl.bake(pixels, lights=2)["lights"].items()
              if k in ("direction", "rgb", "angle")}
    change(lights)
    with pytest.raises(pl.Error, match=message):
        pl.evaluate(pixels, lights)
    with pytest.raises(pl.Error, match="at least one light"):
        pl.evaluate(pixels, {"direction": np.zeros((0, 3)), "rgb": np.zeros((0, 3))})
    with pytest.raises(pl.Error, match="no effects given|unknown effect|effects"):
        pl.evaluate(pixels, lights, effects="sparkle")
