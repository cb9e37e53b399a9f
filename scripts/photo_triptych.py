#!/usr/bin/env python3
"""Side by side: a photo, a render through the photo's camera and their overlay, the same size
each, with a 6-pixel white gap (gallery/photos/). Standard library only.

  scripts/photo_triptych.py PHOTO.png RENDER.png OVERLAY.png OUT.png
"""
import sys

from phi_sft_R1_data import read_png, write_png


def rgb(path):
    w, h, ch, px = read_png(path)
    if ch == 1:
        px = bytearray(v for g in px for v in (g, g, g))
    return w, h, px


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    images = [rgb(p) for p in sys.argv[1:4]]
    w, h = images[0][0], images[0][1]
    if any((i[0], i[1]) != (w, h) for i in images):
        sys.exit("photo_triptych: the three images must have the same size, got " +
                 ", ".join(f"{i[0]}x{i[1]}" for i in images))
    gap = 6
    width = 3 * w + 2 * gap
    out = bytearray(b"\xff" * (width * h * 3))
    for k, (_, _, px) in enumerate(images):
        x0 = k * (w + gap)
        for y in range(h):
            out[(y * width + x0) * 3:(y * width + x0 + w) * 3] = px[y * w * 3:(y + 1) * w * 3]
    write_png(sys.argv[4], width, h, 3, out)


if __name__ == "__main__":
    main()
