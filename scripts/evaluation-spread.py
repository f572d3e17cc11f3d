#!/usr/bin/env python3
"""Prints the prefiltered evaluation pass's spread over scenes, (max - min) / median of its time
(issue 4's cost independence asks < 15%), one line per variant measured on two scenes or more.

Reads the rows scripts/measure-prefiltered.sh appends to MEASURE_OUT/evaluations-WxH.tsv
(variant, scene, evaluate ms); --prefix / --exclude-prefix keep the scenes whose names start (or
do not start) with a string, and --title names that group in the line.
"""
import argparse
import statistics


def ms(v):  # as measure-prefiltered.sh writes its table: three significant digits down to 0.001 ms
    return f"{v:.1f}" if v >= 10 else f"{v:.2f}" if v >= 1 else f"{v:.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tsv")
    parser.add_argument("--prefix", default="", help="only scenes whose name starts with this")
    parser.add_argument("--exclude-prefix", help="no scene whose name starts with this")
    parser.add_argument("--title", help="the group's name in the line")
    args = parser.parse_args()
    rows = {}
    for line in open(args.tsv):
        basis, scene, milliseconds = line.rstrip("\n").split("\t")
        if not scene.startswith(args.prefix):
            continue
        if args.exclude_prefix and scene.startswith(args.exclude_prefix):
            continue
        rows.setdefault(basis, []).append((scene, float(milliseconds)))
    for basis, runs in rows.items():
        if len(runs) < 2:
            continue
        times = [t for _, t in runs]
        median = statistics.median(times)
        spread = (max(times) - min(times)) / median if median > 0 else 0.0
        lo = min(runs, key=lambda r: r[1])
        hi = max(runs, key=lambda r: r[1])
        title = f", {args.title}" if args.title else ""
        print(f"{basis}{title}: evaluate {ms(lo[1])} ms ({lo[0]}) to {ms(hi[1])} ms ({hi[0]}) over {len(runs)} "
              f"scenes, (max - min) / median {spread * 100:.0f}% (issue 4 asks < 15%)")


if __name__ == "__main__":
    main()
