#!/usr/bin/env python3
"""Synthetic photos for `weft photo-scene`: cloths held by two corners at known places, rendered
by weft through a known calibrated camera, then placed again from the render and its mask alone;
prints a table of the recovered corners' errors (mm), the tilt and density found, IoU and the
outline Chamfer distance (docs/photos.md, "A scene from a photo"). Standard library only.

  scripts/photo_scene_synthetic.py [--weft build/weft] [--out out/photo_scene_synthetic]
                                   [--cases NAME,...] [--fits none,depth+tilt,...]

Each case is a truth scene in the camera's frame (x right, y down, z forward; the camera at the
origin): the held corners' positions, the cloth's size, the camera's tilt (gravity
9.81 (0, cos t, sin t)) and the density. `weft run` settles it (dynamic relaxation, 48 frames,
--mask) and its last frame and mask are the "photo". Each fit is a --fit list of
`weft photo-scene` ('+' for ',').
"""
import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

# fx, fy, cx, cy for 480 x 360: unequal focal lengths and an off-centre principal point.
CAMERA = {"intrinsics": {"fx": 620.0, "fy": 600.0, "cx": 250.3, "cy": 170.8, "size": [480, 360]}}

# name: (left corner, right corner [m, camera frame], cloth W x H [m], tilt [deg], density [kg/m^2])
CASES = {
    "square_1.2m": ((-0.275, -0.2, 1.2), (0.275, -0.2, 1.2), (0.55, 0.55), 0.0, 0.19),
    "square_2m": ((-0.275, -0.25, 2.0), (0.275, -0.25, 2.0), (0.55, 0.55), 0.0, 0.19),
    "wide_1.5m": ((-0.4, -0.2, 1.5), (0.4, -0.2, 1.5), (0.8, 0.5), 0.0, 0.19),
    "stretched_3%": ((-0.28325, -0.2, 1.2), (0.28325, -0.2, 1.2), (0.55, 0.55), 0.0, 0.19),
    "turned_0.15m": ((-0.27, -0.2, 1.125), (0.25, -0.2, 1.275), (0.55, 0.55), 0.0, 0.19),
    "tilt_10deg": ((-0.275, -0.2, 1.2), (0.275, -0.2, 1.2), (0.55, 0.55), 10.0, 0.19),
    "heavy_0.5": ((-0.275, -0.2, 1.2), (0.275, -0.2, 1.2), (0.55, 0.55), 0.0, 0.5),
}


def truth_scene(left, right, size, tilt_deg, density):
    left, right = [list(map(float, p)) for p in (left, right)]
    t = math.radians(tilt_deg)
    down = (0.0, math.cos(t), math.sin(t))
    span = [r - l for l, r in zip(left, right)]
    dist = math.sqrt(sum(s * s for s in span))
    warp = [s / dist for s in span]
    dw = sum(d * w for d, w in zip(down, warp))
    up = [-(d - dw * w) for d, w in zip(down, warp)]
    n = math.sqrt(sum(u * u for u in up))
    weft = [u / n for u in up]
    w, h = size
    origin = [l - h * f for l, f in zip(left, weft)]
    draw = [s - w * a for s, a in zip(span, warp)]
    m = lambda v: [f"{x:.6f} m" for x in v]
    return {
        "description": "photo_scene_synthetic.py truth",
        "cloth": {"size": [f"{w} m", f"{h} m"], "resolution": [32, max(2, round(32 * h / w))],
                  "origin": m(origin), "warp_axis": warp, "weft_axis": weft,
                  "material": {"density": f"{density} kg/m^2"},
                  "pins": [{"corner": "u0v1"},
                           {"corner": "u1v1", "path": [{"time": "0 s", "offset": m([0, 0, 0])},
                                                       {"time": "0.05 s", "offset": m(draw)}]}]},
        "simulation": {"model": "mass_spring", "integrator": "dynamic_relaxation",
                       "gravity": [9.81 * d for d in down], "time_step": "auto"},
        "output": {"fps": 24, "frames": 48},
        "render": {"size": [480, 360],
                   "camera": dict(CAMERA, position=["0 m", "0 m", "0 m"],
                                  rotation=[[1, 0, 0], [0, 1, 0], [0, 0, 1]]),
                   "texture": {"woven_check": {"stripes": 6}, "scale": ["0.1 m", "0.1 m"]},
                   "colors": {"background": [0, 0, 0]}, "ground": False, "supports": False, "msaa": 4},
    }


def run(cmd):
    print("+", " ".join(map(str, cmd)), file=sys.stderr)
    subprocess.run(list(map(str, cmd)), check=True, stdout=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--weft", default="build/weft")
    ap.add_argument("--out", default="out/photo_scene_synthetic")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--fits", default="none,depth+tilt,depth+tilt+density")
    ap.add_argument("--max-evaluations", default="40")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "camera.json").write_text(json.dumps(CAMERA))
    print("| case | fit | corner error L, R (mm) | depth error (mm) | tilt (deg, truth) | density (kg/m², truth) | IoU | Chamfer (px) |")
    print("|---|---|---|---|---|---|---|---|")
    for name in a.cases.split(","):
        left, right, size, tilt, density = CASES[name]
        case = out / name
        case.mkdir(exist_ok=True)
        (case / "truth.json").write_text(json.dumps(truth_scene(left, right, size, tilt, density), indent=1))
        if not (case / "truth" / "mask_0048.png").exists():
            run([a.weft, "run", case / "truth.json", "--out", case / "truth", "--mask"])
        for fit in a.fits.split(","):
            dst = case / ("fit_" + fit.replace("+", "_"))
            run([a.weft, "photo-scene", case / "truth" / "frame_0048.png", "--mask",
                 case / "truth" / "mask_0048.png", "--camera", out / "camera.json", "--cloth-size",
                 f"{size[0]}x{size[1]}", "--fit", fit.replace("+", ","), "--max-evaluations",
                 a.max_evaluations, "--out", dst])
            s = json.loads((dst / "summary.json").read_text())
            c = s["chosen"]
            got = c["held_corners_m"]
            errs = [1e3 * math.dist(g, t) for g, t in zip(got, (left, right))]
            depth_err = 1e3 * ((got[0][2] + got[1][2]) - (left[2] + right[2])) / 2
            dens = c.get("density_kg_m2", 0.19)
            print(f"| {name} | {fit.replace('+', ', ')} | {errs[0]:.1f}, {errs[1]:.1f} | {depth_err:+.1f} | "
                  f"{c['tilt_deg']:+.2f} ({tilt:g}) | {dens:.3f} ({density:g}) | {s['iou']:.4f} | "
                  f"{s['chamfer_px']:.3f} |", flush=True)


if __name__ == "__main__":
    main()
