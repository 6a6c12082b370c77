#!/usr/bin/env python3
"""Worlds that move, baked as a sequence against each frame baked alone: docs/results/sequences.md's table.

    python3 bench/bench_sequence.py [--probe 1K.hdr] [--frames 48] [--bin build/bin/probelights]

Two sequences are made from the probe (by default the bundled noon_grass_1k.hdr; a Radiance .hdr read by
tests/python/rgbe.py) into a temporary folder as PFM frames:
  day    a sun of 2 degrees added to the probe, crossing it from east to west over --frames frames (up to 55
         degrees high), its strength and the whole frame's exposure rising and falling with it;
  video  the probe as captured HDR video: every frame the probe times independent per-pixel noise of 5 %.
Each is baked by `probelights bake-sequence ... --evaluate` at 16 and 64 lights: independently (every frame its
own bake, as baking each frame apart gives) and as a sequence at several smoothness values. A row gives the mean
per-frame diffuse and shadow errors (evaluate.h, as single bakes are judged), the flicker (the lamp-lit
response's change from frame to frame over the world-lit response's own, on the same receivers), the lights'
energy-weighted motion a frame (degrees, id to id: what a lamp's keyframes move), the frames cut afresh, and
the bake's milliseconds a frame (reading excluded). "Finished" rows finish every frame as the add-on's single
bake does (angles fitted to the frame's shadows, colours and directions refit: --sun-angles fit --refit
--refit-directions), every frame's energy exact (the default) or free to move as a single bake's refit moves it
(--exact-energy off). Needs numpy.
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "python"))
from rgbe import read_hdr  # noqa: E402


def directions(height, width):
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    el = math.pi / 2 - math.pi * v[:, None]
    phi = 2 * math.pi * (0.5 - u[None, :])
    return np.stack([np.cos(el) * np.cos(phi), np.cos(el) * np.sin(phi), np.sin(el) * np.ones_like(phi)], -1)


def write_pfm(path, pixels):
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (pixels.shape[1], pixels.shape[0]))
        f.write(np.ascontiguousarray(pixels[::-1]).astype("<f4").tobytes())


def make_day(probe, folder, frames, write=write_pfm, ext="pfm"):
    d = directions(*probe.shape[:2])
    for f in range(frames):
        s = (f + 0.5) / frames
        az, el = math.pi * (s - 0.5) * 1.5, math.radians(5 + 50 * math.sin(math.pi * s))
        sun = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        out = probe.copy()
        out[d @ sun > math.cos(math.radians(1.0))] += np.array([3000, 2700, 2200], np.float32) * (
            0.3 + 0.7 * math.sin(math.pi * s))
        write(folder / ("day_%04d.%s" % (f + 1, ext)), out * (0.6 + 0.4 * math.sin(math.pi * s)))


def make_video(probe, folder, frames):
    rng = np.random.default_rng(1)
    for f in range(frames):
        noise = np.clip(rng.normal(1, 0.05, probe.shape[:2] + (1,)), 0, None).astype(np.float32)
        write_pfm(folder / ("video_%04d.pfm" % (f + 1)), probe * noise)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--probe", default=str(HERE.parent / "assets" / "noon_grass_1k.hdr"))
    parser.add_argument("--frames", type=int, default=48)
    parser.add_argument("--bin", default=str(HERE.parent / "build" / "bin" / "probelights"))
    args = parser.parse_args()
    probe = read_hdr(args.probe).astype(np.float32)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        make_day(probe, folder, args.frames)
        make_video(probe, folder, args.frames // 2)
        for name in ("day", "video"):
            for lights in (16, 64):
                finished = ["--sun-angles", "fit", "--refit", "--refit-directions"]
                for label, extra in (("each frame alone", ["--independent"]), ("smoothness 0", ["--smoothness", "0"]),
                                     ("smoothness 0.1 (default)", []), ("smoothness 0.5", ["--smoothness", "0.5"]),
                                     ("smoothness 2", ["--smoothness", "2"]),
                                     ("finished, each frame alone", ["--independent"] + finished),
                                     ("finished, smoothness 0.1", finished),
                                     ("finished, energy free, each frame alone",
                                      ["--independent", "--exact-energy", "off"] + finished),
                                     ("finished, energy free, smoothness 0.1", ["--exact-energy", "off"] + finished)):
                    out = folder / "out.json"
                    subprocess.run([args.bin, "bake-sequence", str(folder / (name + "_####.pfm")), "--lights",
                                    str(lights), "--evaluate", "-q", "-o", str(out)] + extra, check=True,
                                   capture_output=True)
                    s = json.load(open(out))["summary"]
                    rows.append((name, lights, label, s))
    print("probe %s, %dx%d; day: %d frames, video: %d frames\n" % (pathlib.Path(args.probe).name, probe.shape[1],
                                                                    probe.shape[0], args.frames, args.frames // 2))
    print("| sequence | lights | baked | diffuse | shadow | flicker | motion a frame | cut afresh | ms a frame |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|")
    for name, lights, label, s in rows:
        print("| %s | %d | %s | %.3f %% | %.3f %% | %.2f | %.2f deg | %d of %d | %.1f |" % (
            name, lights, label, 100 * s["diffuse"], 100 * s["shadow"], s["flicker"] or float("nan"),
            math.degrees(s["mean_motion"]), s["recut"], s["frames"], s["bake_ms_per_frame"]))


if __name__ == "__main__":
    main()
