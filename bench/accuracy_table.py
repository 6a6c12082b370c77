#!/usr/bin/env python3
"""The accuracy table of docs/results/accuracy.md: every probe in ../shared/hdri and Blender's studiolights, each method at 16 and 64
lights with and without the irradiance refit, through `probelights tradeoff`; prints a Markdown table of the best
(lowest diffuse error) per probe and count, and writes the plot of the bundled probe to docs/.

    python3 bench/accuracy_table.py            (after scripts/build.sh)
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
CLI = os.path.join(ROOT, "build", "bin", "probelights")
probes = sorted(glob.glob(os.path.join(ROOT, "..", "shared", "hdri", "*.hdr")) +
                glob.glob(os.path.join(ROOT, "..", "shared", "hdri", "*.exr")) +
                glob.glob("/usr/share/blender/datafiles/studiolights/world/*.exr"))
if not probes:
    sys.exit("no probes found")

print("| probe | 16 lights: best (diffuse / shadow) | 16: plain variance | 64 lights: best (diffuse / shadow) | "
      "64: plain variance | bake ms (64, variance) |")
print("|---|---|---|---|---|---|")
worst16 = worst64 = 0.0
for path in probes:
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([CLI, "tradeoff", path, "--counts", "16,64", "--effects", "diffuse,shadow", "-o", out.name],
                       check=True, stdout=subprocess.DEVNULL)
        rows = json.load(open(out.name))["rows"]
    cells = []
    for n in (16, 64):
        candidates = [r for r in rows if r["lights"] == n]
        best = min(candidates, key=lambda r: r["diffuse"])
        plain = next(r for r in candidates if r["method"] == "variance" and not r["refit"] and r["resolution"] == "full")
        cells.append("%.2f %% / %.2f %% (%s%s)" % (100 * best["diffuse"], 100 * best["shadow"], best["method"],
                                                  ", refit" if best["refit"] else ""))
        cells.append("%.2f %% / %.2f %%" % (100 * plain["diffuse"], 100 * plain["shadow"]))
        if n == 16:
            worst16 = max(worst16, best["diffuse"])
        else:
            worst64 = max(worst64, best["diffuse"])
            ms = plain["bake_ms"]
    print("| %s | %s | %s | %s | %s | %.1f |" % (os.path.basename(path), *cells, ms))
print()
print("Worst best-method diffuse error: %.2f %% at 16 lights, %.2f %% at 64." % (100 * worst16, 100 * worst64))
subprocess.run([CLI, "tradeoff", os.path.join(ROOT, "assets", "noon_grass_1k.hdr"), "--plot",
                os.path.join(ROOT, "docs", "tradeoff_noon_grass.png")], check=True, stdout=subprocess.DEVNULL)
