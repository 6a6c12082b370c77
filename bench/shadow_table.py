"""The before/after shadow table of docs/results/shadows.md from bench/bench_shadow_table.sh's output (one file per Blender):

    python3 bench/shadow_table.py table45.txt table34.txt

One row per probe and Blender: the world-lit render's noise, then for 16 and 64 suns the rendered relative RMS
difference to the world-lit render for each Shadows choice (Hard; Region spread, the angle before issue 9; Fitted;
Fitted with the refit), the estimate in brackets where it is the add-on's default (Fitted).
"""
import re
import sys

CHOICES = ("HARD", "SPREAD", "FIT", "FIT refit")
head = re.compile(r"ESTIMATE Blender (\S+).*?, (\S+), (\d+) spp: world noise ([\d.]+) %")
line = re.compile(r"ESTIMATE +(\d+) suns (\w+) +(refit)?: estimate ([\d.]+) %, rendered ([\d.]+) %")
# Issue 9's bar: 16 suns within 2 %, 64 within 0.7 % of the world-lit render.
BARS = {16: 2.0, 64: 0.7}


def read_renders(paths, pattern, cell):
    """bench_shadow_estimate.py's output, one file per Blender: a dict per probe and Blender (blender, probe, spp,
    noise, cells), its cells[key] = value for each line `pattern` matches, (key, value) = cell(match)."""
    rows = []
    for path in paths:
        current = None
        for text in open(path):
            if m := head.match(text):
                current = {"blender": m[1], "probe": m[2], "spp": m[3], "noise": m[4], "cells": {}}
                rows.append(current)
            elif (m := pattern.match(text)) and current:
                key, value = cell(m)
                current["cells"][key] = value
    return rows


def main():
    rows = read_renders(sys.argv[1:], line,
                        lambda m: ((int(m[1]), m[2] + (" refit" if m[3] else "")), (float(m[4]), float(m[5]))))
    print("| probe | Blender, spp | world noise | 16: hard / spread / **fitted** (estimate) / fitted+refit "
          "| 64: hard / spread / **fitted** (estimate) / fitted+refit |")
    print("|---|---|---|---|---|")
    worst = {}
    for r in sorted(rows, key=lambda r: (r["probe"].lower(), r["blender"])):
        cells = []
        for n in (16, 64):
            parts = []
            for choice in CHOICES:
                if (n, choice) not in r["cells"]:
                    parts.append("-")
                    continue
                est, ren = r["cells"][(n, choice)]
                parts.append("**%.2f** (%.2f)" % (ren, est) if choice == "FIT" else "%.2f" % ren)
                if choice.startswith("FIT"):
                    key = (r["blender"], n)
                    best = min(r["cells"][(n, c)][1] for c in ("FIT", "FIT refit") if (n, c) in r["cells"])
                    worst[key] = max(worst.get(key, 0), best)
            cells.append(" / ".join(parts))
        print("| %s | %s, %s | %s %% | %s | %s |" % (r["probe"], r["blender"], r["spp"], r["noise"], cells[0], cells[1]))
    for (blender, n), value in sorted(worst.items()):
        print("worst over the probes, Blender %s, %d suns, better of fitted and fitted+refit: %.2f %%" % (blender, n, value),
              file=sys.stderr)
    for blender in sorted({r["blender"] for r in rows}):
        for choice in ("FIT", "FIT refit"):
            for n, bar in BARS.items():
                mine = [r for r in rows if r["blender"] == blender and (n, choice) in r["cells"]]
                over = ["%s %.2f" % (r["probe"].rsplit(".", 1)[0], r["cells"][(n, choice)][1]) for r in mine
                        if r["cells"][(n, choice)][1] > bar]
                print("Blender %s, %s, %d suns: %d of %d probes within %.1f %%; over: %s" % (
                    blender, choice.lower(), n, len(mine) - len(over), len(mine), bar, ", ".join(over) or "none"),
                    file=sys.stderr)


if __name__ == "__main__":
    main()
