#!/usr/bin/env python3
"""Side by side: a photo, a render through the photo's camera and their overlay, the same size
each, with a 6-pixel white gap (gallery/photos/). Standard library only.

  scripts/photo_triptych.py PHOTO.png RENDER.png OVERLAY.png OUT.png [--crop X,Y,W,H] [--zoom N]

--crop keeps the same W x H window (top-left pixel X, Y) of each; --zoom repeats every pixel
N x N times (nearest neighbour: the pixels stay visible as pixels).
"""
import argparse
import sys

from phi_sft_R1_data import read_png, write_png


def rgb(path):
    w, h, ch, px = read_png(path)
    if ch == 1:
        px = bytearray(v for g in px for v in (g, g, g))
    elif ch == 4:
        px = bytearray(v for i, v in enumerate(px) if i % 4 != 3)
    return w, h, px


def crop_zoom(image, box, zoom):
    w, h, px = image
    x0, y0, cw, ch = box if box else (0, 0, w, h)
    if x0 < 0 or y0 < 0 or cw < 1 or ch < 1 or x0 + cw > w or y0 + ch > h:
        sys.exit(f"photo_triptych: --crop {x0},{y0},{cw},{ch} is not inside the {w}x{h} image")
    out = bytearray()
    for y in range(ch * zoom):
        for x in range(cw * zoom):
            i = ((y0 + y // zoom) * w + x0 + x // zoom) * 3
            out += px[i:i + 3]
    return cw * zoom, ch * zoom, out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("images", nargs=3)
    ap.add_argument("out")
    ap.add_argument("--crop", type=lambda t: tuple(int(v) for v in t.split(",")))
    ap.add_argument("--zoom", type=int, default=1)
    a = ap.parse_args()
    images = [rgb(p) for p in a.images]
    w, h = images[0][0], images[0][1]
    if any((i[0], i[1]) != (w, h) for i in images):
        sys.exit("photo_triptych: the three images must have the same size, got " +
                 ", ".join(f"{i[0]}x{i[1]}" for i in images))
    if a.crop is not None and len(a.crop) != 4:
        sys.exit("photo_triptych: --crop expects X,Y,W,H")
    images = [crop_zoom(i, a.crop, max(1, a.zoom)) for i in images]
    w, h = images[0][0], images[0][1]
    gap = 6
    width = 3 * w + 2 * gap
    out = bytearray(b"\xff" * (width * h * 3))
    for k, (_, _, px) in enumerate(images):
        x0 = k * (w + gap)
        for y in range(h):
            out[(y * width + x0) * 3:(y * width + x0 + w) * 3] = px[y * w * 3:(y + 1) * w * 3]
    write_png(a.out, width, h, 3, out)


if __name__ == "__main__":
    main()
