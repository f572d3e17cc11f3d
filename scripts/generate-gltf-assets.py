#!/usr/bin/env python3
"""Writes a glTF asset laid out the way exporters write real ones, and the scenes that use it:
samples/scenes/assets/pergola.gltf + pergola.bin, samples/scenes/gltf-pergola.json (a low sun
through its roof slats) and samples/scenes/gltf-pergola-lamp.json (a spot lamp above the slats).

The pergola (6.4 m x 3.6 m, 2.92 m tall) is modelled in centimetres with z up, as DCC tools export,
under a root node that turns it y-up and scales it to metres. What the file exercises in a loader:

    node hierarchy   root (rotation quaternion + scale 0.01) > groups > instances, four levels deep
    instancing       one post mesh under 8 nodes, one slat mesh under 25, one beam mesh under 2
    transforms       translation/rotation/scale nodes, one beam placed by a column-major "matrix",
                     the west half of the slats mirrored (scale x = -1: the winding must flip)
    indices          u8 (posts), u16 (beams, lattice bars), u32 (leaves), none (planter)
    layouts          an interleaved POSITION/NORMAL buffer view with byteStride 24 (slats), one
                     buffer view shared by two accessors at different byte offsets (beam positions
                     and normals), primitives without NORMAL (flat normals made by the loader)
    modes            TRIANGLES, and TRIANGLE_STRIP for the lattice bars (a 14-index cube strip)
    primitives       a mesh of two primitives (the planter's box and its soil)
    extras           a material, a camera node and an empty node, which a loader must skip

Every occluder is thin (slats 5 cm wide, lattice bars 3 cm, 300 leaf cards of 12 x 8 cm), so
the roof cuts the light into many fine shafts. The leaves come from SplitMix64 with a fixed seed
(scripts/lib/splitmix.py), so the files regenerate byte for byte. Run from anywhere:

    python3 scripts/generate-gltf-assets.py            # rewrites the four files
    python3 scripts/generate-gltf-assets.py --check    # exits 1 if a committed file is out of date
"""
import argparse
import json
import math
import pathlib
import struct
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "lib"))
from splitmix import SplitMix64  # noqa: E402

SEED = 20261202
ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENES = ROOT / "samples" / "scenes"

# glTF enumerations (glTF 2.0 specification, 3.6.2 and 3.7.2).
UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT, FLOAT = 5121, 5123, 5125, 5126
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
TRIANGLE_STRIP = 5  # TRIANGLES (4) is a primitive's default mode

# The cube's corners as bits (x = bit 0, y = bit 1, z = bit 2) and a 14-index strip over them that
# covers its six faces; the generator checks below that every strip triangle faces outwards.
CUBE_STRIP = [3, 2, 7, 6, 4, 2, 0, 3, 1, 7, 5, 4, 1, 0]


def box_faces(lo, hi):
    """24 vertices (4 a face, outward normals) and 36 counter-clockwise indices of a box."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for side in (0, 1):
            n = [0.0, 0.0, 0.0]
            n[axis] = 1.0 if side else -1.0
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(positions)
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = hi[u] if a else lo[u]
                p[v] = hi[v] if b else lo[v]
                positions.append(p)
                normals.append(n)
            # (u, v) is right-handed with the +axis normal: counter-clockwise seen from outside on
            # the + side, reversed on the - side.
            quad = [0, 1, 2, 0, 2, 3] if side else [0, 2, 1, 0, 3, 2]
            indices += [base + q for q in quad]
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    assert_outward(positions, [indices[k:k + 3] for k in range(0, len(indices), 3)], centre)
    return positions, normals, indices


def assert_outward(positions, triangles, centre):
    for a, b, c in triangles:
        pa, pb, pc = positions[a], positions[b], positions[c]
        e1 = [pb[k] - pa[k] for k in range(3)]
        e2 = [pc[k] - pa[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        assert sum(n[k] * (pa[k] - centre[k]) for k in range(3)) > 0, "a box triangle faces inwards"


def strip_triangles(strip):
    """glTF's TRIANGLE_STRIP rule: triangle i is (i, i+1, i+2), every odd one wound back."""
    out = []
    for i in range(len(strip) - 2):
        a, b, c = strip[i], strip[i + 1], strip[i + 2]
        out.append((a, c, b) if i % 2 else (a, b, c))
    return out


def cube_strip_vertices(lo, hi):
    corners = [[hi[k] if (bit >> k) & 1 else lo[k] for k in range(3)] for bit in range(8)]
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    assert_outward(corners, [t for t in strip_triangles(CUBE_STRIP) if len(set(t)) == 3], centre)
    return corners


class Buffer:
    """The binary buffer with its views and accessors, each view 4-byte aligned."""

    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def view(self, payload, target=None, stride=None):
        while len(self.data) % 4:
            self.data.append(0)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if stride:
            v["byteStride"] = stride
        if target:
            v["target"] = target
        self.data += payload
        self.views.append(v)
        return len(self.views) - 1

    def accessor(self, view, component, count, kind, offset=0, bounds=None):
        a = {"bufferView": view, "componentType": component, "count": count, "type": kind}
        if offset:
            a["byteOffset"] = offset
        if bounds:
            a["min"], a["max"] = bounds
        self.accessors.append(a)
        return len(self.accessors) - 1

    def vec3(self, points, view=None, offset=0):
        points = [f32(p) for p in points]
        if view is None:
            view = self.view(b"".join(struct.pack("<3f", *p) for p in points), ARRAY_BUFFER)
        lo = [min(p[k] for p in points) for k in range(3)]
        hi = [max(p[k] for p in points) for k in range(3)]
        return self.accessor(view, FLOAT, len(points), "VEC3", offset, (lo, hi))

    def indices(self, values, component):
        fmt = {UNSIGNED_BYTE: "B", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I"}[component]
        view = self.view(struct.pack("<%d%s" % (len(values), fmt), *values), ELEMENT_ARRAY_BUFFER)
        return self.accessor(view, component, len(values), "SCALAR")


def f32(values):
    """Rounded as the binary buffer stores them, so min/max match the data."""
    return [struct.unpack("<f", struct.pack("<f", v))[0] for v in values]


def build():
    buf = Buffer()
    meshes = []

    def mesh(name, primitives):
        meshes.append({"name": name, "primitives": primitives})
        return len(meshes) - 1

    # Post: 16 x 16 x 260 cm, u8 indices (24 vertices).
    p, n, i = box_faces([-8, -8, 0], [8, 8, 260])
    post = mesh("post", [{"attributes": {"POSITION": buf.vec3(p), "NORMAL": buf.vec3(n)},
                          "indices": buf.indices(i, UNSIGNED_BYTE), "material": 0}])

    # Beam: 640 x 10 x 20 cm along x; positions and normals in one view at two byte offsets.
    p, n, i = box_faces([-320, -5, 0], [320, 5, 20])
    shared = buf.view(b"".join(struct.pack("<3f", *v) for v in p + n), ARRAY_BUFFER)
    beam = mesh("beam", [{"attributes": {"POSITION": buf.vec3(p, shared), "NORMAL": buf.vec3(n, shared, 12 * len(p))},
                          "indices": buf.indices(i, UNSIGNED_SHORT), "material": 0}])

    # Slat: 5 x 360 x 12 cm along y, interleaved POSITION/NORMAL (byteStride 24).
    p, n, i = box_faces([-2.5, -180, 0], [2.5, 180, 12])
    inter = buf.view(b"".join(struct.pack("<6f", *(a + b)) for a, b in zip(p, n)), ARRAY_BUFFER, stride=24)
    slat = mesh("slat", [{"attributes": {"POSITION": buf.vec3(p, inter), "NORMAL": buf.vec3(n, inter, 12)},
                          "indices": buf.indices(i, UNSIGNED_SHORT), "material": 0}])

    # Lattice bar: 3 x 3 x 200 cm, one TRIANGLE_STRIP without normals (flat ones from the loader).
    corners = cube_strip_vertices([-1.5, -1.5, -100], [1.5, 1.5, 100])
    bar = mesh("lattice-bar", [{"attributes": {"POSITION": buf.vec3(corners)},
                                "indices": buf.indices(CUBE_STRIP, UNSIGNED_SHORT), "mode": TRIANGLE_STRIP}])

    # Planter: a box of two primitives, its walls (non-indexed, no normals) and the soil on top.
    p, _, i = box_faces([-40, -40, 0], [40, 40, 45])
    walls = [p[k] for k in i]
    p, n, i = box_faces([-36, -36, 45], [36, 36, 47])
    planter = mesh("planter", [{"attributes": {"POSITION": buf.vec3(walls)}},
                               {"attributes": {"POSITION": buf.vec3(p), "NORMAL": buf.vec3(n)},
                                "indices": buf.indices(i, UNSIGNED_SHORT)}])

    # Leaves: 300 cards of 12 x 8 cm over the slats, both sides (real exports duplicate a card's
    # faces for two-sided foliage), u32 indices.
    rng = SplitMix64(SEED)
    lp, ln, li = [], [], []
    for _ in range(300):
        cx, cy, cz = rng.uniform(-300, 300), rng.uniform(-170, 170), rng.uniform(293, 300)
        yaw, tilt = rng.uniform(0, 2 * math.pi), rng.uniform(-0.5, 0.5)
        ax, ay = math.cos(yaw), math.sin(yaw)
        bx, by, bz = -ay * math.cos(tilt), ax * math.cos(tilt), math.sin(tilt)
        nx, ny, nz = ay * bz, -ax * bz, ax * by - ay * bx
        quad = [[cx + su * 6 * ax + sv * 4 * bx, cy + su * 6 * ay + sv * 4 * by, cz + sv * 4 * bz]
                for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        for sign, order in ((1, (0, 1, 2, 0, 2, 3)), (-1, (0, 2, 1, 0, 3, 2))):
            base = len(lp)
            lp += quad
            ln += [[sign * nx, sign * ny, sign * nz]] * 4
            li += [base + o for o in order]
    leaves = mesh("leaves", [{"attributes": {"POSITION": buf.vec3(lp), "NORMAL": buf.vec3(ln)},
                              "indices": buf.indices(li, UNSIGNED_INT), "material": 1}])

    nodes = []

    def node(**fields):
        nodes.append(fields)
        return len(nodes) - 1

    posts = [node(name="post-%d" % k, mesh=post, translation=[x, y, 0.0])
             for k, (x, y) in enumerate((x, y) for y in (-140.0, 140.0) for x in (-290.0, -97.0, 97.0, 290.0))]
    beams = [node(name="beam-south", mesh=beam, translation=[0.0, -140.0, 260.0]),
             node(name="beam-north", mesh=beam,
                  matrix=[1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0.0, 140.0, 260.0, 1.0])]
    middle = node(name="slat-0", mesh=slat, translation=[0.0, 0.0, 280.0])
    east = [node(name="slat-e%d" % k, mesh=slat, translation=[25.0 * k, 0.0, 280.0]) for k in range(1, 13)]
    west = [node(name="slat-w%d" % k, mesh=slat, translation=[25.0 * k, 0.0, 280.0]) for k in range(1, 13)]
    # The screen between the two western posts of the south side: bars crossed at +-45 degrees.
    s = math.sqrt(0.5)
    bars = [node(name="bar-%d" % k, mesh=bar, translation=[-250.0 + 30.0 * k, -150.0, 130.0],
                 rotation=[0.0, math.sin(math.radians(22.5)) * (1 if k % 2 else -1), 0.0,
                           math.cos(math.radians(22.5))])
            for k in range(6)]
    roof = node(name="roof", children=[middle,
                                       node(name="slats-east", children=east),
                                       node(name="slats-west", scale=[-1.0, 1.0, 1.0], children=west),
                                       node(name="leaves", mesh=leaves)])
    frame = node(name="frame", children=posts + beams)
    screen = node(name="screen", children=bars)
    pot = node(name="planter", mesh=planter, translation=[150.0, 60.0, 0.0], rotation=[0.0, 0.0, 0.2588190, 0.9659258])
    cam = node(name="camera", camera=0, translation=[900.0, -700.0, 170.0])
    empty = node(name="locator", translation=[0.0, 0.0, 400.0])
    root = node(name="pergola", rotation=[-s, 0.0, 0.0, s], scale=[0.01, 0.01, 0.01],
                children=[frame, roof, screen, pot, cam, empty])

    gltf = {
        "asset": {"version": "2.0", "generator": "Tyndall scripts/generate-gltf-assets.py"},
        "scene": 0,
        "scenes": [{"name": "pergola", "nodes": [root]}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [{"name": "timber", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.3, 0.18, 1.0]}},
                      {"name": "leaf", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.1, 1.0]}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1, "zfar": 100.0}}],
        "accessors": buf.accessors,
        "bufferViews": buf.views,
        "buffers": [{"uri": "pergola.bin", "byteLength": len(buf.data)}],
    }
    return gltf, bytes(buf.data)


MEDIUM = {"scattering": [0.03, 0.03, 0.03], "absorption": [0.003, 0.003, 0.003],
          "phase": {"type": "henyey-greenstein", "g": 0.5}}
PERGOLA = {"type": "gltf", "path": "assets/pergola.gltf", "translation": [0, 0, 0], "rotationDegrees": [0, 15, 0],
           "scale": 1.0, "albedo": [0.45, 0.3, 0.18]}
GROUND = {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "albedo": [0.5, 0.5, 0.5]}


def scenes():
    sun = {
        "description": "A low sun through a pergola loaded from glTF (assets/pergola.gltf, written by "
                       "scripts/generate-gltf-assets.py): 25 roof slats, a lattice screen and 300 leaf cards "
                       "cut fine shafts; the camera looks towards the sun.",
        "camera": {"position": [5.0, 1.2, 6.0], "target": [0, 2.0, 0], "up": [0, 1, 0],
                   "fovYDegrees": 60, "near": 0.1, "far": 80},
        "light": {"type": "directional", "direction": [0.45, -0.42, 0.79], "color": [1.0, 0.92, 0.8],
                  "intensity": 3},
        "medium": MEDIUM,
        "objects": [GROUND, PERGOLA],
        "shadowMap": {"size": 2048},
    }
    lamp = {
        "description": "A 35-degree spot lamp above the glTF pergola's roof (assets/pergola.gltf): the slats and "
                       "leaf cards cut its cone into fine shafts; the camera is outside the cone.",
        "camera": {"position": [5.5, 1.7, 6.5], "target": [0, 1.4, 0], "up": [0, 1, 0],
                   "fovYDegrees": 60, "near": 0.1, "far": 80},
        "light": {"type": "spot", "position": [0.3, 4.2, 0.2], "direction": [0, -1, 0], "color": [1.0, 0.9, 0.75],
                  "intensity": 60, "innerConeDegrees": 30, "outerConeDegrees": 35},
        "medium": {"scattering": [0.04, 0.04, 0.04], "absorption": [0.004, 0.004, 0.004],
                   "phase": {"type": "henyey-greenstein", "g": 0.3}},
        "objects": [GROUND, PERGOLA],
        "shadowMap": {"size": 2048},
    }
    return {"gltf-pergola.json": sun, "gltf-pergola-lamp.json": lamp}


def outputs():
    gltf, data = build()
    files = {SCENES / "assets" / "pergola.gltf": (json.dumps(gltf, indent=1) + "\n").encode(),
             SCENES / "assets" / "pergola.bin": data}
    for name, scene in scenes().items():
        files[SCENES / name] = (json.dumps(scene, indent=2) + "\n").encode()
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a committed file is out of date")
    args = parser.parse_args()
    stale = []
    for path, content in outputs().items():
        if args.check:
            if not path.exists() or path.read_bytes() != content:
                stale.append(path)
        else:
            path.write_bytes(content)
    if stale:
        print("out of date (run scripts/generate-gltf-assets.py): " + ", ".join(str(p.relative_to(ROOT)) for p in stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
