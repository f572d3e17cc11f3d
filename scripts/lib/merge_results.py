#!/usr/bin/env python3
"""Merges two tyndall-bench results.json files: every row of NEW, plus the rows of OLD's scenes
that NEW did not measure. scripts/measure.sh tradeoffs uses it (KEEP_FROM) to measure again only
the scenes of one kind of light: a profile row is chosen over one kind's scenes, so each kind's
choice still comes from one run. Both runs must share the device, frame counts and schedule.

usage: merge_results.py NEW.json OLD.json OUT.json
"""
import json
import sys

SHARED = ("device", "frames", "warmUpFrames", "schedule", "orbitFrames", "orbitDegreesPerFrame", "chooseAt")


def main(new_path, old_path, out_path):
    with open(new_path) as f:
        new = json.load(f)
    with open(old_path) as f:
        old = json.load(f)
    for key in SHARED:
        if new.get(key) != old.get(key):
            sys.exit(f"{new_path} and {old_path} differ in {key}: {new.get(key)!r} against {old.get(key)!r}")
    measured = {row["scene"] for row in new["rows"]}
    kept = [row for row in old["rows"] if row["scene"] not in measured]
    kept_scenes = list(dict.fromkeys(row["scene"] for row in kept))
    # Kinds of light must not mix runs: a kind's profile row is chosen over its scenes' medians.
    new_lights = {row.get("light") for row in new["rows"]}
    mixed = sorted({row.get("light") for row in kept} & new_lights)
    if mixed:
        sys.exit(f"kept scenes of {old_path} share a kind of light with {new_path}'s ({', '.join(mixed)}): "
                 "measure every scene of that kind again")
    merged = dict(new)
    merged["rows"] = kept + new["rows"]
    merged["command"] = (new["command"] + "\n# the rows of " + ", ".join(kept_scenes) + " from an earlier run ("
                         + old_path + "):\n" + old["command"])
    with open(out_path, "w") as f:
        json.dump(merged, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
