#!/usr/bin/python3
"""Plots of `ferret experiment` output (the paper's exploration figures).

    python3 examples/plot_experiment.py DIR

Reads DIR/summary.csv (and DIR/sweep_camera_fov.csv, DIR/sweep_ir_fov.csv if present)
and writes into DIR:
  time_<map>.png          mean time to find per zone and method, 95% intervals (paper Fig. 6a/b)
  sweep_camera_fov.png    mean time to find vs camera fov alpha (IR fov held), per map and method
  sweep_ir_fov.png        the same vs IR fov beta (camera fov held)
  ratios.csv              per map and zone: each method's time over rapid's and over the oracle's,
                          and the geometric mean of cdos/rapid over zones 2..N
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


def num(text):
    try:
        v = float(text)
    except ValueError:
        return math.nan
    return v


def ordered(methods):
    return sorted(methods, key=lambda m: (METHOD_ORDER.index(m) if m in METHOD_ORDER else 99, m))


def bar_plots(rows, out_dir):
    by_map = defaultdict(list)
    for r in rows:
        by_map[r["map"]].append(r)
    written = []
    for name, mrows in by_map.items():
        zones = sorted({int(r["zone"]) for r in mrows})
        methods = ordered({r["method"] for r in mrows})
        width = 0.8 / len(methods)
        fig, ax = plt.subplots(figsize=(7, 4))
        for k, method in enumerate(methods):
            cell = {int(r["zone"]): r for r in mrows if r["method"] == method}
            xs = [z + (k - (len(methods) - 1) / 2) * width for z in zones]
            means = [num(cell[z]["mean_time_s"]) if z in cell else math.nan for z in zones]
            cis = [num(cell[z]["ci95_time_s"]) if z in cell else 0 for z in zones]
            ax.bar(xs, means, width, yerr=cis, capsize=2, label=method, color=COLORS.get(method))
        ax.set_xticks(zones)
        ax.set_xticklabels(["zone %d" % z for z in zones])
        ax.set_ylabel("mean time to find the object (s)")
        ax.set_title("%s map: time to find per zone (95%% intervals)" % name)
        ax.legend()
        ax.grid(axis="y", alpha=0.3)
        fig.tight_layout()
        path = os.path.join(out_dir, "time_%s.png" % name)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def sweep_plot(rows, key, label, out_dir, name):
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
    ax.set_xlabel(label)
    ax.set_ylabel("mean time to find (s), all zones")
    ax.set_title("time to find vs %s" % label)
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


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_experiment.py DIR")
    out_dir = sys.argv[1]
    rows = read_rows(os.path.join(out_dir, "summary.csv"))
    written = bar_plots(rows, out_dir)
    written.append(ratios(rows, out_dir))
    for csv_name, key, label, png in [("sweep_camera_fov.csv", "camera_fov_deg", "camera fov alpha (deg)", "sweep_camera_fov.png"),
                                      ("sweep_ir_fov.csv", "ir_fov_deg", "IR fov beta (deg)", "sweep_ir_fov.png")]:
        p = os.path.join(out_dir, csv_name)
        if os.path.exists(p):
            written.append(sweep_plot(read_rows(p), key, label, out_dir, png))
    print("plotted: " + " ".join(written))


if __name__ == "__main__":
    main()
