#!/usr/bin/env python3
"""The adaptive-against-uniform table of docs/remeshing.md on the disc drape:
runs assets/scenes/disc_drape_50_remeshed.json (adaptive) and disc_drape_50_uniform.json on
uniform meshes of the 50 cm square (assets/meshes/drape_square_50.py CELLS), one run at a time,
and prints a Markdown table: vertices at the end, CPU time (user + system of the run), the drape
coefficient and fold count of the last frame (weft run's "last frame:" line, as weft measure),
and the distance of the last frame's mesh to the finest uniform run's (scripts/mesh_distance.py:
area-weighted mean both ways, and the largest).

    python3 scripts/remesh_trade.py WEFT OUT_DIR [CELLS ...] [--adaptive 'LABEL:KEY=VALUE,...' ...]

WEFT: the weft binary; OUT_DIR: where the meshes and runs go; CELLS: the uniform meshes' cells
per side (default 20 40 62 100; the last is the reference). Each --adaptive adds a row: the
remeshed scene with each KEY=VALUE passed as `--set simulation.remesh.KEY=VALUE` (e.g.
'coarse:h_min=1cm,h_max=5cm,c=2mm'), run in OUT_DIR/adaptive_LABEL. A run whose folder already
holds its trade_log.txt is not run again (delete the folder to rerun it).
"""
import argparse
import csv
import os
import re
import resource
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCENES = os.path.join(ROOT, "assets", "scenes")


def run_scene(weft, scene, out, extra):
    """Runs `weft run` (niced) unless out/ already holds it; returns (cpu_s, last_line)."""
    log = os.path.join(out, "trade_log.txt")
    if os.path.exists(log):
        cpu, line = open(log).read().split("\n", 1)
        return float(cpu), line.strip()
    cmd = ["nice", "-n", "10", weft, "run", scene, "--last", "--export-meshes", "obj", "--up",
           "z", "--out", out] + extra
    print("running:", " ".join(cmd), file=sys.stderr, flush=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit("weft run failed:\n" + done.stderr[-2000:])
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    line = next((l for l in (done.stdout + done.stderr).splitlines() if "last frame:" in l), "")
    with open(log, "w") as f:
        f.write("%.3f\n%s\n" % (cpu, line))
    return cpu, line


def vertices_and_remeshes(out):
    """The vertices of the last frame and the remeshes over the run (stats.csv)."""
    with open(os.path.join(out, "stats.csv")) as f:
        rows = list(csv.DictReader(f))
    return rows[-1]["vertices"], sum(int(r["remeshes"]) for r in rows)


def last_mesh(out):
    meshes = sorted(m for m in os.listdir(out) if m.startswith("mesh_") and m.endswith(".obj"))
    return os.path.join(out, meshes[-1])


def distance(a, b):
    text = subprocess.run([sys.executable, os.path.join(HERE, "mesh_distance.py"), a, b],
                          capture_output=True, text=True, check=True).stdout.split()
    return [float(t) for t in text[:4]]  # mean_ab mean_ba max_ab max_ba, mm


def adaptive_runs(weft, out_dir, options):
    """The scene's own adaptive row, then one per --adaptive 'LABEL:KEY=VALUE,...'."""
    scene = os.path.join(SCENES, "disc_drape_50_remeshed.json")
    rows = [("adaptive (the scene)", "adaptive", [])]
    for option in options:
        label, _, settings = option.partition(":")
        if not label or not settings or re.search(r"[^\w.-]", label) or \
                any(row[1] == "adaptive_" + label for row in rows):
            sys.exit("--adaptive %r: expected LABEL:KEY=VALUE,... with a new LABEL of letters, "
                     "digits, '.', '-' or '_'" % option)
        extra = []
        for setting in settings.split(","):
            if "=" not in setting:
                sys.exit("--adaptive %r: %r is not KEY=VALUE" % (option, setting))
            extra += ["--set", "simulation.remesh." + setting.strip()]
        rows.append(("adaptive %s (%s)" % (label, settings), "adaptive_" + label, extra))
    runs = []
    for label, folder, extra in rows:
        out = os.path.join(out_dir, folder)
        runs.append((label, out) + run_scene(weft, scene, out, extra))
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("weft")
    parser.add_argument("out_dir")
    parser.add_argument("cells", nargs="*", type=int, default=[20, 40, 62, 100])
    parser.add_argument("--adaptive", action="append", default=[], metavar="LABEL:KEY=VALUE,...")
    args = parser.parse_args()
    weft, out_dir, cells = os.path.abspath(args.weft), os.path.abspath(args.out_dir), args.cells
    os.makedirs(out_dir, exist_ok=True)
    adaptive = adaptive_runs(weft, out_dir, args.adaptive)
    runs = []  # (label, out folder, cpu, last line)
    for n in cells:
        mesh = os.path.join(out_dir, "square_%d.obj" % n)
        if not os.path.exists(mesh):
            subprocess.run([sys.executable, os.path.join(ROOT, "assets", "meshes",
                                                         "drape_square_50.py"), str(n), mesh],
                           check=True, stdout=sys.stderr)
        out = os.path.join(out_dir, "uniform_%d" % n)
        cpu, line = run_scene(weft, os.path.join(SCENES, "disc_drape_50_uniform.json"), out,
                              ["--set", "cloth.mesh=" + mesh])
        runs.append(("uniform %.3g mm (%d cells)" % (500.0 / n, n), out, cpu, line))
    runs[-1:-1] = adaptive

    reference = last_mesh(runs[-1][1])
    print("| mesh | vertices at the end | remeshes | CPU | drape coefficient | folds | "
          "distance to the %d-cell run: mean both ways; largest |" % cells[-1])
    print("|---|---|---|---|---|---|---|")
    for label, out, cpu, line in runs:
        vertices, remeshes = vertices_and_remeshes(out)
        m = re.search(r"drape coefficient ([0-9.]+), (\d+) folds", line)
        dc, folds = (m.group(1), m.group(2)) if m else ("—", "—")
        if out == runs[-1][1]:
            dist = "— (the reference)"
        else:
            d = distance(last_mesh(out), reference)
            dist = "%.1f, %.1f mm; %.0f mm" % (d[0], d[1], max(d[2], d[3]))
        print("| %s | %s | %s | %.1f s | %s | %s | %s |" % (
            label, vertices, remeshes, cpu, dc, folds, dist))


if __name__ == "__main__":
    main()
