#!/usr/bin/env python3
"""Draws tyndall-bench's time-against-error plots with matplotlib: for each plot in its pareto.json,
FILE.svg and FILE.png in OUTDIR, every configuration as a point (its time over the Reference's,
its relative RMSE of L_in; both medians over the scenes, on log axes), its Pareto front as a
staircase with its points numbered and listed, the profiles' picks circled and named.

The data (points, front, picks) is tyndall-bench's (samples/bench/pareto.h); this script only draws.
Usage: scripts/plot-pareto.py PARETO_JSON OUTDIR
"""
import argparse
import json
import math
import os
import sys

try:
    import matplotlib
except ImportError:
    sys.exit(f"plot-pareto.py: {sys.executable} has no matplotlib: apt-get install python3-matplotlib "
             "(scripts/install-deps.sh), or run it with a python3 that has it")

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator  # noqa: E402

# Okabe–Ito colours and four shapes: series stay distinct for colour-blind readers and in grey.
COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]
SHAPES = ["o", "s", "^", "D"]
FRONT_COLOUR = "#404040"
# Rendered byte-for-byte alike on every run, so that regenerating a committed plot changes nothing.
matplotlib.rcParams.update({"svg.hashsalt": "tyndall-pareto", "svg.fonttype": "none", "font.size": 11})


def ratio_text(value, _position=None):
    """A tick label of the time axis: 0.02, 0.5, 2 (as many digits as the value needs)."""
    return f"{value:.10g}"


def percent_text(value, _position=None):
    """A tick label of the error axis in percent: 0.5%, 2%, 10%."""
    return f"{100 * value:.10g}%"


def log_axis(axis, formatter):
    # Labels at 1, 2 and 5 of each decade: the data often spans less than two decades.
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(formatter))
    axis.set_minor_locator(LogLocator(base=10, subs=tuple(range(2, 10))))
    axis.set_minor_formatter(FuncFormatter(lambda *_: ""))


def decade_limits(values):
    """Log-axis limits around `values` with a margin, spanning at least a decade so that the axis
    carries tick labels."""
    lo, hi = math.log10(min(values)), math.log10(max(values))
    margin = 0.05 * (hi - lo)
    lo, hi = lo - margin, hi + margin
    if hi - lo < 1.0:
        middle = 0.5 * (lo + hi)
        lo, hi = middle - 0.5, middle + 0.5
    return 10 ** lo, 10 ** hi


def draw(plot, outdir):
    points = plot["points"]
    finite = [p for p in points if p["x"] is not None and p["y"] is not None
              and math.isfinite(p["x"]) and math.isfinite(p["y"]) and p["x"] > 0]
    notes = []
    if len(finite) < len(points):
        notes.append(f"{len(points) - len(finite)} non-finite, not drawn")
    # A configuration with no error at all would vanish from a log axis: drawn at its bottom.
    xlim = decade_limits([p["x"] for p in finite] or [1.0])
    ylim = decade_limits([p["y"] for p in finite if p["y"] > 0] or [0.01])
    y_floor = ylim[0]
    at_floor = sum(1 for p in finite if p["y"] <= 0)
    if at_floor:
        notes.append(f"{at_floor} with zero error, drawn at the axis minimum")

    def y_of(p):
        return p["y"] if p["y"] > 0 else y_floor

    fig, ax = plt.subplots(figsize=(12.8, 8.0), dpi=100, layout="constrained")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", color="#e0e0e0", linewidth=0.8)
    ax.set_axisbelow(True)

    series = []
    for p in finite:
        if p["series"] not in series:
            series.append(p["series"])
    for k, name in enumerate(series):
        members = [p for p in finite if p["series"] == name]
        ax.scatter([p["x"] for p in members], [y_of(p) for p in members], s=36, marker=SHAPES[k % len(SHAPES)],
                   color=COLOURS[k % len(COLOURS)], label=name, zorder=3, clip_on=False)

    front = sorted((p for p in finite if p["front"] > 0), key=lambda p: p["front"])
    if front:
        # The staircase: from each front point right to the next one's time, then down to its error.
        ax.step([p["x"] for p in front], [y_of(p) for p in front], where="post", color=FRONT_COLOUR,
                linewidth=1.6, zorder=2, label="Pareto front")
        for p in front:
            ax.annotate(str(p["front"]), (p["x"], y_of(p)), xytext=(4, 4), textcoords="offset points",
                        fontsize=9, color=FRONT_COLOUR, zorder=5)

    picks = [p for p in finite if p["marker"]]
    if picks:
        ax.scatter([p["x"] for p in picks], [y_of(p) for p in picks], s=220, facecolors="none",
                   edgecolors="black", linewidths=1.8, zorder=4, label="picked for a profile", clip_on=False)
        for p in picks:
            ax.annotate(p["marker"], (p["x"], y_of(p)), xytext=(10, -14), textcoords="offset points", fontsize=10,
                        fontweight="bold", zorder=5)

    log_axis(ax.xaxis, ratio_text)
    log_axis(ax.yaxis, percent_text)
    ax.set_xlabel("GPU time / the Reference's GPU time (ratio, log scale; smaller is faster)")
    ax.set_ylabel("relative RMSE of L_in against the Reference (%, log scale)")
    ax.set_title(plot["title"], fontsize=12)

    # The front's points by number, and any notes, listed in the legend under its symbols (text-only
    # entries), so that the layout makes room for the longest configuration name.
    handles, labels = ax.get_legend_handles_labels()
    listing = ([""] + ["Pareto front:"] if front else []) + [f"{p['front']:>2}  {p['label']}" for p in front]
    listing += [""] + notes if notes else []
    handles += [Line2D([], [], linestyle="none")] * len(listing)
    ax.legend(handles, labels + listing, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              frameon=False, fontsize=9, handlelength=1.5)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    if not finite:
        ax.text(0.5, 0.5, "no drawable point", transform=ax.transAxes, ha="center", va="center")
        ax.xaxis.set_major_locator(NullLocator())
        ax.yaxis.set_major_locator(NullLocator())

    stem = os.path.join(outdir, plot["file"])
    fig.savefig(stem + ".svg", metadata={"Date": None})
    fig.savefig(stem + ".png", metadata={"Software": None})
    plt.close(fig)
    return [stem + ".svg", stem + ".png"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pareto_json", help="tyndall-bench's OUT/pareto.json")
    parser.add_argument("outdir", help="where FILE.svg and FILE.png go")
    args = parser.parse_args()
    with open(args.pareto_json) as f:
        plots = json.load(f)["plots"]
    if not plots:
        sys.exit(f"plot-pareto.py: {args.pareto_json} holds no plot")
    os.makedirs(args.outdir, exist_ok=True)
    for plot in plots:
        for path in draw(plot, args.outdir):
            print(path)


if __name__ == "__main__":
    main()
