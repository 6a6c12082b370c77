"""The USD that probelights writes (the module's usd() and the CLI's --usd), read back by OpenUSD itself (PyPI's
usd-core, pinned in tests/usd-core-version; ctest's "usd" runs this file in scripts/usd-env.sh's environment):
the stage opens and passes OpenUSD's validators, every light's direction, position, colour x intensity
and angle read back through UsdLux and UsdGeom's transforms are the bake's, and the reflections dome shows each
pixel of the probe in the direction the probe's own convention gives it."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

pxr = pytest.importorskip("pxr", reason="usd-core is not installed here (scripts/usd-env.sh)")
from pxr import Sdf, Usd, UsdGeom, UsdLux, UsdValidation  # noqa: E402

import _probelights as pl  # noqa: E402

BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
CLI = os.path.join(BUILD, "bin", "probelights")
SUN_DIAMETER = math.radians(0.53)


def bake(probe, **extra):
    return pl.bake_file(probe, lights=16, refit=True, effects="diffuse,shadow", **extra)


def stage_of(text, folder, name="lights.usda"):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    stage = Usd.Stage.Open(path)
    assert stage, path
    return path, stage


def lights_of(stage):
    return [p for p in stage.Traverse() if p.HasAPI(UsdLux.LightAPI)]


def world(prim):
    return np.array(UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default()))


def direction_of(matrix, local):
    # USD's matrices act on row vectors: world = local * M.
    v = np.array([*local, 0.0]) @ matrix
    return v[:3] / np.linalg.norm(v[:3])


def degrees_between(a, b):
    return math.degrees(math.atan2(np.linalg.norm(np.cross(a, b)), float(np.dot(a, b))))


def compliant(path):
    """OpenUSD's own validators (all that usd-core registers: its core, UsdGeom, UsdLux, UsdShade, ...), each
    problem as 'validator: message'."""
    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    found = UsdValidation.ValidationContext(validators).Validate(Usd.Stage.Open(path))
    return ["%s: %s" % (e.GetValidator().GetMetadata().name if e.GetValidator() else "?", e.GetMessage())
            for e in found]


def test_suns_read_back_by_openusd(bundled_probe, tmp_path):
    r = bake(bundled_probe)
    L = r["lights"]
    path, stage = stage_of(pl.usd(L), str(tmp_path))
    assert compliant(path) == []
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z and UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert stage.GetDefaultPrim().GetPath() == Sdf.Path("/probelights")
    suns = lights_of(stage)
    assert len(suns) == len(L["rgb"]) == 16 and all(s.IsA(UsdLux.DistantLight) for s in suns)
    worst = 0.0
    for sun, d, rgb, angle, omega in zip(suns, L["direction"], L["rgb"], L["angle"], L["solid_angle"]):
        light = UsdLux.DistantLight(sun)
        # A UsdLux light shines along its local -Z: it comes from its local +Z.
        worst = max(worst, degrees_between(direction_of(world(sun), (0, 0, 1)), d / np.linalg.norm(d)))
        api = UsdLux.LightAPI(sun)
        assert api.GetNormalizeAttr().Get() is True
        # Normalized: intensity x colour is the illuminance on a facing surface (float attributes).
        given = api.GetIntensityAttr().Get() * np.array(api.GetColorAttr().Get())
        assert given == pytest.approx(np.maximum(rgb, 0), rel=1e-6, abs=1e-7 * rgb.max())
        assert light.GetAngleAttr().Get() == pytest.approx(math.degrees(angle), rel=1e-6)
        assert sun.GetAttribute("probelights:solidAngle").Get() == pytest.approx(omega, rel=1e-15)
    assert worst < 1e-4, worst
    print("  16 suns back from USD: directions within %.1e degrees" % worst)


def test_points_read_back_by_openusd(bundled_probe, tmp_path):
    r = bake(bundled_probe)
    L, distance = r["lights"], 7.0
    path, stage = stage_of(pl.usd(L, light_type="point", distance=distance), str(tmp_path))
    assert compliant(path) == []
    points = lights_of(stage)
    assert len(points) == 16 and all(p.IsA(UsdLux.SphereLight) for p in points)
    for point, d, rgb, angle in zip(points, L["direction"], L["rgb"], L["angle"]):
        at = world(point)[3, :3]
        assert at == pytest.approx(distance * d / np.linalg.norm(d), abs=1e-9)
        api, sphere = UsdLux.LightAPI(point), UsdLux.SphereLight(point)
        radius = sphere.GetRadiusAttr().Get()
        # The fitted cone seen from the origin, at least the Sun's size.
        assert radius == pytest.approx(distance * math.sin(max(angle, SUN_DIAMETER) / 2), rel=1e-6)
        # Normalized: luminance = intensity / (4 pi r^2); a sphere of luminance L seen under a half-angle a
        # (sin a = r / d) gives a facing surface L pi sin^2 a, so the origin's irradiance is intensity / (4 d^2).
        luminance = api.GetIntensityAttr().Get() / (4 * math.pi * radius ** 2) * np.array(api.GetColorAttr().Get())
        irradiance = luminance * math.pi * (radius / distance) ** 2
        assert irradiance == pytest.approx(np.maximum(rgb, 0), rel=1e-6, abs=1e-7 * rgb.max())


def test_reflections_dome_shows_the_probe_where_the_probe_puts_it(bundled_probe, tmp_path):
    r = bake(bundled_probe)
    folder = tmp_path / "scene"
    folder.mkdir()
    out = folder / "lights.usda"
    subprocess.run([CLI, "bake", bundled_probe, "--lights", "16", "--usd", str(out), "--usd-dome", "reflections",
                    "-q"], check=True)
    stage = Usd.Stage.Open(str(out))
    assert compliant(str(out)) == []
    lights = lights_of(stage)
    domes = [p for p in lights if p.IsA(UsdLux.DomeLight)]
    assert len(domes) == 1 and len(lights) == 17
    dome = UsdLux.DomeLight(domes[0])
    # Written relative to the .usda ("../.." up to the probe), and resolved by USD to the probe itself.
    texture = dome.GetTextureFileAttr().Get()
    assert texture.path.startswith("../") and os.path.samefile(texture.resolvedPath, bundled_probe)
    assert dome.GetTextureFormatAttr().Get() == "latlong"
    # The split of the add-on's default: the dome for reflections alone, the lamps for diffuse light alone.
    api = UsdLux.LightAPI(domes[0])
    assert (api.GetDiffuseAttr().Get(), api.GetSpecularAttr().Get(), api.GetIntensityAttr().Get()) == (0, 1, 1)
    for lamp in (UsdLux.LightAPI(p) for p in lights if p != domes[0]):
        assert (lamp.GetDiffuseAttr().Get(), lamp.GetSpecularAttr().Get()) == (1, 0)
    # A pixel at (u, v) (from the left, from the top) lies, in the dome's own frame (UsdLux, after OpenEXR:
    # pole on +Y, longitude +pi at the left edge, 0 towards +Z, pi/2 towards +X), at longitude pi (1 - 2u) and
    # latitude pi (1/2 - v); the dome's transform must take it to the probe's direction for that pixel
    # (phi = 2 pi (0.5 - u), elevation = pi/2 - pi v, Z up).
    m = world(domes[0])
    rng = np.random.default_rng(3)
    for u, v in rng.random((50, 2)):
        lon, lat = math.pi * (1 - 2 * u), math.pi * (0.5 - v)
        local = (math.cos(lat) * math.sin(lon), math.sin(lat), math.cos(lat) * math.cos(lon))
        phi, el = 2 * math.pi * (0.5 - u), math.pi / 2 - math.pi * v
        ours = np.array([math.cos(el) * math.cos(phi), math.cos(el) * math.sin(phi), math.sin(el)])
        assert degrees_between(direction_of(m, local), ours) < 1e-9, (u, v)
    assert r["lights"]["rgb"].shape == (16, 3)


def test_residual_dome_with_the_lamps_of_the_sources(bundled_probe, tmp_path):
    # The lamps of the sources and a dome of the residual: their light together is the probe's, read back
    # from the USD (intensity x colour, float attributes) and the residual's sums (the bake's JSON).
    out, residual, lights = tmp_path / "lights.usda", tmp_path / "residual.exr", tmp_path / "lights.json"
    subprocess.run([CLI, "bake", bundled_probe, "--lights", "8", "--residual", str(residual), "--usd", str(out),
                    "--usd-dome", "residual", "-o", str(lights), "-q"], check=True)
    stage = Usd.Stage.Open(str(out))
    assert compliant(str(out)) == []
    found = lights_of(stage)
    domes = [p for p in found if p.IsA(UsdLux.DomeLight)]
    assert len(domes) == 1 and len(found) == 9
    dome = UsdLux.DomeLight(domes[0])
    assert dome.GetTextureFileAttr().Get().path == "./residual.exr"
    assert os.path.samefile(dome.GetTextureFileAttr().Get().resolvedPath, residual)
    # No split: every light lights everything (no diffuse or specular multipliers authored).
    for p in found:
        assert not UsdLux.LightAPI(p).GetDiffuseAttr().HasAuthoredValue()
        assert not UsdLux.LightAPI(p).GetSpecularAttr().HasAuthoredValue()
    lamps = sum(UsdLux.LightAPI(p).GetIntensityAttr().Get() * np.array(UsdLux.LightAPI(p).GetColorAttr().Get())
                for p in found if p != domes[0])
    with open(lights) as f:
        baked = json.load(f)
    whole = pl.bake_file(bundled_probe, lights=8)["total_rgb"]
    assert lamps + np.array(baked["sources"]["residual_rgb"]) == pytest.approx(whole, rel=1e-6)


def test_usd_bad_requests(bundled_probe, tmp_path):
    r = pl.bake(np.ones((8, 16, 3), np.float32), lights=2)
    with pytest.raises(pl.Error, match="light_type takes sun or point"):
        pl.usd(r["lights"], light_type="spot")
    with pytest.raises(pl.Error, match="cannot name"):
        pl.usd(r["lights"], reflections="a@@@b.hdr")
    with pytest.raises(pl.Error, match="one dome"):
        pl.usd(r["lights"], reflections="./a.hdr", residual="./r.exr")
    # An @ in a path is written in usda's other form, and read back whole.
    path, stage = stage_of(pl.usd(r["lights"], reflections="./sky@noon.hdr"), str(tmp_path))
    dome = [p for p in lights_of(stage) if p.IsA(UsdLux.DomeLight)][0]
    assert UsdLux.DomeLight(dome).GetTextureFileAttr().Get().path == "./sky@noon.hdr"
    # No lights: a valid, empty stage.
    none = pl.usd({"direction": np.zeros((0, 3)), "rgb": np.zeros((0, 3))})
    path, stage = stage_of(none, str(tmp_path), "none.usda")
    assert lights_of(stage) == [] and compliant(path) == []


def test_a_sequence_reads_back_frame_by_frame(tmp_path):
    """bake-sequence --usd: one layer whose lights carry a time sample a frame, each the JSON's light of the same
    id at that frame; sampled between frames, OpenUSD interpolates (the lamp moves, it does not jump)."""
    width, height = 128, 64
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    el, phi = math.pi / 2 - math.pi * v[:, None], 2 * math.pi * (0.5 - u[None, :])
    d = np.stack([np.cos(el) * np.cos(phi), np.cos(el) * np.sin(phi), np.sin(el) * np.ones_like(phi)], -1)
    for f in range(4):
        sun = np.array([math.cos(0.2 * f), math.sin(0.2 * f), 0.5]) / math.hypot(1, 0.5)
        img = np.where(d[..., 2:] > 0, 0.5, 0.1) * np.ones(3)
        img[d @ sun > math.cos(math.radians(3))] += 800
        with open(tmp_path / ("sky_%04d.pfm" % (f + 11)), "wb") as out:
            out.write(b"PF\n%d %d\n-1.0\n" % (width, height))
            out.write(np.ascontiguousarray(img[::-1]).astype("<f4").tobytes())
    subprocess.run([CLI, "bake-sequence", str(tmp_path / "sky_####.pfm"), "--lights", "4", "-q", "-o",
                    str(tmp_path / "seq.json"), "--usd", str(tmp_path / "seq.usda"), "--fps", "25"], check=True,
                   capture_output=True)
    frames = json.load(open(tmp_path / "seq.json"))["frames"]
    path = str(tmp_path / "seq.usda")
    assert compliant(path) == []
    stage = Usd.Stage.Open(path)
    assert (stage.GetStartTimeCode(), stage.GetEndTimeCode(), stage.GetTimeCodesPerSecond()) == (11, 14, 25)
    suns = lights_of(stage)
    assert len(suns) == 4
    for frame in frames:
        t = Usd.TimeCode(frame["frame"])
        for sun, light in zip(suns, frame["lights"]):
            matrix = np.array(UsdGeom.Xformable(sun).ComputeLocalToWorldTransform(t))
            assert degrees_between(direction_of(matrix, (0, 0, 1)), np.array(light["direction"])) < 1e-4
            api = UsdLux.LightAPI(sun)
            given = api.GetIntensityAttr().Get(t) * np.array(api.GetColorAttr().Get(t))
            assert given == pytest.approx(light["rgb"], rel=1e-6, abs=1e-7 * max(light["rgb"]))
            assert UsdLux.DistantLight(sun).GetAngleAttr().Get(t) == pytest.approx(math.degrees(light["angle"]),
                                                                                  rel=1e-6)
    # Half-way between two frames the brightest lamp is half-way between its two directions.
    sun_id = max(range(4), key=lambda k: frames[1]["lights"][k]["rgb"][1])
    a, b = (np.array(frames[k]["lights"][sun_id]["direction"]) for k in (1, 2))
    between = direction_of(np.array(UsdGeom.Xformable(suns[sun_id]).ComputeLocalToWorldTransform(Usd.TimeCode(12.5))),
                           (0, 0, 1))
    assert degrees_between(between, a) == pytest.approx(degrees_between(between, b), abs=0.05)
