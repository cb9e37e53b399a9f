#!/usr/bin/env python3
"""Puts PNG images of the same height side by side, left to right, into one RGB PNG (for the
gallery's comparisons; no imaging library needed: 8-bit grey, RGB or RGBA, non-interlaced, as
weft writes them).

    python3 scripts/png_side_by_side.py OUT.png LEFT.png RIGHT.png [MORE.png ...]
"""
import sys

from photo_triptych import rgb
from phi_sft_R1_data import write_png


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    images = [rgb(p) for p in sys.argv[2:]]
    height = images[0][1]
    if any(h != height for _, h, _ in images):
        sys.exit("the images differ in height")
    width = sum(w for w, _, _ in images)
    out = bytearray()
    for y in range(height):
        for w, _, px in images:
            out += px[y * w * 3:(y + 1) * w * 3]
    write_png(sys.argv[1], width, height, 3, out)


if __name__ == "__main__":
    main()
