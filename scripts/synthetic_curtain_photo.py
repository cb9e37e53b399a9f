#!/usr/bin/env python3
"""A photo-like test image of a curtain hanging from two supports, for `weft folds --overlay`
(gallery/folds_overlay.png). Synthetic, not a photo: a wall, two pegs, and a cloth shaded by
swag folds along cosine arcs y = a cos(pi x / l) whose amplitudes grow by `--ratio` from one
fold to the next (seed 001's wrinkle-line shape), with a weave texture and noise. Standard
library only; deterministic.

  scripts/synthetic_curtain_photo.py OUT.png [--ratio 1.31]

Geometry (pixels): supports at (100, 80) and (500, 80), l = 130 cm across 400 px, the cloth
h = 140 cm tall at the same scale: pass `--supports 100,80,500,80` to weft folds.
"""
import argparse
import math
import struct
import zlib

W, H = 600, 620
LEFT, RIGHT, TOP = 100.0, 500.0, 80.0
SPAN_M, HEIGHT_M = 1.30, 1.40
SCALE = (RIGHT - LEFT) / SPAN_M  # px per metre


def noise(x, y):
    """Deterministic hash noise in [-1, 1]."""
    n = (x * 374761393 + y * 668265263) & 0xFFFFFFFF
    n = ((n ^ (n >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((n ^ (n >> 16)) & 0xFFFF) / 32767.5 - 1.0


def pixel(px, py, ratio):
    wall = 0.80 - 0.10 * py / H
    base = (wall * 236, wall * 228, wall * 212)
    for sx in (LEFT, RIGHT):  # pegs
        if (px - sx) ** 2 + (py - TOP) ** 2 <= 36:
            return (60, 45, 35)
    x_m = (px - 0.5 * (LEFT + RIGHT)) / SCALE
    depth = (py - TOP) / SCALE
    if abs(x_m) > 0.5 * SPAN_M or depth < 0:
        return base
    c = math.cos(math.pi * x_m / SPAN_M)
    a0 = 1.01 * HEIGHT_M
    n = 7
    top = a0 / ratio ** n * c  # the upper boundary sags between the supports
    if depth < top or depth > HEIGHT_M * (0.99 + 0.01 * c):
        return base
    rho = depth / max(c, 1e-3)  # amplitude of the cosine arc through this point
    phase = math.log(rho / a0) / math.log(ratio)  # fold i at phase -i
    fold = math.cos(math.pi * phase) * min(1.0, 3.0 * c)
    weave = 0.025 * math.sin(px * 1.9) * math.sin(py * 2.1)
    shade = 0.60 + 0.28 * fold + weave + 0.03 * noise(px, py)
    shade = min(max(shade, 0.0), 1.0)
    return (shade * 120 + 30, shade * 150 + 35, shade * 185 + 45)


def write_png(path, rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(
            ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--ratio", type=float, default=1.31)
    args = parser.parse_args()
    rows = []
    for py in range(H):
        row = []
        for px in range(W):
            row.extend(min(255, max(0, int(round(v)))) for v in pixel(px, py, args.ratio))
        rows.append(row)
    write_png(args.out, rows)


if __name__ == "__main__":
    main()
