#!/usr/bin/env python3
"""plot_accuracy.py: draws the accuracy.csv of `lantern bench accuracy` with matplotlib.

Per group of comparable rows (scene, shininess, image size), two panels on log-log axes: the
interior RMSE (shading alone) and the whole-image RMSE (shading, silhouettes and aliasing)
against the milliseconds per frame. One curve per shading mode and sample count (colour: the
mode, line style: the sample count), the Pareto front of the panel's error as a staircase with
rings, and the 1e-3 acceptance line. Every drawn series has its own legend entry.

Usage: plot_accuracy.py bench-accuracy/accuracy.csv -o accuracy.svg [-o accuracy.png]
Needs Debian's python3-matplotlib; `lantern bench accuracy` runs it when it is installed.
"""
import argparse
import csv
import sys

ERROR_FLOOR = 1e-8  # log axes: a zero error is drawn here
ACCEPTANCE = 1e-3  # numerics.md 7.3: interior RMSE of a reference preset
MODE_COLOURS = {"flat": "#d62728", "gouraud": "#1f77b4", "phong": "#2ca02c"}
MSAA_STYLES = {1: "-", 2: "-.", 4: "--", 8: ":"}
PANELS = [
    ("interior_rmse", "pareto_interior", "interior RMSE (shading alone)"),
    ("rmse", "pareto_whole", "whole-image RMSE (shading, silhouettes, aliasing)"),
]


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("ms_per_frame", "rmse", "interior_rmse"):
            r[key] = float(r[key])
        for key in ("width", "height", "segments", "msaa", "pareto_interior", "pareto_whole"):
            r[key] = int(r[key])
    return rows


# The transparency methods' and shadow filters' markers (other scenes: circles).
METHOD_MARKERS = {"sorted": "s", "exact": "o", "weighted": "^", "hardware": "v", "pcf": "D", "pcss": "P"}


def group_of(row):
    return f"{row['scene']}, shininess {row['shininess']}, {row['width']}x{row['height']}"


def draw_panel(ax, rows, error, front_flag, title):
    curves = {}
    for r in rows:
        # Transparency scenes: one curve per method too (marker), the method in the label; the
        # shadow scenes: one per shadow filter and cascade count, along the map resolutions.
        method = r.get("transparency") or r.get("shadow_filter") or ""
        if r.get("shadow_cascades"):
            method += f" {r['shadow_cascades']}c"
        curves.setdefault((r["shading"], r["msaa"], method), []).append(r)
    for (mode, msaa, method), points in sorted(curves.items()):
        points.sort(key=lambda r: (r["segments"], int(r.get("shadow_resolution") or 0)))
        ax.plot([max(r["ms_per_frame"], 1e-3) for r in points],
                [max(r[error], ERROR_FLOOR) for r in points],
                color=MODE_COLOURS.get(mode, "black"), linestyle=MSAA_STYLES.get(msaa, "-"),
                marker=METHOD_MARKERS.get(method.split(" ")[0], "o"), markersize=3, linewidth=1.2,
                label=f"{mode}, {msaa}x MSAA" + (f", {method}" if method else ""))
    front = sorted((r for r in rows if r[front_flag]), key=lambda r: r["ms_per_frame"])
    if front:
        xs, ys = [], []
        for i, r in enumerate(front):
            x, y = max(r["ms_per_frame"], 1e-3), max(r[error], ERROR_FLOOR)
            if i > 0:  # a staircase: the best error so far holds until the next point
                xs.append(x)
                ys.append(ys[-1])
            xs.append(x)
            ys.append(y)
        ax.plot(xs, ys, color="black", linewidth=1.0, label="Pareto front")
        ax.plot([max(r["ms_per_frame"], 1e-3) for r in front],
                [max(r[error], ERROR_FLOOR) for r in front], linestyle="none", marker="o",
                markersize=8, markerfacecolor="none", markeredgecolor="black")
    ax.axhline(ACCEPTANCE, color="grey", linestyle=":", linewidth=1.0,
               label="1e-3 acceptance")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ms per frame")
    ax.set_ylabel(title)
    ax.grid(True, which="major", linewidth=0.3)
    ax.legend(fontsize=7, loc="best")


def plot(rows, outputs):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # Text stays text in the SVG (searchable, and the tests read the legend).
    plt.rcParams["svg.fonttype"] = "none"
    plt.rcParams["svg.hashsalt"] = "lantern"  # the same clip-path ids on every run
    groups = []
    for r in rows:
        if group_of(r) not in groups:
            groups.append(group_of(r))
    fig, axes = plt.subplots(len(groups), 2, figsize=(12, 4.4 * len(groups)), squeeze=False)
    for gi, group in enumerate(groups):
        in_group = [r for r in rows if group_of(r) == group]
        for col, (error, front_flag, title) in enumerate(PANELS):
            ax = axes[gi][col]
            draw_panel(ax, in_group, error, front_flag, title)
            ax.set_title(group, fontsize=10)
    fig.suptitle("lantern bench accuracy: error against ms per frame")
    fig.tight_layout()
    for path in outputs:
        # No date in the file: the same CSV gives the same SVG.
        metadata = {"Date": None} if path.endswith(".svg") else None
        fig.savefig(path, metadata=metadata)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="accuracy.csv written by lantern bench accuracy")
    parser.add_argument("-o", "--output", action="append", required=True,
                        help="the plot: .svg, .png or .pdf (repeatable)")
    args = parser.parse_args(argv)
    rows = read_rows(args.csv)
    if not rows:
        print(f"plot_accuracy.py: {args.csv}: no rows", file=sys.stderr)
        return 1
    plot(rows, args.output)
    for path in args.output:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
