#!/usr/bin/env python3
"""Predicts the Cusick drape coefficient (DC) of the published fabrics in
assets/fabrics/published_drape.json from their measured properties, without fitting anything,
and prints each prediction beside the measured DC and the authors' own CLO3D prediction.

    python3 scripts/predict_published_drape.py [--weft BIN] [--scene SCENE] [--seeds N]
                                               [--data JSON] [--out DIR]

For each fabric: weight (g/m²) and the authors' CLO3D inputs converted from KES-FB -- bending
g·mm²/s² (= 1e-9 N·m, a rigidity per width), stretch and shear g/s² (= 1e-3 N/m, a force per
width) -- become cloth.material of the scene (its preset removed), and `weft measure --static
--seeds N` solves the rest shape from N imperfection seeds. Its static.csv gives DC and folds
per seed; the table shows mean ± sample sd. The tester's specimen and support diameters are not
in the source: the scene's are used (30 cm on an 18 cm disc, the standard Cusick test).
Python 3 standard library only.
"""
import argparse
import csv
import datetime
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The source's units to SI: g·mm²/s² -> N·m, g/s² -> N/m.
G_MM2_PER_S2_IN_N_M = 1e-3 * 1e-6
G_PER_S2_IN_N_PER_M = 1e-3
# Keys each fabric must have (dotted paths into its JSON object), all positive numbers.
REQUIRED = ("weight_g_m2", "clo3d_bending_g_mm2_per_s2.warp", "clo3d_bending_g_mm2_per_s2.weft",
            "clo3d_stretch_g_per_s2.warp", "clo3d_stretch_g_per_s2.weft",
            "clo3d_shear_g_per_s2", "drape.coefficient", "clo3d_simulated_drape_coefficient")
# Rough textile ranges, to catch a wrong conversion factor (not to judge the fabric).
PLAUSIBLE = {"bend": (1e-7, 1e-3), "stretch": (10.0, 1e5), "shear": (0.1, 1e4)}


def value(fabric, key):
    """The positive number at the dotted key, or exits naming the fabric and the key."""
    node = fabric
    for part in key.split("."):
        node = node.get(part) if isinstance(node, dict) else None
    name = fabric.get("name", "<unnamed fabric>")
    if node is None:
        sys.exit("error: fabric '%s': %s is missing or null" % (name, key))
    if isinstance(node, bool) or not isinstance(node, (int, float)) or node <= 0:
        sys.exit("error: fabric '%s': %s is %r, not a positive number" % (name, key, node))
    return float(node)


def material(fabric):
    """The fabric's cloth.material in SI units, checked against the plausible ranges."""
    mat = {
        "density": value(fabric, "weight_g_m2") * 1e-3,  # g/m² -> kg/m²
        "stretch_warp": value(fabric, "clo3d_stretch_g_per_s2.warp") * G_PER_S2_IN_N_PER_M,
        "stretch_weft": value(fabric, "clo3d_stretch_g_per_s2.weft") * G_PER_S2_IN_N_PER_M,
        "shear": value(fabric, "clo3d_shear_g_per_s2") * G_PER_S2_IN_N_PER_M,
        "bend_warp": value(fabric, "clo3d_bending_g_mm2_per_s2.warp") * G_MM2_PER_S2_IN_N_M,
        "bend_weft": value(fabric, "clo3d_bending_g_mm2_per_s2.weft") * G_MM2_PER_S2_IN_N_M,
    }
    for key, x in mat.items():
        kind = key.split("_")[0]
        lo, hi = PLAUSIBLE.get(kind, (0, float("inf")))
        if not lo <= x <= hi:
            print("warning: fabric '%s': %s = %.3g outside %g..%g (SI): check the units"
                  % (fabric["name"], key, x, lo, hi), file=sys.stderr)
    return mat


def solve(weft, scene, mat, seeds, out):
    """Runs weft measure --static; returns static.csv's rows, or exits with weft's message."""
    units = {"density": "kg/m^2", "bend_warp": "N*m", "bend_weft": "N*m"}
    cmd = [weft, "measure", scene, "--static", "--seeds", str(seeds), "--out", out,
           "--set", "cloth.material.preset=null"]
    for key, x in mat.items():
        cmd += ["--set", "cloth.material.%s=%.6g %s" % (key, x, units.get(key, "N/m"))]
    print("running:", " ".join("'%s'" % c if " " in c else c for c in cmd),
          file=sys.stderr, flush=True)
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("error: weft failed (exit %d) on: %s\n%s"
                 % (done.returncode, " ".join(cmd), (done.stdout + done.stderr)[-3000:]))
    with open(os.path.join(out, "static.csv")) as f:
        return list(csv.DictReader(f))


def spread(xs):
    """'mean ± sd' (sample sd; just the value for one seed)."""
    if len(xs) == 1:
        return "%.3f" % xs[0]
    return "%.3f ± %.3f" % (statistics.mean(xs), statistics.stdev(xs))


def row(fabric, mat, rows):
    """One Markdown table row, and (measured DC, weft's mean DC, CLO3D's DC)."""
    measured = value(fabric, "drape.coefficient")
    clo = value(fabric, "clo3d_simulated_drape_coefficient")
    dcs = [float(r["drape_coefficient"]) for r in rows]
    folds = [int(r["folds"]) for r in rows]
    conv = sum(int(r["converged"]) for r in rows)
    err = statistics.mean(dcs) - measured
    fold_text = "%d–%d" % (min(folds), max(folds)) if min(folds) != max(folds) else str(folds[0])
    cells = [fabric["name"], "%.1f" % value(fabric, "weight_g_m2"),
             "%.2e, %.2e" % (mat["bend_warp"], mat["bend_weft"]), "%.3f" % measured,
             spread(dcs), "%+.3f" % err, "%.3f" % clo, "%+.3f" % (clo - measured),
             fold_text, "%d/%d" % (conv, len(rows))]
    return "| " + " | ".join(cells) + " |", (measured, statistics.mean(dcs), clo)


def summary(label, measured, predicted):
    """Mean absolute error, bias (mean signed error) and Pearson r of predictions."""
    errors = [p - m for m, p in zip(measured, predicted)]
    mae = statistics.mean(abs(e) for e in errors)
    mm, mp = statistics.mean(measured), statistics.mean(predicted)
    cov = sum((m - mm) * (p - mp) for m, p in zip(measured, predicted))
    r = cov / (sum((m - mm) ** 2 for m in measured) * sum((p - mp) ** 2 for p in predicted)) ** 0.5
    return "%s: MAE %.3f, bias %+.3f, Pearson r with measured %.2f (n = %d)" % (
        label, mae, statistics.mean(errors), r, len(errors))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--weft", default=os.path.join(ROOT, "build", "weft"))
    parser.add_argument("--scene", default=os.path.join(ROOT, "assets/scenes/cusick_drape.json"))
    parser.add_argument("--data", default=os.path.join(ROOT, "assets/fabrics/published_drape.json"))
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--out", default=os.path.join("out", "published_drape"))
    args = parser.parse_args()
    for path in (args.weft, args.scene, args.data):
        if not os.path.isfile(path):
            sys.exit("error: no such file: %s" % path)
    with open(args.data) as f:
        fabrics = json.load(f)["fabrics"]
    for fabric in fabrics:  # every value checked before the first (slow) solve
        fabric.setdefault("name", fabric.get("source_id", "<unnamed fabric>"))
        [value(fabric, key) for key in REQUIRED]
    lines, dcs = [], []  # dcs: (measured, weft mean, CLO3D) per fabric
    for i, fabric in enumerate(fabrics):
        mat = material(fabric)
        rows = solve(args.weft, args.scene, mat, args.seeds,
                     os.path.join(args.out, "fabric_%d" % (i + 1)))
        line, triple = row(fabric, mat, rows)
        lines.append(line)
        dcs.append(triple)
    print("%s, %s, %d seed(s) per fabric" % (datetime.date.today().isoformat(),
                                             os.path.relpath(args.scene, ROOT), args.seeds))
    print()
    print("| fabric | g/m² | B warp, weft (N·m) | measured DC | weft DC | weft − measured "
          "| CLO3D DC | CLO3D − measured | folds | converged |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    print("\n".join(lines))
    print()
    measured, weft_dc, clo_dc = zip(*dcs)
    print(summary("weft (mean over seeds)", measured, weft_dc))
    print(summary("CLO3D (authors)", measured, clo_dc))


if __name__ == "__main__":
    main()
