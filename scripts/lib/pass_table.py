#!/usr/bin/env python3
"""Per-pass GPU times of a tyndall-bench results.json: for each configuration given (technique and
parameters as the results name them, "reference -" for the Reference) and each kind of light, the
median over that kind's scenes of every pass's milliseconds and of the frame's, as Markdown tables,
one per technique. Scenes of several lights (their passes per light) are left out.

usage: pass_table.py RESULTS.json "TECHNIQUE PARAMETERS" ...
"""
import json
import statistics
import sys


def main(path, configurations):
    with open(path) as f:
        results = json.load(f)
    rows = [r for r in results["rows"] if r.get("measured", True) and r["light"] != "several"]
    print(f"{results['device']}, {rows[0]['width']}×{rows[0]['height']}, {rows[0]['shadowMap']}² map: "
          "median over the scenes of each kind of light, ms")
    by_technique = {}
    for configuration in configurations:
        technique, _, parameters = configuration.partition(" ")
        chosen = [r for r in rows if r["technique"] == technique and r["parameters"] == (parameters or "-")]
        if not chosen:
            sys.exit(f"no rows of {configuration!r} in {path}")
        by_technique.setdefault(technique, []).append((configuration, chosen))
    for technique, tables in by_technique.items():
        passes = list(dict.fromkeys(p for _, chosen in tables for r in chosen for p in r["passMilliseconds"]))
        print()
        print("| configuration | lights | scenes | frame | " + " | ".join(passes) + " |")
        print("|---|---|---|---|" + "---|" * len(passes))
        for configuration, chosen in tables:
            for light in dict.fromkeys(r["light"] for r in chosen):
                of_light = [r for r in chosen if r["light"] == light]
                cells = []
                for p in passes:
                    times = [r["passMilliseconds"][p] for r in of_light if p in r["passMilliseconds"]]
                    cells.append(f"{statistics.median(times):.3f}" if times else "-")
                frame = statistics.median(r["totalMilliseconds"] for r in of_light)
                print(f"| `{parameters_of(configuration)}` | {light} | {len(of_light)} | {frame:.3f} | "
                      + " | ".join(cells) + " |")


def parameters_of(configuration):
    return configuration.partition(" ")[2] or configuration

if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
