#!/usr/bin/env python3
"""Small copies of the phi-SfT R1 frame 0 for tests/data/photos/phi_sft_R1/, and the check of
the camera's (row, column) order. Standard library only; deterministic.

  scripts/phi_sft_R1_data.py SRC DST [--factor 4] [--points 4000]

SRC is ../shared/photos/phi_sft_R1 (read its README), DST tests/data/photos/phi_sft_R1. Writes
  mask_000.png        the cloth mask box-filtered by FACTOR (1920x1080 -> 480x270), then cut at
                      half coverage (white = cloth)
  mask_000_cloth.png  its largest 4-connected component: the cloth without the two small blobs
                      below it that the dataset's mask also holds
  rgb_000.png         the colour frame box-filtered by FACTOR
  0_R1_quad.obj       the frame-0 template's vertices and quads only (no texture coordinates,
                      normals or material), the quads' corners as vertex indices
  point_cloud_000.npy every k-th point of ground_truth/point_cloud_000.npy (about POINTS of them;
                      float32, N x 3, metres, camera coordinates: x right, y down, z forward)
and prints, for both readings of R1_scene.json's (focal_lengths, optical_centers) pairs, the
IoU between the mask and the pixels the full point cloud projects onto (at the small size),
and the share of points that land inside the mask; and how far the cloud leaves the vertical
plane through the held corners (template vertices 0 and 992; gravity taken as the camera's +y):
the mean signed distance per 10 cm cell, + away from the camera.
"""
import argparse
import json
import math
import shutil
import struct
import sys
import zlib
from pathlib import Path


def read_png(path):
    """8-bit grey, RGB or RGBA, non-interlaced PNG -> (width, height, channels, bytearray)."""
    data = Path(path).read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    channels = {0: 1, 2: 3, 6: 4}.get(ctype)
    if depth != 8 or channels is None or interlace:
        sys.exit(f"{path}: expected an 8-bit grey, RGB or RGBA non-interlaced PNG")
    raw, stride = zlib.decompress(idat), width * channels
    out, prev = bytearray(stride * height), bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out[y * stride:(y + 1) * stride], prev = line, line
    return width, height, channels, out


def write_png(path, width, height, channels, pixels):
    raw = b"".join(b"\x00" + bytes(pixels[y * width * channels:(y + 1) * width * channels])
                   for y in range(height))
    chunk = lambda kind, body: (struct.pack(">I", len(body)) + kind + body +
                                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    ctype = {1: 0, 3: 2}[channels]
    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" +
                           chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, ctype, 0, 0, 0)) +
                           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def box_downscale(width, height, channels, pixels, factor):
    w, h = width // factor, height // factor
    out = bytearray(w * h * channels)
    for y in range(h):
        for x in range(w):
            for ch in range(channels):
                s = sum(pixels[((y * factor + j) * width + x * factor + i) * channels + ch]
                        for j in range(factor) for i in range(factor))
                out[(y * w + x) * channels + ch] = (s + factor * factor // 2) // (factor * factor)
    return w, h, out


def components(mask, w, h):
    """The 4-connected components of the pixels >= 128, largest first, as lists of indices."""
    seen, found = bytearray(w * h), []
    for start in range(w * h):
        if mask[start] < 128 or seen[start]:
            continue
        seen[start], stack, part = 1, [start], []
        while stack:
            i = stack.pop()
            part.append(i)
            x, y = i % w, i // w
            for j, ok in ((i - 1, x > 0), (i + 1, x < w - 1), (i - w, y > 0), (i + w, y < h - 1)):
                if ok and mask[j] >= 128 and not seen[j]:
                    seen[j] = 1
                    stack.append(j)
        found.append(part)
    return sorted(found, key=len, reverse=True)


def npy_points(path):
    """The N x 3 little-endian float32 array of a version-1 .npy file, as a flat list."""
    data = Path(path).read_bytes()
    if data[:6] != b"\x93NUMPY":
        sys.exit(f"{path}: not a .npy file")
    header_len = struct.unpack("<H", data[8:10])[0]
    header = data[10:10 + header_len].decode("latin1")
    if "'<f4'" not in header or "False" not in header:
        sys.exit(f"{path}: expected little-endian float32 in C order, header {header.strip()}")
    body = data[10 + header_len:]
    return list(struct.unpack(f"<{len(body) // 4}f", body)), header


def write_npy(path, flat):
    n = len(flat) // 3
    header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, 3), }" % n
    header += " " * (63 - (10 + len(header)) % 64) + "\n"
    Path(path).write_bytes(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) +
                           header.encode("latin1") + struct.pack(f"<{len(flat)}f", *flat))


def projection_iou(flat, mask, w, h, factor, f, c):
    """IoU of the mask with the pixels hit by x = f0 X/Z + c0, y = f1 Y/Z + c1 (full-size px)."""
    hit, inside = bytearray(w * h), 0
    for i in range(0, len(flat), 3):
        X, Y, Z = flat[i:i + 3]
        x, y = (f[0] * X / Z + c[0]) / factor, (f[1] * Y / Z + c[1]) / factor
        ix, iy = math.floor(x), math.floor(y)
        if 0 <= ix < w and 0 <= iy < h:
            hit[iy * w + ix] = 1
            inside += mask[iy * w + ix] >= 128
    both = sum(1 for i in range(w * h) if hit[i] and mask[i] >= 128)
    union = sum(1 for i in range(w * h) if hit[i] or mask[i] >= 128)
    return both / union, inside / (len(flat) // 3)


def lean_table(flat, obj_path):
    """Rows of mean out-of-plane distances (mm) of the points, 10 cm cells down and along."""
    verts = [[float(v) for v in l.split()[1:4]] for l in obj_path.read_text().splitlines()
             if l.startswith("v ")]
    c0, c1 = [(-v[0], -v[1], v[2]) for v in (verts[0], verts[992])]
    dot = lambda a, b: sum(x * y for x, y in zip(a, b))
    d = [c1[i] - c0[i] for i in range(3)]
    w = [x / math.sqrt(dot(d, d)) for x in d]
    v = [-w[1] * x for x in w]
    v[1] += 1.0
    v = [x / math.sqrt(dot(v, v)) for x in v]
    n = (w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0])
    cells = {}
    for i in range(0, len(flat), 3):
        q = [flat[i + k] - c0[k] for k in range(3)]
        key = (min(5, max(0, int(dot(q, v) / 0.1))), min(5, max(0, int(dot(q, w) / 0.1))))
        cells.setdefault(key, []).append(dot(q, n))
    return [[1e3 * sum(cells[(r, c)]) / len(cells[(r, c)]) if (r, c) in cells else float("nan")
             for c in range(6)] for r in range(6)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("src", type=Path)
    ap.add_argument("dst", type=Path)
    ap.add_argument("--factor", type=int, default=4)
    ap.add_argument("--points", type=int, default=4000)
    a = ap.parse_args()
    a.dst.mkdir(parents=True, exist_ok=True)
    w, h, _, mask = read_png(a.src / "masks/mask_000.png")
    sw, sh, small = box_downscale(w, h, 1, mask, a.factor)
    small = bytearray(255 if v >= 128 else 0 for v in small)
    write_png(a.dst / "mask_000.png", sw, sh, 1, small)
    parts = components(small, sw, sh)
    cloth = bytearray(sw * sh)
    for i in parts[0]:
        cloth[i] = 255
    write_png(a.dst / "mask_000_cloth.png", sw, sh, 1, cloth)
    print(f"mask_000: {len(parts)} components of {[len(p) for p in parts]} px; "
          "mask_000_cloth.png keeps the first")
    w, h, ch, rgb = read_png(a.src / "rgbs/rgb_000.png")
    write_png(a.dst / "rgb_000.png", *box_downscale(w, h, ch, rgb, a.factor)[:2], ch,
              box_downscale(w, h, ch, rgb, a.factor)[2])
    flat, header = npy_points(a.src / "ground_truth/point_cloud_000.npy")
    n = len(flat) // 3
    step = max(1, n // a.points)
    write_npy(a.dst / "point_cloud_000.npy",
              [v for i in range(0, n, step) for v in flat[3 * i:3 * i + 3]])
    shutil.copyfile(a.src / "LICENSE", a.dst / "LICENSE")
    lines = (a.src / "0_R1_quad.obj").read_text().splitlines()
    kept = [l for l in lines if l.startswith("v ")]
    kept += ["f " + " ".join(c.split("/")[0] for c in l.split()[1:]) for l in lines if l.startswith("f ")]
    (a.dst / "0_R1_quad.obj").write_text("# phi-SfT R1 frame-0 template (0_R1_quad.obj): vertices and quads only\n" +
                                         "\n".join(kept) + "\n")
    scene = json.loads((a.src / "R1_scene.json").read_text())
    f, c = scene["focal_lengths"][0], scene["optical_centers"][0]
    print(f"{n} points, every {step}th kept ({len(range(0, n, step))}); z from "
          f"{min(flat[2::3]):.3f} to {max(flat[2::3]):.3f} m")
    for name, ff, cc in (("as given (x, y) = (first, second)", f, c),
                         ("(row, column): x uses the second", f[::-1], c[::-1])):
        iou, share = projection_iou(flat, small, sw, sh, a.factor, ff, cc)
        print(f"{name}: fx {ff[0]}, fy {ff[1]}, cx {cc[0]}, cy {cc[1]}: "
              f"IoU {iou:.3f}, points inside the mask {100 * share:.1f} %")
    print("out of the corners' vertical plane, mm (+ away from the camera), 10 cm cells: "
          "rows down from the top edge, columns from vertex 0 towards vertex 992")
    for row in lean_table(flat, a.src / "0_R1_quad.obj"):
        print(" ".join(f"{x:7.1f}" for x in row))


if __name__ == "__main__":
    main()
