#!/usr/bin/env python3
"""A render perturbed the way a photo of the same cloth would differ from it, to stand in for a
photo in `weft compare` (gallery/compare_report/). Not a photo: the render is scaled by
--scale about its centre and shifted by --shift pixels onto a --size grid (bilinear), blurred
(3x3 binomial, --blur passes), given a colour cast (--cast r,g,b factors) and uniform noise of
±--noise grey levels from a fixed hash (deterministic). Standard library only; reads 8-bit
RGB/RGBA non-interlaced PNGs (what weft writes).

  scripts/perturbed_render_photo.py RENDER.png OUT.png [--size 480x360] [--scale 0.8]
      [--shift 22,-8] [--blur 2] [--cast 1.08,1,0.9] [--noise 6]
"""
import argparse
import struct
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                raise SystemExit(f"{path}: only 8-bit RGB/RGBA non-interlaced PNGs")
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def write_png(path, w, h, rows):
    raw = b"".join(b"\x00" + bytes(v for p in row for v in p) for row in rows)
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def noise(x, y):
    """Deterministic hash noise in [-1, 1]."""
    n = (x * 374761393 + y * 668265263) & 0xFFFFFFFF
    n = ((n ^ (n >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((n ^ (n >> 16)) & 0xFFFF) / 32767.5 - 1.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("render")
    ap.add_argument("out")
    ap.add_argument("--size", default="480x360")
    ap.add_argument("--scale", type=float, default=0.8)
    ap.add_argument("--shift", default="22,-8")
    ap.add_argument("--blur", type=int, default=2)
    ap.add_argument("--cast", default="1.08,1,0.9")
    ap.add_argument("--noise", type=float, default=6.0)
    a = ap.parse_args()
    sw, sh, src = read_png(a.render)
    w, h = (int(v) for v in a.size.split("x"))
    dx, dy = (float(v) for v in a.shift.split(","))
    cast = [float(v) for v in a.cast.split(",")]

    def sample(rx, ry):  # bilinear, edges clamped
        x0, y0 = int(rx // 1), int(ry // 1)
        fx, fy = rx - x0, ry - y0
        def px(x, y):
            return src[min(max(y, 0), sh - 1)][min(max(x, 0), sw - 1)]
        q = [px(x0, y0), px(x0 + 1, y0), px(x0, y0 + 1), px(x0 + 1, y0 + 1)]
        wt = [(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy]
        return [sum(wt[k] * q[k][c] for k in range(4)) for c in range(3)]

    # Photo pixel p shows render point (p - centre_photo - shift) / scale + centre_render.
    img = [[sample((x - (w - 1) / 2 - dx) / a.scale + (sw - 1) / 2,
                   (y - (h - 1) / 2 - dy) / a.scale + (sh - 1) / 2) for x in range(w)] for y in range(h)]
    for _ in range(a.blur):
        out = []
        for y in range(h):
            row = []
            for x in range(w):
                acc = [0.0, 0.0, 0.0]
                for j in (-1, 0, 1):
                    for i in (-1, 0, 1):
                        k = (2 if i == 0 else 1) * (2 if j == 0 else 1) / 16.0
                        p = img[min(max(y + j, 0), h - 1)][min(max(x + i, 0), w - 1)]
                        for c in range(3):
                            acc[c] += k * p[c]
                row.append(acc)
            out.append(row)
        img = out
    rows = [[tuple(min(255, max(0, round(p[c] * cast[c] + a.noise * noise(3 * x + c, y))))
                   for c in range(3)) for x, p in enumerate(row)] for y, row in enumerate(img)]
    write_png(a.out, w, h, rows)


if __name__ == "__main__":
    main()
