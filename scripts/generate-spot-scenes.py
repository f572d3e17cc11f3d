#!/usr/bin/env python3
"""Writes the local-light scenes of thin, many-bladed occluders:
samples/scenes/spot-{fan,fan-up,fan-narrow,fan-close,grille,lattice,foliage,street}.json and
samples/scenes/point-{fan,cage,street}.json.

Each spot scene has a 35-degree spot light whose cone is cut into fine shafts by thin boxes, seen
from a different place relative to the cone:

    spot-fan      a ceiling fan's eight thin, pitched blades under the lamp; camera outside the cone
    spot-fan-up   an uplight under a three-bladed fan, lighting the ceiling; camera below and behind
                  the cone, the lamp in view
    spot-fan-narrow  a 15-degree lamp just above five blades, seen from 18 m
    spot-fan-close   a 60-degree lamp tilted over twelve blades; camera inside the cone close under
                  the fan, looking up into the lamp
    spot-grille   a grille of thin parallel bars; camera inside the cone, under the grille
    spot-lattice  a lattice of crossed thin bars turned 20 degrees; camera on the cone's outer edge
    spot-foliage  400 small leaf cards at random rotations (fixed seed); camera outside the cone
    spot-street   a street lamp tilted over a railing of thin bars, seen from 60 m: the lit cone is a
                  few dozen pixels and its footprint on the ground a pixel or two high

The point scenes (six shadow maps each) cut a bare bulb's light into shafts in every direction:

    point-fan     the ceiling fan with the bulb just above its blades: they cut shafts downwards
    point-cage    a lantern: the bulb in a square cage of 24 thin bars between solid top and bottom
                  plates, so that the light leaves sideways in blades across the floor
    point-street  spot-street's railing with a bare bulb under a small housing, seen from 60 m

The layout is deterministic: the leaves come from SplitMix64 with a fixed seed (scripts/lib/splitmix.py, so
the output does not depend on the Python version's random module). Run from anywhere:

    python3 scripts/generate-spot-scenes.py            # rewrites the eleven scene files
    python3 scripts/generate-spot-scenes.py --check    # exits 1 if a committed file is out of date
"""
import argparse
import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "lib"))
from splitmix import SplitMix64  # noqa: E402

SEED = 20261128
MEDIUM = ('{"scattering": [0.04, 0.04, 0.04], "absorption": [0.004, 0.004, 0.004],\n'
          '             "phase": {"type": "henyey-greenstein", "g": 0.3}}')
FLOOR = {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "albedo": [0.5, 0.5, 0.5]}
DARK = [0.25, 0.25, 0.25]


def r(values, digits=4):
    return [round(v, digits) + 0.0 for v in values]


def box(center, half, rotation=(0, 0, 0), albedo=DARK):
    return {"type": "box", "center": r(center), "halfExtents": r(half), "rotationDegrees": r(rotation, 2),
            "albedo": albedo}


def fan_blades(count, radius, half, pitch, first_yaw, height):
    """`count` blades round the hub, blade k along yaw first_yaw + k·360/count. Blades lie along x
    before rotation: pitched about their long axis (x), then turned about y (R = Rz·Ry·Rx), so a
    blade at yaw θ points along (cos θ, 0, −sin θ)."""
    blades = []
    for k in range(count):
        yaw = first_yaw + 360.0 * k / count
        c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
        blades.append(box([radius * c, height, -radius * s], half, [pitch, yaw, 0]))
    return blades


def fan():
    objects = [box([0, 6.15, 0], [0.16, 0.06, 0.16])]  # the hub
    objects += fan_blades(8, 1.0, [0.85, 0.012, 0.07], 14, 22.5, 6.1)
    objects += [box([1.5, 0.45, 0.6], [0.45, 0.45, 0.45], [0, 30, 0], [0.7, 0.35, 0.2]),
                {"type": "sphere", "center": [-1.2, 0.6, -0.8], "radius": 0.6, "albedo": [0.2, 0.4, 0.7]}]
    return {
        "description": "A 35-degree spot lamp hanging under a ceiling fan: eight thin, pitched blades cut fine "
                       "shafts; the camera is outside the cone.",
        "camera": '{"position": [6.5, 2.2, 8], "target": [0, 3, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "spot", "position": [0, 7, 0], "direction": [0, -1, 0], "color": [1.0, 0.9, 0.75],\n'
                 '            "intensity": 60, "innerConeDegrees": 30, "outerConeDegrees": 35}',
        "objects": objects,
    }


def grille():
    # Bars along x, 0.06 thick, every 0.3 across z, 2.7 below the lamp.
    objects = [box([0, 5.3, -3.0 + 0.3 * i], [3.4, 0.03, 0.03]) for i in range(21)]
    objects += [box([-1.6, 0.5, -1.2], [0.5, 0.5, 0.5], [0, 20, 0], [0.7, 0.35, 0.2]),
                {"type": "sphere", "center": [1.4, 0.7, -2.0], "radius": 0.7, "albedo": [0.2, 0.4, 0.7]}]
    return {
        "description": "A 35-degree spot lamp above a grille of 21 thin bars; the camera stands inside the cone, "
                       "under the grille, looking across the shafts.",
        "camera": '{"position": [0.8, 1.7, 0.4], "target": [-4.0, 4.0, -0.3], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "spot", "position": [0, 8, 0], "direction": [0, -1, 0], "color": [1.0, 0.95, 0.85],\n'
                 '            "intensity": 80, "innerConeDegrees": 30, "outerConeDegrees": 35}',
        "objects": objects,
    }


def lattice():
    # Two layers of bars, 0.05 thick, every 0.35, crossing; the whole lattice turned 20° about y.
    turn = math.radians(20.0)
    c, s = math.cos(turn), math.sin(turn)
    objects = []
    for i in range(13):
        o = -2.1 + 0.35 * i
        # along x at z = o, and along z at x = o, before the turn
        objects.append(box([o * s, 5.2, o * c], [2.4, 0.025, 0.025], [0, 20, 0]))
        objects.append(box([o * c, 5.25, -o * s], [0.025, 0.025, 2.4], [0, 20, 0]))
    objects += [box([0.5, 0.6, -1.0], [0.6, 0.6, 0.6], [0, 40, 0], [0.7, 0.35, 0.2])]
    # Camera 5.5 below the lamp and 5.5 · tan 35° = 3.851 off its axis: on the outer edge of the cone.
    return {
        "description": "A 35-degree spot lamp above a lattice of crossed thin bars; the camera stands on the "
                       "cone's outer edge, looking up across it.",
        "camera": '{"position": [3.851, 1.5, 0.0], "target": [-2.0, 3.5, -1.0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "spot", "position": [0, 7, 0], "direction": [0, -1, 0], "color": [1.0, 0.9, 0.75],\n'
                 '            "intensity": 60, "innerConeDegrees": 28, "outerConeDegrees": 35}',
        "objects": objects,
    }


def foliage():
    rng = SplitMix64(SEED)
    objects = []
    for _ in range(400):
        # Uniform over a disc of radius 1.8 and a layer 1.5 deep, 1.2 to 2.7 below the lamp.
        radius = 1.8 * math.sqrt(rng.uniform(0.0, 1.0))
        angle = rng.uniform(0.0, 2.0 * math.pi)
        y = rng.uniform(4.8, 6.3)
        rotation = [rng.uniform(-60.0, 60.0), rng.uniform(0.0, 180.0), rng.uniform(-60.0, 60.0)]
        half = [rng.uniform(0.08, 0.14), 0.004, rng.uniform(0.04, 0.07)]
        objects.append(box([radius * math.cos(angle), y, radius * math.sin(angle)], half, rotation, [0.2, 0.35, 0.15]))
    objects += [box([1.0, 0.5, 0.3], [0.5, 0.5, 0.5], [0, 35, 0], [0.7, 0.35, 0.2])]
    return {
        "description": f"A 35-degree spot lamp shining down through 400 small leaf cards at random rotations "
                       f"(scripts/generate-spot-scenes.py, seed {SEED}); the camera is outside the cone.",
        "camera": '{"position": [-6, 2.0, 7.5], "target": [0, 3.5, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "spot", "position": [0, 7.5, 0], "direction": [0, -1, 0], "color": [1.0, 0.95, 0.8],\n'
                 '            "intensity": 70, "innerConeDegrees": 30, "outerConeDegrees": 35}',
        "objects": objects,
    }


def street():
    # 41 bars 15 cm apart, 2 m tall, and a top rail, half a metre in front of the lamp's post.
    objects = [box([0.15 * i, 1.0, 0.5], [0.02, 1.0, 0.02]) for i in range(-20, 21)]
    objects += [box([0, 2.0, 0.5], [3.2, 0.03, 0.03]), box([0, 5.2, 0], [0.3, 0.1, 0.3], albedo=[0.1, 0.1, 0.1])]
    return {
        "description": "A 35-degree street lamp tilted over a railing of thin bars, seen from 60 m along the "
                       "street: the lit cone covers a few dozen pixels and its footprint on the ground a pixel "
                       "or two of height.",
        "camera": '{"position": [25, 1.7, 55], "target": [0, 2.5, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 50, "near": 0.1, "far": 400}',
        "light": '{"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0.35], "color": [1.0, 0.85, 0.6],\n'
                 '            "intensity": 120, "innerConeDegrees": 30, "outerConeDegrees": 35}',
        "objects": objects,
    }


def point_fan():
    scene = fan()
    return {
        "description": "A bare bulb just above a ceiling fan's eight thin, pitched blades: they cut its light "
                       "into shafts downwards, while it shines freely upwards; the camera is outside, looking up "
                       "at the fan.",
        "camera": '{"position": [6.5, 2.2, 8], "target": [0, 4.5, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "point", "position": [0, 6.5, 0], "color": [1.0, 0.9, 0.75], "intensity": 40}',
        "objects": scene["objects"],
    }


def cage():
    # A square cage 1.2 wide: 7 bars per side (0.04 thick, 0.2 apart, the corners shared: 24 bars),
    # 1.6 tall, between solid plates, around the bulb at its centre.
    places = []
    for i in range(7):
        o = round(-0.6 + 0.2 * i, 4)
        for place in ((o, -0.6), (o, 0.6), (-0.6, o), (0.6, o)):
            if place not in places:
                places.append(place)
    objects = [box([x, 2.5, z], [0.02, 0.8, 0.02]) for x, z in places]
    objects += [box([0, 3.33, 0], [0.66, 0.03, 0.66]), box([0, 1.67, 0], [0.66, 0.03, 0.66]),
                box([0, 0.83, 0], [0.05, 0.83, 0.05]),  # the stand
                box([2.6, 0.5, -1.5], [0.5, 0.5, 0.5], [0, 30, 0], [0.7, 0.35, 0.2]),
                {"type": "sphere", "center": [-2.2, 0.6, 1.8], "radius": 0.6, "albedo": [0.2, 0.4, 0.7]}]
    return {
        "description": "A lantern: a bare bulb in a square cage of thin bars between solid top and bottom "
                       "plates, on a stand; the light leaves sideways in blades across the floor and the "
                       "medium. The camera is outside, a few metres off.",
        "camera": '{"position": [7, 1.6, 6], "target": [0, 2.0, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 60, "near": 0.1, "far": 80}',
        "light": '{"type": "point", "position": [0, 2.5, 0], "color": [1.0, 0.85, 0.6], "intensity": 30}',
        "objects": objects,
    }


def point_street():
    scene = street()
    return {
        "description": "spot-street's railing and post with a bare bulb under a small housing, seen from 60 m "
                       "along the street: the lit volume is a few dozen pixels wide.",
        "camera": '{"position": [25, 1.7, 55], "target": [0, 2.5, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 50, "near": 0.1, "far": 400}',
        "light": '{"type": "point", "position": [0, 5, 0], "color": [1.0, 0.85, 0.6], "intensity": 120}',
        "objects": scene["objects"],
    }


def fan_up():
    objects = [{"type": "plane", "point": [0, 8, 0], "normal": [0, -1, 0], "albedo": [0.6, 0.6, 0.6]},
               box([0, 6.15, 0], [0.16, 0.06, 0.16])] + fan_blades(3, 1.1, [0.95, 0.015, 0.16], 10, 10, 6.1)
    return {
        "description": "An uplight under a ceiling fan's three broad blades: the 50-degree cone shines up through "
                       "them onto the ceiling; the camera stands below the lamp, behind its cone, looking up past it.",
        "camera": '{"position": [1.0, 1.6, 1.5], "target": [0, 6, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 70, "near": 0.1, "far": 80}',
        "light": '{"type": "spot", "position": [0.2, 4.5, 0.1], "direction": [0, 1, 0], "color": [1.0, 0.9, 0.75],\n'
                 '            "intensity": 60, "innerConeDegrees": 40, "outerConeDegrees": 50}',
        "objects": objects,
    }


def fan_narrow():
    objects = [box([0, 6.15, 0], [0.12, 0.05, 0.12])] + fan_blades(5, 0.7, [0.6, 0.01, 0.05], 20, 0, 6.1)
    return {
        "description": "A narrow 15-degree spot lamp just above a five-bladed fan, seen from 18 m: the blades cut "
                       "its thin cone into a few shafts next to the lamp.",
        "camera": '{"position": [12, 2, 14], "target": [0, 3, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 50, "near": 0.1, "far": 100}',
        "light": '{"type": "spot", "position": [0, 6.8, 0], "direction": [0, -1, 0], "color": [1.0, 0.9, 0.75],\n'
                 '            "intensity": 200, "innerConeDegrees": 12, "outerConeDegrees": 15}',
        "objects": objects,
    }


def fan_close():
    objects = [box([0, 6.15, 0], [0.16, 0.06, 0.16])] + fan_blades(12, 1.0, [0.85, 0.01, 0.04], 25, 5, 6.1)
    return {
        "description": "A wide 60-degree spot lamp tilted over a twelve-bladed fan; the camera stands inside the "
                       "cone close under the fan, looking up into the lamp between the blades.",
        "camera": '{"position": [2.5, 4.0, 3.0], "target": [0, 5.5, 0], "up": [0, 1, 0],\n'
                  '             "fovYDegrees": 75, "near": 0.05, "far": 60}',
        "light": '{"type": "spot", "position": [0, 6.6, 0], "direction": [0.2, -1, 0.1], "color": [1.0, 0.9, 0.75],\n'
                 '            "intensity": 60, "innerConeDegrees": 50, "outerConeDegrees": 60}',
        "objects": objects,
    }


SCENES = {"spot-fan": fan, "spot-fan-up": fan_up, "spot-fan-narrow": fan_narrow, "spot-fan-close": fan_close,
          "spot-grille": grille, "spot-lattice": lattice, "spot-foliage": foliage, "spot-street": street, "point-fan": point_fan, "point-cage": cage, "point-street": point_street}


def scene_text(scene):
    objects = [FLOOR] + scene["objects"]
    lines = ",\n".join("    " + json.dumps(o, separators=(", ", ": ")) for o in objects)
    return f"""{{
  "description": {json.dumps(scene["description"])},
  "camera": {scene["camera"]},
  "light": {scene["light"]},
  "medium": {MEDIUM},
  "objects": [
{lines}
  ],
  "shadowMap": {{"size": 2048}}
}}
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed files instead of writing them")
    args = parser.parse_args()
    folder = pathlib.Path(__file__).resolve().parent.parent / "samples" / "scenes"
    status = 0
    for name, make in SCENES.items():
        path = folder / f"{name}.json"
        text = scene_text(make())
        json.loads(text)
        if args.check:
            if not path.exists() or path.read_text() != text:
                print(f"{path} is out of date: run scripts/generate-spot-scenes.py", file=sys.stderr)
                status = 1
        else:
            path.write_text(text)
            print(f"wrote {path}")
    return status


if __name__ == "__main__":
    sys.exit(main())
