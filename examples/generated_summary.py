#!/usr/bin/env python3
"""Pools an experiment on generated hidden spaces (maps named CLUTTER-sSEED, as a
`generate:` entry names them) by clutter and zone: found/runs per method, and per
object found by both, the geometric mean of each method's time over the oracle's and
over rapid's, with its 95 % interval (Student t on the log ratios, exponentiated).
Zones 2-5 are also pooled, the zones the search policies differ in.

    python3 examples/generated_summary.py out/generated/runs.csv > summary.md

Python's standard library only. Prints Markdown tables.
"""
import csv
import math
import sys
from collections import defaultdict

# Two-sided 97.5 % quantiles of Student's t for small samples; 1.96 beyond.
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262,
        10: 2.228, 15: 2.131, 20: 2.086, 30: 2.042, 60: 2.000, 120: 1.980}


def t975(df):
    keys = [k for k in sorted(T975) if k <= df]
    return T975[keys[-1]] if keys and df <= 120 else 1.96


def geomean_ci(ratios):
    logs = [math.log(r) for r in ratios]
    n = len(logs)
    if n == 0:
        return float("nan"), float("nan"), float("nan")
    m = sum(logs) / n
    if n < 2:
        return math.exp(m), float("nan"), float("nan")
    s = math.sqrt(sum((x - m) ** 2 for x in logs) / (n - 1))
    h = t975(n - 1) * s / math.sqrt(n)
    return math.exp(m), math.exp(m - h), math.exp(m + h)


def main(path):
    runs = list(csv.DictReader(open(path, newline="")))
    runs = [r for r in runs if r["experiment"] == "main"]
    methods = []
    for r in runs:
        if r["method"] not in methods:
            methods.append(r["method"])
    # (clutter, zone group) -> method -> object key -> time (None when not found)
    times = defaultdict(lambda: defaultdict(dict))
    for r in runs:
        clutter = r["map"].split("-s")[0]
        key = (r["map"], r["zone"], r["object"])
        t = float(r["time_s"]) if r["found"] in ("1", "true", "yes") else None
        for group in (r["zone"], "2-5" if r["zone"] != "1" else None):
            if group:
                times[(clutter, group)][r["method"]][key] = t
    maps = sorted({r["map"] for r in runs})
    print(f"{len(maps)} maps, {len(runs)} runs, methods {', '.join(methods)}\n")
    baselines = [b for b in ("oracle", "rapid") if b in methods]
    header = "| clutter | zone | method | found | mean time (s) | " + " | ".join(
        f"geomean / {b} [95 %]" for b in baselines) + " |"
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for (clutter, group) in sorted(times, key=lambda k: (k[0], k[1] != "2-5", k[1])):
        by = times[(clutter, group)]
        for m in methods:
            ts = by[m]
            found = [t for t in ts.values() if t is not None]
            cells = []
            for b in baselines:
                if b == m:
                    cells.append("")
                    continue
                ratios = [ts[k] / by[b][k] for k in ts
                          if ts[k] is not None and by[b].get(k) is not None and by[b][k] > 0 and ts[k] > 0]
                g, lo, hi = geomean_ci(ratios)
                cells.append(f"{g:.2f} [{lo:.2f}, {hi:.2f}] (n {len(ratios)})")
            mean = sum(found) / len(found) if found else float("nan")
            print(f"| {clutter} | {group} | {m} | {len(found)}/{len(ts)} | {mean:.1f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
