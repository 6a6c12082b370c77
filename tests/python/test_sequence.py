"""The module's SequenceBaker as the add-on and a pipeline script use it: frames of pixels one by one, the same N
lights each frame with their ids, each frame's lights carrying its probe's light exactly, the same frames and
lights as the CLI's bake-sequence, and a clear error for a frame it cannot take."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

import _probelights as pl

from conftest import BUILD


def day(frames, width=128, height=64):
    """A sky of 0.2-0.6 over a ground of 0.05 and a sun of 2 degrees crossing it from east to west."""
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    el = math.pi / 2 - math.pi * v[:, None]
    phi = 2 * math.pi * (0.5 - u[None, :])
    d = np.stack([np.cos(el) * np.cos(phi), np.cos(el) * np.sin(phi), np.sin(el) * np.ones_like(phi)], -1)
    sky = np.where(d[..., 2:] > 0, 0.2 + 0.4 * d[..., 2:], 0.05) * np.ones(3)
    for f in range(frames):
        s = (f + 0.5) / frames
        az, elevation = math.pi * (s - 0.5), math.pi / 3 * math.sin(math.pi * s)
        sun = np.array([math.cos(elevation) * math.cos(az), math.cos(elevation) * math.sin(az), math.sin(elevation)])
        img = sky.copy()
        img[d @ sun > math.cos(math.radians(2))] += 2000
        yield img.astype(np.float32), sun


def test_frames_keep_their_lights_and_their_light():
    baker = pl.SequenceBaker(lights=8, evaluate=True)
    sun_ids = set()
    for f, (pixels, sun) in enumerate(day(12)):
        frame = baker.add(pixels, frame=f + 1)
        lights = frame["lights"]
        assert frame["frame"] == f + 1 and list(lights["id"]) == list(range(8))
        assert np.allclose(lights["rgb"].sum(axis=0), frame["total_rgb"], rtol=1e-9)
        brightest = int(np.argmax(lights["rgb"][:, 1]))
        assert math.degrees(math.acos(min(1.0, float(lights["direction"][brightest] @ sun)))) < 3
        sun_ids.add(brightest)
        assert frame["evaluation"]["diffuse"] < 0.1
    assert len(sun_ids) == 1 and baker.frames == 12


def test_frames_finished_as_a_single_bake_keep_their_energy_or_report_its_shift():
    # The add-on's recipe: angles fitted to each frame's shadows, colours and directions refit; every frame's
    # energy exact (the default), or free to move as a single bake's refit moves it (exact_energy=False).
    recipe = dict(lights=8, sun_angles="fit", refit=True, move_directions=True, evaluate=True)
    finished, free = pl.SequenceBaker(**recipe), pl.SequenceBaker(exact_energy=False, **recipe)
    plain = pl.SequenceBaker(lights=8, evaluate=True)
    errors = [0.0, 0.0]
    for f, (pixels, _) in enumerate(day(6)):
        a, b, c = finished.add(pixels, frame=f + 1), plain.add(pixels, frame=f + 1), free.add(pixels, frame=f + 1)
        assert b["energy_shift"] == 0.0 and abs(a["energy_shift"]) < 1e-12
        assert np.allclose(a["lights"]["rgb"].sum(axis=0), a["total_rgb"], rtol=1e-9)
        shift = c["energy_shift"]
        assert abs(shift) < 0.2
        assert math.isclose(c["lights"]["rgb"].sum(), sum(c["total_rgb"]) * (1 + shift), rel_tol=1e-9)
        assert np.all(a["lights"]["angle"] >= 0) and np.all(np.isfinite(a["lights"]["direction"]))
        errors[0] += a["evaluation"]["shadow"]
        errors[1] += b["evaluation"]["shadow"]
    assert errors[0] < errors[1], errors  # the fitted angles and the refit pay on the shadows
    with pytest.raises(ValueError, match="exact_energy takes on or off"):
        pl.SequenceBaker(exact_energy="maybe")


def test_the_width_frames_are_fitted_at_reaches_the_core():
    # Each frame is finished at fit_width (auto: 256 with exact energy, a sequence's price) and judged at
    # evaluator_width.
    recipe = dict(lights=8, sun_angles="fit", refit=True, move_directions=True)
    pixels = next(day(1))[0]
    default = pl.SequenceBaker(**recipe).add(pixels, frame=1)["lights"]
    narrow = pl.SequenceBaker(fit_width=32, **recipe).add(pixels, frame=1)["lights"]
    assert not np.array_equal(default["rgb"], narrow["rgb"])
    with pytest.raises(ValueError, match="fit_width takes auto or a width of at least 1 pixel"):
        pl.SequenceBaker(fit_width=0)


@pytest.mark.skipif(pl.build != "full", reason="runs the CLI: the full module's")
def test_the_module_bakes_the_frames_as_the_command_does(tmp_path):
    cli = os.path.join(BUILD, "bin", "probelights")
    baker = pl.SequenceBaker(lights=6, smoothness=0.3)
    ours = []
    for f, (pixels, _) in enumerate(day(5)):
        with open(tmp_path / ("sky_%04d.pfm" % (f + 1)), "wb") as out:
            out.write(b"PF\n%d %d\n-1.0\n" % (pixels.shape[1], pixels.shape[0]))
            out.write(np.ascontiguousarray(pixels[::-1]).astype("<f4").tobytes())
        ours.append(baker.add(pixels, frame=f + 1))
    subprocess.run([cli, "bake-sequence", str(tmp_path / "sky_####.pfm"), "--lights", "6", "--smoothness", "0.3",
                    "-q", "-o", str(tmp_path / "seq.json")], check=True, capture_output=True)
    theirs = json.load(open(tmp_path / "seq.json"))["frames"]
    for a, b in zip(ours, theirs):
        assert a["recut"] == b["recut"]
        assert np.allclose(a["lights"]["rgb"], [l["rgb"] for l in b["lights"]], rtol=1e-6)
        assert np.allclose(a["lights"]["direction"], [l["direction"] for l in b["lights"]], atol=1e-6)


def test_a_frame_it_cannot_take_is_a_clear_error():
    # pl.Error is a ValueError; test_portable_module.py loads another _probelights, whose Error is another class.
    baker = pl.SequenceBaker(lights=4)
    frames = day(2)
    baker.add(next(frames)[0])
    with pytest.raises(ValueError, match="frame 2 is 64x32 latlong, the sequence's first frame 128x64 latlong"):
        baker.add(next(day(1, 64, 32))[0])
    with pytest.raises(ValueError, match="unknown option 'count'"):
        pl.SequenceBaker(count=4)
    with pytest.raises(ValueError, match="not by the sh method"):
        pl.SequenceBaker(method="sh")
    with pytest.raises(ValueError, match="smoothness"):
        pl.SequenceBaker(smoothness=-1)
    bad = next(day(1))[0]
    bad[3, 4, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        pl.SequenceBaker(lights=4).add(bad)
