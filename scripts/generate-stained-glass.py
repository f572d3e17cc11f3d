#!/usr/bin/env python3
"""Writes samples/scenes/assets/stained-glass.png: a rose window for a light's colour texture.

Concentric rings of coloured panes (deep saturated glass, as a stained-glass window filters light)
separated by dark lead came, around a pale centre. The texture is laid over a light's shadow map
square (tyndall::FrameDesc::lightColor), so its centre is the spot light's axis. Deterministic and
dependency-free (PNG written with zlib). Run from anywhere:

    python3 scripts/generate-stained-glass.py            # rewrites the PNG
    python3 scripts/generate-stained-glass.py --check    # exits 1 if the committed file is out of date
"""
import argparse
import math
import pathlib
import struct
import sys
import zlib

SIZE = 256
# sRGB colours of the glass, ring by ring from the centre out; each ring has its own pane count.
RINGS = [
    (0.00, 0.14, 1, [(250, 240, 200)]),
    (0.14, 0.30, 8, [(200, 40, 40), (40, 90, 200)]),
    (0.30, 0.48, 12, [(230, 170, 30), (40, 150, 70), (150, 50, 170)]),
    (0.48, 0.70, 16, [(40, 90, 200), (200, 40, 40), (230, 170, 30), (40, 150, 70)]),
]
LEAD = (25, 22, 20)         # the came between panes
LEAD_WIDTH = 0.012          # in units of the texture's half-width
OUTSIDE = (0, 0, 0)         # beyond the window the glass is opaque (no light passes)


def pixel(x, y):
    u = (x + 0.5) / SIZE * 2.0 - 1.0
    v = (y + 0.5) / SIZE * 2.0 - 1.0
    r = math.hypot(u, v)
    angle = (math.atan2(v, u) + math.pi) / (2.0 * math.pi)  # [0, 1)
    for inner, outer, panes, colours in RINGS:
        if r < outer:
            if r - inner < LEAD_WIDTH or outer - r < LEAD_WIDTH:
                return LEAD if inner > 0.0 or outer - r < LEAD_WIDTH else colours[0]
            if panes > 1:
                position = angle * panes
                if min(position % 1.0, 1.0 - position % 1.0) * 2.0 * math.pi * r / panes < LEAD_WIDTH:
                    return LEAD
                return colours[int(position) % len(colours)]
            return colours[0]
    return OUTSIDE


def png_bytes():
    rows = bytearray()
    for y in range(SIZE):
        rows.append(0)  # filter: none
        for x in range(SIZE):
            rows.extend(pixel(x, y))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)  # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(rows), 9)) +
            chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if the committed file differs")
    args = parser.parse_args()
    path = pathlib.Path(__file__).resolve().parent.parent / "samples" / "scenes" / "assets" / "stained-glass.png"
    data = png_bytes()
    if args.check:
        if not path.exists() or path.read_bytes() != data:
            print(f"{path} is out of date: run scripts/generate-stained-glass.py", file=sys.stderr)
            return 1
        return 0
    path.write_bytes(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
