"""The README's table of Fitted + Refit renders from scripts/bench_shadow_table.sh run with
PROBELIGHTS_SHADOW_CHOICES=FIT+refit (one file per Blender), beside the figures the README's big shadow table
holds for the same choice (the refit before it fitted on 1024 ground points):

    PROBELIGHTS_SHADOW_CHOICES=FIT+refit bash scripts/bench_shadow_table.sh BLENDER > refit45.txt
    python3 scripts/refit_table.py README.md refit45.txt refit34.txt
"""
import re
import sys

head = re.compile(r"ESTIMATE Blender (\S+).*?, (\S+), (\d+) spp: world noise ([\d.]+) %")
line = re.compile(r"ESTIMATE +(\d+) suns FIT +refit: estimate ([\d.]+) %, rendered ([\d.]+) % "
                  r"\(lamps' noise ([\d.]+) %; less both noises ([\d.]+) %\)")
old_row = re.compile(r"^\| (\S+) \| (\S+), \d+ \| [\d.]+ % \| ([^|]+) \| ([^|]+) \|$")

before = {}
for text in open(sys.argv[1]):
    if m := old_row.match(text.strip()):
        before[(m[1], m[2])] = [float(cell.split("/")[-1]) for cell in (m[3], m[4])]

rows = []
for path in sys.argv[2:]:
    current = None
    for text in open(path):
        if m := head.match(text):
            current = {"blender": m[1], "probe": m[2], "spp": m[3], "noise": m[4], "cells": {}}
            rows.append(current)
        elif (m := line.match(text)) and current:
            current["cells"][int(m[1])] = tuple(float(m[k]) for k in (2, 3, 4, 5))

print("| probe | Blender, spp | world noise | 16 refit suns: before -> **now** (estimate; lamps' noise; less both "
      "noises) | 64 refit suns: the same |")
print("|---|---|---|---|---|")
worst = {}
for r in sorted(rows, key=lambda r: (r["probe"].lower(), r["blender"])):
    old = before.get((r["probe"], r["blender"]), [float("nan")] * 2)
    cells = []
    for k, n in enumerate((16, 64)):
        if n not in r["cells"]:
            cells.append("-")
            continue
        est, ren, lamps, clean = r["cells"][n]
        cells.append("%.2f -> **%.2f** (%.2f; %.2f; %.2f)" % (old[k], ren, est, lamps, clean))
        worst.setdefault((r["blender"], n), []).append((clean, r["probe"]))
    print("| %s | %s, %s | %s %% | %s | %s |" % (r["probe"], r["blender"], r["spp"], r["noise"], cells[0], cells[1]))
for (blender, n), values in sorted(worst.items()):
    bar = 2.0 if n == 16 else 0.7
    over = ", ".join("%s %.2f" % (p, v) for v, p in sorted(values, reverse=True) if v > bar)
    print("Blender %s, %d refit suns, less both noises: worst %.2f %%; over %.1f %%: %s" % (
        blender, n, max(values)[0], bar, over or "none"), file=sys.stderr)
