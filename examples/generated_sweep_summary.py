#!/usr/bin/env python3
"""Pools the fov sweeps of an experiment on generated hidden spaces (maps named
CLUTTER-sSEED, as a `generate:` entry names them) by clutter: for each swept fov
value, each method's mean time to find over zones 2-5 and the objects it found,
and per object found by both, the geometric mean of one method's time over
another's with its 95 % interval (examples/generated_summary.py's). Zone 1 (in front
of both sensors at the start) gets its own ratio row.

    python3 examples/generated_sweep_summary.py out/generated_fov/runs.csv > sweeps.md

Python's standard library only. Prints Markdown tables, one a sweep.
"""
import csv
import sys
from collections import defaultdict

from generated_summary import geomean_ci

SWEEPS = (("camera_fov", "camera_fov_deg", "camera fov α (IR fov held)"),
          ("ir_fov", "ir_fov_deg", "IR fov β (camera fov held)"))
PAIRS = (("bayes", "cdos"), ("bayes", "rapid"), ("cdos", "rapid"))


def found(r):
    return r["found"] in ("1", "true", "yes")


def fmt_value(v):
    return f"{float(v):g}°"


def main(path):
    runs = list(csv.DictReader(open(path, newline="")))
    for experiment, column, title in SWEEPS:
        rows = [r for r in runs if r["experiment"] == experiment]
        if not rows:
            continue
        values = sorted({float(r[column]) for r in rows})
        methods = []
        for r in rows:
            if r["method"] not in methods:
                methods.append(r["method"])
        held = sorted({r["ir_fov_deg" if column == "camera_fov_deg" else "camera_fov_deg"] for r in rows})
        # (clutter, value, zone group) -> method -> object key -> time or None
        times = defaultdict(lambda: defaultdict(dict))
        for r in rows:
            clutter = r["map"].split("-s")[0]
            group = "1" if r["zone"] == "1" else "2-5"
            key = (r["map"], r["zone"], r["object"])
            times[(clutter, float(r[column]), group)][r["method"]][key] = float(r["time_s"]) if found(r) else None
        maps = sorted({r["map"] for r in rows})
        print(f"### {title}: {', '.join(held)}° held; {len(maps)} maps, {len(rows)} runs\n")
        print("| clutter | zones 2–5 | " + " | ".join(fmt_value(v) for v in values) + " |")
        print("|---|---|" + "---:|" * len(values))
        for clutter in sorted({k[0] for k in times}):
            for m in methods:
                cells = []
                for v in values:
                    ts = times[(clutter, v, "2-5")][m]
                    ok = [t for t in ts.values() if t is not None]
                    mean = sum(ok) / len(ok) if ok else float("nan")
                    cells.append(f"{mean:.1f} s ({len(ok)}/{len(ts)})")
                print(f"| {clutter} | {m} | " + " | ".join(cells) + " |")
            for group in ("2-5", "1"):
                for a, b in PAIRS:
                    if a not in methods or b not in methods:
                        continue
                    if group == "1" and b == "rapid":
                        continue
                    cells = []
                    for v in values:
                        by = times[(clutter, v, group)]
                        ratios = [by[a][k] / by[b][k] for k in by[a]
                                  if by[a][k] and by[b].get(k)]
                        g, lo, hi = geomean_ci(ratios)
                        cells.append(f"**{g:.2f}** [{lo:.2f}, {hi:.2f}]")
                    label = f"{a} / {b}" + ("" if group == "2-5" else ", zone 1")
                    print(f"| {clutter} | {label} | " + " | ".join(cells) + " |")
        print()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
