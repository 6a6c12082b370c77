#!/usr/bin/env python3
"""probelights next to its peers, whole processes, and docs/results/peers.md written from the figures.

    python3 bench/bench_peers.py MOBILEAR ENVTOOLS [--probe 1K.hdr] [--runs 9] [--write]

MOBILEAR and ENVTOOLS are checkouts (work trees) of nandor/MobileAR and cedricpinson/envtools; this script
does not fetch them. Each peer is built here from its checkout into a temporary folder:
  MobileAR  its variance cut (ar/VarianceCutSampler.cpp, ar/LightProbeSampler.cpp) in a small command
            (bench/peers/mobilear_variance_cut.cpp: reads the probe with OpenCV as MobileAR keeps its probes);
            Apple's <simd/simd.h> and OpenCV's umbrella header stand in (bench/peers/)
  envtools  extractLights, its own sources, against Debian's OpenImageIO 2.4, with the two calls that OpenImageIO
            2 changed (ImageInput::open and ImageOutput::create return a unique_ptr) given .release()
probelights is build/bin/probelights (scripts/build.sh). Every command cuts the probe into 256 lights, at 1K (the
probe given, by default the bundled one) and at 8K (the same resized to 8192 x 4096 by oiiotool); each is timed
--runs times as a whole process after a run not counted (the page cache warm), and its median wall time and
largest resident memory printed.
Needs g++, OpenCV's core, imgproc and imgcodecs headers, Debian's libopenimageio-dev and oiiotool (apt).
"""
import argparse
import datetime
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent


def build_mobilear(src, out):
    ar = pathlib.Path(src) / "MobileAR" / "ar"
    if not (ar / "VarianceCutSampler.cpp").exists():
        sys.exit(f"bench_peers: {src} is not a MobileAR checkout (no MobileAR/ar/VarianceCutSampler.cpp)")
    exe = out / "mobilear_variance_cut"
    subprocess.run(["g++", "-O2", "-std=c++17", f"-I{HERE / 'peers'}", f"-I{ar}", "-I/usr/include/opencv4",
                    str(HERE / "peers" / "mobilear_variance_cut.cpp"), str(ar / "VarianceCutSampler.cpp"),
                    str(ar / "LightProbeSampler.cpp"), "-lopencv_imgcodecs", "-lopencv_imgproc", "-lopencv_core",
                    "-o", str(exe)], check=True)
    return exe


def build_envtools(src, out):
    src = pathlib.Path(src)
    if not (src / "extractLightsVariance.cpp").exists():
        sys.exit(f"bench_peers: {src} is not an envtools checkout (no extractLightsVariance.cpp)")
    work = out / "envtools"
    shutil.copytree(src, work, ignore=shutil.ignore_patterns(".git", "etc", "test*"))
    for name, call in (("extractLightsVariance.cpp", "ImageInput::open ( argv[optind] )"),
                       ("extractLightsVarianceDebug.cpp", 'ImageOutput::create ("out/test_variance.png")')):
        text = (work / name).read_text()
        if call not in text:
            sys.exit(f"bench_peers: {name} no longer has '{call}'; look at the envtools checkout")
        (work / name).write_text(text.replace(call, call + ".release()"))
    exe = out / "extractLights"
    subprocess.run(["g++", "-O2", "-std=c++17", "-fopenmp", "extractLightsVariance.cpp", "SummedAreaTable.cpp",
                    "SummedAreaTableRegion.cpp", "-o", str(exe), "-lOpenImageIO", "-lOpenImageIO_Util"],
                   cwd=work, check=True)
    return exe


def run_once(cmd):
    """Wall seconds and peak resident MB of one whole process."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"bench_peers: {' '.join(map(str, cmd))} failed: {proc.stderr.read().decode(errors='replace')}")
    return wall, usage.ru_maxrss / 1024


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mobilear")
    parser.add_argument("envtools")
    parser.add_argument("--probe", default=str(ROOT / "assets" / "noon_grass_1k.hdr"))
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--write", action="store_true", help="write docs/results/peers.md")
    args = parser.parse_args()
    ours = ROOT / "build" / "bin" / "probelights"
    if not ours.exists():
        sys.exit("bench_peers: no build/bin/probelights (bash scripts/build.sh)")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        mobilear = build_mobilear(args.mobilear, tmp)
        envtools = build_envtools(args.envtools, tmp)
        probe_8k = tmp / "probe_8k.hdr"
        subprocess.run(["oiiotool", args.probe, "--resize", "8192x4096", "-o", str(probe_8k)], check=True)
        sizes = {"1K": pathlib.Path(args.probe), "8K": probe_8k}
        tools = {
            "probelights": lambda p: [ours, "bake", p, "--lights", "256", "-q", "-o", tmp / "lights.json"],
            "MobileAR variance cut": lambda p: [mobilear, p, "256"],
            "envtools extractLights": lambda p: [envtools, "-n", "8", "-m", "256", p],
        }
        # Each command's runs one after another after one run not counted: run in turn, a peer's 8K run (2-3 GB)
        # pushed the next command's libraries out of the page cache (probelights' 1K bake took 0.35 s, 0.05 s warm).
        runs = {}
        for s, p in sizes.items():
            for t, cmd in tools.items():
                run_once(cmd(p))
                runs[(t, s)] = [run_once(cmd(p)) for _ in range(args.runs)]
        fig = {k: (statistics.median(w for w, _ in v), max(m for _, m in v)) for k, v in runs.items()}
    rows = ["| probe | " + " | ".join(tools) + " |", "|---|" + "---|" * len(tools)]
    for s in sizes:
        cells = []
        for t in tools:
            wall, mb = fig[(t, s)]
            ratio = wall / fig[("probelights", s)][0]
            cells.append(f"{wall:.3f} s, {mb:.0f} MB" + ("" if t == "probelights" else f" ({ratio:.1f}x)"))
        rows.append(f"| {s} .hdr | " + " | ".join(cells) + " |")
    table = "\n".join(rows)
    print(table)
    if args.write:
        commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
        probe = pathlib.Path(args.probe).name
        page = f"""# probelights next to its peers

Regenerate: `python3 bench/bench_peers.py MOBILEAR_CHECKOUT ENVTOOLS_CHECKOUT --write` (how each peer is built:
the script's header). Figures of commit {commit}, {datetime.date.today()}, on the 2-core development machine.

256 lights from one probe, each command a whole process (start, read, cut, write): the median wall time of
{args.runs} runs after one not counted (files and libraries in the page cache) and the largest resident memory;
in brackets, the time against probelights'. 1K: {probe}; 8K: the same resized to 8192 x 4096.

{table}

What differs besides the cut: probelights reads with OpenImageIO 3.2 (PyPI's wheel: two libraries beside zlib and
the C and C++ runtimes; `probelights --help` takes 10-20 ms), computes exact solid angles and writes JSON; MobileAR's command reads with OpenCV and
prints one line a light; envtools links Debian's OpenImageIO 2.4, whose 261 libraries take about a quarter of
a second to load before main().
"""
        (ROOT / "docs" / "results" / "peers.md").write_text(page)
        print("wrote docs/results/peers.md")


if __name__ == "__main__":
    main()
