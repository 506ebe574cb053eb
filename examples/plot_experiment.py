#!/usr/bin/python3
"""Plots of `ferret experiment` output (the paper's exploration figures).

    python3 examples/plot_experiment.py DIR

Reads DIR/summary.csv (and DIR/sweep_camera_fov.csv, DIR/sweep_ir_fov.csv if present)
and writes into DIR:
  time_<map>.png          mean time to find per zone and method with the CSV's 95% bootstrap
                          intervals (paper Fig. 6a/b)
  sweep_camera_fov.png    mean time to find vs camera fov alpha (IR fov held), per map and method
  sweep_ir_fov.png        the same vs IR fov beta (camera fov held)
  ratios.csv              per map and zone: each method's time over rapid's and over the oracle's,
                          and the geometric mean of cdos/rapid over zones 2..N
  paired_ratios.csv       with DIR/runs.csv: per map, zone and method, the per-object ratio of its
                          time to rapid's (same object, same noise), their geometric mean with a
                          95% interval on the log scale (never below zero), and how many objects
                          it found faster
Sharded runs: concatenate the shards' CSVs first (docs/object_search.md).
Needs python3-matplotlib (Debian).
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHOD_ORDER = ["cdos", "cdos-literal", "rapid", "nearest", "oracle"]
COLORS = {"cdos": "#d95f02", "cdos-literal": "#e6ab02", "rapid": "#1b9e77", "nearest": "#7570b3", "oracle": "#666666"}


def read_rows(path):
    """Rows of a CSV; repeated header lines (from concatenated shards) are skipped."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return [r for r in reader if r["map"] != "map"]


# Student t quantile at 0.975 for 1..30 degrees of freedom; beyond, 1.96 + 2.4/df is
# within 0.01 of it (the same table the experiment used before its bootstrap intervals).
T975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042]


def t975(df):
    return T975[df - 1] if df <= 30 else 1.96 + 2.4 / df


def geometric_mean_ci95(values):
    """Geometric mean of positive values and its 95% interval: the Student t interval of
    the mean of the logs, exponentiated (a ratio's interval that cannot reach zero and is
    symmetric in a/b versus b/a). (nan, nan, nan) if any value is not positive;
    (g, nan, nan) for one value."""
    if not values or any(not (v > 0) or math.isinf(v) for v in values):
        return math.nan, math.nan, math.nan
    logs = [math.log(v) for v in values]
    n = len(logs)
    m = sum(logs) / n
    if n < 2:
        return math.exp(m), math.nan, math.nan
    sd = math.sqrt(sum((x - m) ** 2 for x in logs) / (n - 1))
    half = t975(n - 1) * sd / math.sqrt(n)
    return math.exp(m), math.exp(m - half), math.exp(m + half)


def interval(row):
    """(lo, hi) of a summary row: the bootstrap columns, or an old CSV's symmetric
    half-width clipped at zero."""
    if "ci95_lo_time_s" in row:
        return num(row["ci95_lo_time_s"]), num(row["ci95_hi_time_s"])
    mean, half = num(row["mean_time_s"]), num(row["ci95_time_s"])
    return max(0.0, mean - half), mean + half


def num(text):
    try:
        v = float(text)
    except ValueError:
        return math.nan
    return v


def ordered(methods):
    return sorted(methods, key=lambda m: (METHOD_ORDER.index(m) if m in METHOD_ORDER else 99, m))


def zone_ratio_summary(mrows):
    """'cdos / rapid over zones 2-5: 0.14' (geometric mean of the zones' mean-time ratios)."""
    t = {(int(r["zone"]), r["method"]): num(r["mean_time_s"]) for r in mrows}
    zones = sorted({z for z, _ in t if z >= 2})
    ratios = [t[(z, "cdos")] / t[(z, "rapid")] for z in zones
              if (z, "cdos") in t and (z, "rapid") in t and t[(z, "rapid")] > 0]
    ratios = [x for x in ratios if x > 0 and not math.isnan(x)]
    if not ratios:
        return ""
    g = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
    return "cdos / rapid over zones %d-%d: %.2f (geometric mean of the zone means)" % (
        zones[0], zones[-1], g)


def bar_plots(rows, out_dir):
    by_map = defaultdict(list)
    for r in rows:
        by_map[r["map"]].append(r)
    written = []
    for name, mrows in by_map.items():
        zones = sorted({int(r["zone"]) for r in mrows})
        methods = ordered({r["method"] for r in mrows})
        width = 0.8 / len(methods)
        fig, ax = plt.subplots(figsize=(8, 4.6))
        for k, method in enumerate(methods):
            cell = {int(r["zone"]): r for r in mrows if r["method"] == method}
            xs = [z + (k - (len(methods) - 1) / 2) * width for z in zones]
            means = [num(cell[z]["mean_time_s"]) if z in cell else math.nan for z in zones]
            lows, highs = [], []
            for z, m in zip(zones, means):
                lo, hi = interval(cell[z]) if z in cell else (math.nan, math.nan)
                # No bar where there is no interval (fewer than two finds).
                lows.append(m - lo if not math.isnan(lo) else 0.0)
                highs.append(hi - m if not math.isnan(hi) else 0.0)
            found = sum(int(cell[z]["found"]) for z in zones if z in cell)
            runs = sum(int(cell[z]["runs"]) for z in zones if z in cell)
            ax.bar(xs, means, width, yerr=[lows, highs], capsize=2, color=COLORS.get(method),
                   label="%s (found %d/%d)" % (method, found, runs), error_kw={"elinewidth": 0.8})
        ax.set_xticks(zones)
        ax.set_xticklabels(["zone %d" % z for z in zones])
        ax.set_ylabel("mean time to find the object (s)")
        ax.set_ylim(bottom=0)
        result = zone_ratio_summary(mrows)
        ax.set_title("%s map: mean time to find per zone and method\n%s%s95%% bootstrap intervals"
                     % (name, result, "; " if result else ""), fontsize=10)
        ax.legend(fontsize=8)
        ax.grid(axis="y", alpha=0.3)
        fig.tight_layout()
        path = os.path.join(out_dir, "time_%s.png" % name)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def sweep_plot(rows, key, label, held, out_dir, name):
    # Mean over zones of each (map, method, fov), weighted by runs found.
    acc = defaultdict(lambda: [0.0, 0])
    for r in rows:
        found = int(r["found"])
        mean = num(r["mean_time_s"])
        if found and not math.isnan(mean):
            a = acc[(r["map"], r["method"], num(r[key]))]
            a[0] += mean * found
            a[1] += found
    maps = sorted({k[0] for k in acc})
    methods = ordered({k[1] for k in acc})
    fig, ax = plt.subplots(figsize=(7, 4))
    styles = ["-o", "--s", ":^", "-.d"]
    for mi, m in enumerate(maps):
        for method in methods:
            pts = sorted((k[2], v[0] / v[1]) for k, v in acc.items() if k[0] == m and k[1] == method and v[1])
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], styles[mi % len(styles)],
                        color=COLORS.get(method), label="%s, %s" % (method, m))
    # The result: the range of cdos / rapid over the swept values, per map.
    spans = []
    for m in maps:
        per = {}
        for (mm, method, fov), v in acc.items():
            if mm == m and v[1]:
                per[(method, fov)] = v[0] / v[1]
        r = [per[("cdos", f)] / per[("rapid", f)] for (meth, f) in per if meth == "cdos" and ("rapid", f) in per]
        if r:
            spans.append("%s %.2f-%.2f" % (m, min(r), max(r)))
    held_rows = {num(r[held[0]]) for r in rows}
    held_text = "%s = %s deg" % (held[1], ", ".join("%g" % v for v in sorted(held_rows)))
    ax.set_xlabel(label)
    ax.set_ylabel("mean time to find (s), all zones")
    ax.set_ylim(bottom=0)
    ax.set_title("time to find vs %s (%s), mean over all zones' finds\n%s" % (
        label.replace(" (deg)", ""), held_text, ("cdos / rapid: " + ", ".join(spans)) if spans else ""), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def ratios(rows, out_dir):
    cell = {(r["map"], int(r["zone"]), r["method"]): num(r["mean_time_s"]) for r in rows}
    path = os.path.join(out_dir, "ratios.csv")
    lines = ["map,zone,method,mean_time_s,ratio_to_rapid,ratio_to_oracle"]
    logs = []
    for (m, z, method), t in sorted(cell.items(), key=lambda kv: (kv[0][0], kv[0][1], ordered([kv[0][2]]))):
        rapid = cell.get((m, z, "rapid"), math.nan)
        oracle = cell.get((m, z, "oracle"), math.nan)
        lines.append("%s,%d,%s,%.4g,%.4g,%.4g" % (m, z, method, t, t / rapid if rapid else math.nan,
                                                  t / oracle if oracle else math.nan))
        if method == "cdos" and z >= 2 and rapid and not math.isnan(t / rapid):
            logs.append(math.log(t / rapid))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
        if logs:
            f.write("# geometric mean of cdos/rapid over zones >= 2 of all maps: %.3f\n" % math.exp(sum(logs) / len(logs)))
    return path


def paired_ratios(runs, out_dir):
    """Per (map, zone, method): the ratio of its time to rapid's on each object both found."""
    time = {}
    for r in runs:
        if r["experiment"] == "main" and r["found"] == "1":
            time[(r["map"], int(r["zone"]), r["method"], int(r["object"]))] = num(r["time_s"])
    keys = sorted({(m, z, meth) for (m, z, meth, _) in time if meth != "rapid"},
                  key=lambda k: (k[0], k[1], ordered([k[2]])))
    lines = ["map,zone,method,baseline,pairs,geomean_ratio,ci95_lo,ci95_hi,faster"]
    for m, z, meth in keys:
        pairs = [(t, time[(m, z, "rapid", o)]) for (mm, zz, me, o), t in time.items()
                 if (mm, zz, me) == (m, z, meth) and (m, z, "rapid", o) in time]
        ratios = [a / b for a, b in pairs if b > 0]
        g, lo, hi = geometric_mean_ci95(ratios)
        lines.append("%s,%d,%s,rapid,%d,%.4g,%.4g,%.4g,%d" % (m, z, meth, len(ratios), g, lo, hi,
                                                             sum(a < b for a, b in pairs)))
    path = os.path.join(out_dir, "paired_ratios.csv")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_experiment.py DIR")
    out_dir = sys.argv[1]
    rows = read_rows(os.path.join(out_dir, "summary.csv"))
    written = bar_plots(rows, out_dir)
    written.append(ratios(rows, out_dir))
    runs_path = os.path.join(out_dir, "runs.csv")
    if os.path.exists(runs_path):
        written.append(paired_ratios(read_rows(runs_path), out_dir))
    for csv_name, key, label, held, png in [
            ("sweep_camera_fov.csv", "camera_fov_deg", "camera fov alpha (deg)", ("ir_fov_deg", "IR fov beta"),
             "sweep_camera_fov.png"),
            ("sweep_ir_fov.csv", "ir_fov_deg", "IR fov beta (deg)", ("camera_fov_deg", "camera fov alpha"),
             "sweep_ir_fov.png")]:
        p = os.path.join(out_dir, csv_name)
        if os.path.exists(p):
            written.append(sweep_plot(read_rows(p), key, label, held, out_dir, png))
    print("plotted: " + " ".join(written))


if __name__ == "__main__":
    main()
