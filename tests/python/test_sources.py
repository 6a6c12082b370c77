"""Lamps for the sources, a residual for the world (issue 30), on every probe the tests have: the bundled one and
those of ../shared/hdri when it is beside the repository. The residual is never negative and never above the
level; the lamps and the residual together carry the probe's light per channel (to 1e-9); the residual image the
module hands back is the residual the sums describe; and the knobs mean what they say."""

import glob
import math
import os

import numpy as np
import pytest

import _probelights as pl

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "..", "shared", "hdri")
BUNDLED = os.path.join(HERE, "..", "..", "assets", "noon_grass_1k.hdr")
PROBES = [BUNDLED] + sorted(p for p in glob.glob(os.path.join(SHARED, "*"))
                            if p.endswith((".hdr", ".exr")) and os.path.basename(p) != os.path.basename(BUNDLED))

pytestmark = pytest.mark.skipif(not hasattr(pl, "bake_file"), reason="the module without files (portable)")


def latlong_integral(image):
    """Sum of value x exact solid angle over a lat-long image (rows top to bottom)."""
    h, w = image.shape[:2]
    edges = np.pi / 2 - np.pi * np.arange(h + 1) / h
    omega = (2 * np.pi / w) * (np.sin(edges[:-1]) - np.sin(edges[1:]))
    return (image.astype(np.float64).sum(axis=1) * omega[:, None]).sum(axis=0)


@pytest.mark.parametrize("probe", PROBES, ids=[os.path.basename(p) for p in PROBES])
@pytest.mark.parametrize("knob", [{"source_level": 10}, {"source_share": 0.5}], ids=["level10", "share50"])
def test_lamps_and_residual_give_back_the_probe(probe, knob):
    whole = pl.bake_file(probe, lights=16)["total_rgb"]
    r = pl.bake_file(probe, lights=16, effects="diffuse,shadow", evaluate=True, **knob)
    s = r["sources"]
    residual = s["residual"]
    assert residual.dtype == np.float32 and not residual.flags.writeable
    assert residual.min() >= 0
    y = residual.astype(np.float64) @ np.array([0.2126, 0.7152, 0.0722])
    assert y.max() <= s["level"] * (1 + 1e-6)
    lamps = r["lights"]["rgb"].sum(axis=0)
    assert lamps + s["residual_rgb"] == pytest.approx(whole, rel=1e-9)
    assert lamps == pytest.approx(s["sources_rgb"], rel=1e-9, abs=1e-12 * max(whole))
    assert latlong_integral(residual) == pytest.approx(s["residual_rgb"], rel=1e-6)
    if "source_share" in knob:
        assert s["share"] == pytest.approx(0.5, abs=1e-9)
    else:
        assert s["level"] == pytest.approx(10 * s["mean_luminance"])
    # The errors are of lamps + residual against the whole probe; what the lamps cannot be is the shape of
    # their sources, a fraction of the light.
    assert r["evaluation"]["diffuse"] < 0.02 and r["evaluation"]["shadow"] < 0.05, r["evaluation"]
    print("  %s %s: lamps take %.1f %%, diffuse %.3f %%, shadow %.3f %%" % (
        os.path.basename(probe), knob, 100 * s["share"], 100 * r["evaluation"]["diffuse"],
        100 * r["evaluation"]["shadow"]))


def test_without_sources_there_is_no_residual(bundled_probe):
    assert pl.bake_file(bundled_probe, lights=4)["sources"] is None


@pytest.mark.parametrize("kwargs, message", [
    ({"source_level": -1}, "source_level takes a multiple"),
    ({"source_share": 1.0}, "source_share takes a share"),
    ({"source_level": 10, "refit": True}, "leave out the refit"),
    ({"source_level": 10, "max_error": 0.01}, "not max_error"),
])
def test_bad_sources_requests(bundled_probe, kwargs, message):
    # pl.Error is a ValueError; test_portable_module.py loads another _probelights, whose Error is another class.
    with pytest.raises(ValueError, match=message):
        pl.bake_file(bundled_probe, lights=4, **kwargs)


def test_a_buffer_takes_sources_too():
    pixels = np.full((64, 128, 3), 0.1, np.float32)
    pixels[20:23, 40:43] = (500, 400, 300)
    r = pl.bake(pixels, lights=2, source_level=10)
    assert r["sources"]["residual"].shape == (64, 128, 3)
    assert r["lights"]["rgb"].sum(axis=0) + r["sources"]["residual_rgb"] == pytest.approx(
        latlong_integral(pixels), rel=1e-9)
    assert math.isclose(r["sources"]["residual"][21, 41].max(), r["sources"]["residual"][21, 41].max())
