"""Mutated probe files, baked by the CLI under a time and memory limit: every one must end in finite,
non-negative lights, or in one error line. Never a crash, a hang, exit 1 or a NaN.

    fuzz_test.py PROBELIGHTS_BINARY BUNDLED_PROBE [CASES]

The cases are baked as libraries (`bake FOLDER --out-dir`, BATCH of them per process: each either a whole JSON
of finite lights or an error of one line in summary.json, the process exiting 0 or 3), which reads and bakes each
file through the same entry as a single bake (bake_file.h) without paying a process start per case; every
SINGLE-th case is also baked alone, where it must exit 0 with a whole JSON or exit 2 with one line on stderr. A
batch that crashes, hangs or exits otherwise is baked again case by case, which names the case.

The mutations are drawn from a fixed seed (the same cases every run): bit flips, byte runs overwritten,
truncations and header edits of the bundled probe, of a small .hdr and a small EXR made from it (oiiotool), and of
a small 16-bit TIFF and PNG. A failing case is kept in fuzz-failures/ beside the binary to reproduce it."""
import concurrent.futures
import json
import math
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile

TIME_LIMIT = 30  # seconds per case; a case takes ~0.05 s
MEMORY_LIMIT = 2 << 30  # address space per process
BATCH = 50  # cases per library process
SINGLE = 10  # every SINGLE-th case is also baked alone


def make_inputs(probe, folder):
    """The files to mutate: the bundled probe, and small ones made from it."""
    def oiio(*args):
        subprocess.run(["oiiotool", *args], check=True, capture_output=True)
    small = os.path.join(folder, "small.hdr")
    oiio(probe, "--resize", "128x64", "-o", small)
    oiio(small, "--resize", "64x32", "-d", "half", "--compression", "zip", "-o", os.path.join(folder, "small.exr"))
    oiio(small, "--resize", "64x32", "-d", "half", "--compression", "piz", "--tile", "16", "16", "-o",
         os.path.join(folder, "tiled.exr"))
    oiio(small, "--resize", "64x32", "-d", "uint16", "-o", os.path.join(folder, "small.tif"))
    oiio(small, "--resize", "64x32", "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o",
         os.path.join(folder, "small.png"))
    inputs = {"bundled.hdr": open(probe, "rb").read()}
    for name in ("small.hdr", "small.exr", "tiled.exr", "small.tif", "small.png"):
        inputs[name] = open(os.path.join(folder, name), "rb").read()
    return inputs


def header_length(data):
    end = data.find(b"\n-Y ")
    if end < 0:
        end = data.find(b"\n+Y ")
    return end + 1 if end >= 0 else min(len(data), 400)


def mutate(rng, name, data):
    data = bytearray(data)
    kind = rng.choice(["flip", "flip", "overwrite", "truncate", "header", "header", "append"])
    head = header_length(data)
    if kind == "flip":
        for _ in range(rng.randint(1, 24)):
            i = rng.randrange(min(len(data), head + 4096) if rng.random() < 0.7 else len(data))
            data[i] ^= 1 << rng.randrange(8)
    elif kind == "overwrite":
        i = rng.randrange(len(data))
        data[i:i + rng.randint(1, 64)] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
    elif kind == "truncate":
        data = data[:rng.randrange(len(data))]
    elif kind == "append":
        data += bytes(rng.randrange(256) for _ in range(rng.randint(1, 4096)))
    elif name.endswith(".hdr"):  # the resolution line, or the format line
        numbers = [0, 1, 2, 3, -1, 7, 65535, 65536, 2 ** 31 - 1, 2 ** 31, 2 ** 32 + 5, 10 ** 12]
        line = rng.choice([b"-Y %d +X %d", b"+Y %d -X %d", b"-Y %d +X %d junk", b"-Y %d"])
        values = tuple(rng.choice(numbers + [rng.randrange(1, 100000)]) for _ in range(line.count(b"%d")))
        res = data.find(b"\n-Y ")
        eol = data.find(b"\n", res + 1)
        if rng.random() < 0.8:
            data[res + 1:eol] = line % values
        else:
            data[:res] = rng.choice([b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n", b"#?RGBE\n",
                                     b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=-1e30\n", b""])
    else:  # a binary header: 32-bit fields among its first bytes set to edge values
        for _ in range(rng.randint(1, 6)):
            i = rng.randrange(min(len(data) - 4, 400))
            value = rng.choice([0, 1, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF, rng.randrange(1 << 32)])
            data[i:i + 4] = value.to_bytes(4, "little")
    return bytes(data), kind


def limit():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def lights_problem(out):
    """None when `out` is a whole JSON of finite lights with non-negative colours, else what is wrong."""
    try:
        d = json.load(open(out))
        values = [v for light in d["lights"] for v in light["rgb"] + light["direction"]]
        if not all(math.isfinite(v) for v in values) or any(v < 0 for l in d["lights"] for v in l["rgb"]):
            return "a non-finite or negative light"
    except (OSError, ValueError, KeyError) as e:
        return f"no whole JSON ({e})"
    return None


def run_batch(binary, folder, batch):
    """Bakes `batch` (cases) as one library; returns {index: problem or None}, or None when the process itself
    failed (crash, hang, an exit other than 0 or 3), for the caller to bake the cases one by one."""
    first = batch[0][0]
    inputs, outputs = os.path.join(folder, f"batch{first}"), os.path.join(folder, f"batch{first}-out")
    os.makedirs(inputs)
    paths = {}
    for index, name, data, _ in batch:
        path = os.path.join(inputs, f"case{index}{os.path.splitext(name)[1]}")
        with open(path, "wb") as f:
            f.write(data)
        paths[path] = index
    args = [binary, "bake", inputs, "--out-dir", outputs, "--lights", "8", "--projection", "latlong", "-q"]
    try:
        p = subprocess.run(args, capture_output=True, timeout=TIME_LIMIT * 4, preexec_fn=limit)
    except subprocess.TimeoutExpired:
        return None
    if p.returncode not in (0, 3):
        return None
    try:
        summary = json.load(open(os.path.join(outputs, "summary.json")))
    except (OSError, ValueError):
        return None
    found = {}
    for entry in summary["results"]:
        index = paths.get(entry["probe"])
        if "error" in entry:
            found[index] = "an error of more than one line" if "\n" in entry["error"].strip() else None
        else:
            found[index] = lights_problem(os.path.join(outputs, entry["output"]))
    if set(found) != set(paths.values()) or summary.get("not_started"):
        return None
    shutil.rmtree(inputs)
    shutil.rmtree(outputs)
    return found


def run_case(binary, folder, index, name, data, kind):
    path = os.path.join(folder, f"case{index}{os.path.splitext(name)[1]}")
    out = path + ".json"
    with open(path, "wb") as f:
        f.write(data)

    args = [binary, "bake", path, "--lights", "8", "--projection", "latlong", "-q", "-o", out]
    try:
        p = subprocess.run(args, capture_output=True, timeout=TIME_LIMIT, preexec_fn=limit)
    except subprocess.TimeoutExpired:
        return f"timed out after {TIME_LIMIT} s (kept {path})"
    err = p.stderr.decode(errors="replace")
    problem = None
    if p.returncode == 0:
        wrong = lights_problem(out)
        problem = f"exit 0 with {wrong}" if wrong else None
    elif p.returncode == 2:
        if err.count("\n") != 1 or not err.startswith("probelights: error: "):
            problem = "exit 2 without exactly one error line"
    else:
        problem = f"exit {p.returncode}"
    if problem is None:
        for f in (path, out):
            if os.path.exists(f):
                os.remove(f)
        return None
    return f"{problem}: {err.strip()[:300]} (kept {path})"


def main():
    binary, probe = sys.argv[1], sys.argv[2]
    cases = int(sys.argv[3]) if len(sys.argv) > 3 else 3000
    folder = tempfile.mkdtemp(prefix="probelights-fuzz-")
    inputs = make_inputs(probe, folder)
    rng = random.Random(20261202)
    names = sorted(inputs)
    weights = {"bundled.hdr": 1, "small.hdr": 4, "small.exr": 4, "tiled.exr": 2, "small.tif": 2, "small.png": 2}
    plan = []
    for i in range(cases):
        name = rng.choices(names, [weights[n] for n in names])[0]
        data, kind = mutate(rng, name, inputs[name])
        plan.append((i, name, data, kind))
    outcomes = {}
    failures = []
    batches = [plan[i:i + BATCH] for i in range(0, len(plan), BATCH)]
    retried = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        by_batch = {pool.submit(run_batch, binary, folder, batch): batch for batch in batches}
        alone = {pool.submit(run_case, binary, folder, *case): case for case in plan[::SINGLE]}
        for future in concurrent.futures.as_completed(by_batch):
            batch = by_batch[future]
            found = future.result()
            if found is None:  # the batch's process failed: each case alone says which
                retried += 1
                found = {case[0]: pool.submit(run_case, binary, folder, *case).result() for case in batch}
            for i, name, _, kind in batch:
                outcomes[(name, kind)] = outcomes.get((name, kind), 0) + 1
                if found[i]:
                    failures.append(f"case {i} ({name}, {kind}) in a library: {found[i]}")
        for future in concurrent.futures.as_completed(alone):
            i, name, _, kind = alone[future]
            if future.result():
                failures.append(f"case {i} ({name}, {kind}) alone: {future.result()}")
    if retried:
        print(f"{retried} batches failed as processes and were baked case by case")
    print(f"{cases} mutated probes in libraries of {BATCH}, every {SINGLE}th also alone; by file and mutation: " +
          ", ".join(f"{n} {k} {c}" for (n, k), c in sorted(outcomes.items())))
    if failures:
        kept = os.path.join(os.path.dirname(os.path.abspath(binary)), "fuzz-failures")
        os.makedirs(kept, exist_ok=True)
        for line in sorted(failures):
            print("FAIL", line)
        for f in os.listdir(folder):
            if f.startswith("case"):
                shutil.copy(os.path.join(folder, f), kept)
            elif f.startswith("batch") and not f.endswith("-out"):
                for g in os.listdir(os.path.join(folder, f)):
                    shutil.copy(os.path.join(folder, f, g), kept)
        print(f"{len(failures)} failures among {cases} cases; their files are in {kept}")
        sys.exit(1)
    shutil.rmtree(folder)
    print("every case ended in exit 0 with finite lights or exit 2 with one line")


if __name__ == "__main__":
    main()
