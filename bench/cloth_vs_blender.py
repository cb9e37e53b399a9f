#!/usr/bin/env python3
"""weft against Blender's cloth on the two-corner hang, CPU time per frame on one thread.

Runs, for each size, weft's inextensibility sweep (fast projection to 1 % strain, implicit Euler
by conjugate gradients to 1e-3, one thread) with the fixed step of 1/120 s and with the
adaptive step, then Blender's cloth on the same sheet (bench/blender_cloth_hang.py, `blender -b
-t 1`), and prints one table: CPU ms per frame of each, weft's ratio to Blender, the targets of
the issue that asked for this comparison, and the growth of each column with the vertex count.
Blender's column is left out when no `blender` is found. The sweep's CPU time is the process's
over the frames (the set-up left out); Blender's is its bake's.

Both run pinned to one CPU (`taskset -c CPU`, the last one by default). Blender's `-t 1` does
not keep its cloth solver on one thread: on a busy machine its waiting threads spin, and its
CPU time per frame at 32² was measured at 24–293 ms unpinned against 20 ms pinned.

  python3 bench/cloth_vs_blender.py [--sizes 32,64,128,256] [--frames 48] [--quality 5]
      [--sweep build/bench/inextensibility_sweep] [--blender blender] [--wool-mass]
      [--preconditioner auto|multigrid|lines|block_jacobi] [--cpu N]
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TARGET_RATIO = {64: 0.10, 128: 0.12, 256: 0.15}  # weft / Blender, CPU per frame


def pinned(command, cpu):
    return (["taskset", "-c", str(cpu)] + command) if shutil.which("taskset") else command


def sweep_cpu_ms(sweep, n, frames, adaptive, preconditioner, cpu):
    command = [sweep, "--sizes", str(n), "--cg", "1e-3", "--methods", "tol 1e-2",
               "--threads", "1", "--frames", str(frames)]
    if adaptive:
        command += ["--adaptive", "0.25"]
    if preconditioner == "multigrid":
        command.append("--multigrid")
    elif preconditioner == "block_jacobi":
        command.append("--block-jacobi")
    elif preconditioner == "lines":
        command.append("--lines")
    out = subprocess.run(pinned(command, cpu), check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        if line.startswith("%d²" % n) and "fast_projection" in line:
            fields = line.split()
            # size, "fast_projection", "tol", "1e-2", ms/frame, cpu ms, iter/step, fact/step,
            # CG/step, max it, max strain, mean strain, unconverged, steps/frame, rejected
            return {"cpu_ms": float(fields[5]), "cg": float(fields[8]),
                    "strain": fields[10], "unconverged": int(fields[12])}
    raise SystemExit("no fast_projection row for %d² in the sweep's output:\n%s" % (n, out))


def blender_cpu_ms(blender, n, frames, quality, wool_mass, cpu):
    command = [blender, "-b", "--factory-startup", "-t", "1", "--python-exit-code", "1",
               "--python", os.path.join(HERE, "blender_cloth_hang.py"), "--",
               str(n), str(frames), str(quality)]
    if wool_mass:
        command.append("--wool-mass")
    out = subprocess.run(pinned(command, cpu), check=True, capture_output=True, text=True).stdout
    match = re.search(r"cpu_ms_per_frame=([0-9.]+) lowest_z=([-0-9.]+) max_strain=([0-9.]+)", out)
    if not match:
        raise SystemExit("no weft-bench line in Blender's output:\n%s" % out[-2000:])
    return {"cpu_ms": float(match.group(1)), "strain": "%.0f%%" % (100 * float(match.group(3)))}


def growth(rows, key):
    if len(rows) < 2 or rows[0][key] is None or rows[-1][key] is None:
        return "-"
    vertices = math.log((rows[-1]["n"] ** 2) / (rows[0]["n"] ** 2))
    return "%.2f" % (math.log(rows[-1][key] / rows[0][key]) / vertices)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="32,64,128,256")
    parser.add_argument("--frames", type=int, default=48)
    parser.add_argument("--quality", type=int, default=5)
    parser.add_argument("--sweep", default=os.path.join(HERE, "..", "build", "bench",
                                                        "inextensibility_sweep"))
    parser.add_argument("--blender", default=shutil.which("blender"))
    parser.add_argument("--wool-mass", action="store_true")
    parser.add_argument("--preconditioner", default="auto",
                        choices=["auto", "multigrid", "lines", "block_jacobi"])
    parser.add_argument("--cpu", type=int, default=(os.cpu_count() or 1) - 1)
    args = parser.parse_args()
    if not os.path.exists(args.sweep):
        raise SystemExit("%s: not found (build with -DWEFT_BUILD_BENCH=ON)" % args.sweep)
    if not args.blender:
        print("blender not found: its column is left out", file=sys.stderr)
    rows = []
    for n in [int(s) for s in args.sizes.split(",")]:
        fixed = sweep_cpu_ms(args.sweep, n, args.frames, False, args.preconditioner, args.cpu)
        adaptive = sweep_cpu_ms(args.sweep, n, args.frames, True, args.preconditioner, args.cpu)
        blender = (blender_cpu_ms(args.blender, n, args.frames, args.quality, args.wool_mass,
                                  args.cpu) if args.blender else None)
        rows.append({"n": n, "fixed": fixed["cpu_ms"], "adaptive": adaptive["cpu_ms"],
                     "blender": blender["cpu_ms"] if blender else None,
                     "detail": (fixed, adaptive, blender)})
        print_row(rows[-1])
    print("growth as vertices^k from %d² to %d²: weft fixed %s, adaptive %s, Blender %s "
          "(target for weft: at most 1.3)" % (rows[0]["n"], rows[-1]["n"], growth(rows, "fixed"),
                                              growth(rows, "adaptive"), growth(rows, "blender")))


def print_row(row):
    if not hasattr(print_row, "header"):
        print_row.header = True
        print("%-6s %12s %12s %12s %14s %8s  %s" % ("size", "weft fixed", "weft adapt.",
                                                     "Blender", "weft/Blender", "target",
                                                     "strain (fixed, adaptive, Blender), CG "
                                                     "iterations a step, unconverged steps"))
    fixed, adaptive, blender = row["detail"]
    ratio = "-"
    if row["blender"]:
        best = min(row["fixed"], row["adaptive"])
        ratio = "%.2f" % (best / row["blender"])
    target = TARGET_RATIO.get(row["n"])
    print("%-6s %12.1f %12.1f %12s %14s %8s  %s, %s, %s; CG %.1f, %.1f; unconverged %d, %d" % (
        "%d²" % row["n"], row["fixed"], row["adaptive"],
        "%.1f" % row["blender"] if row["blender"] else "-", ratio,
        "%.2f" % target if target else "-", fixed["strain"], adaptive["strain"],
        blender["strain"] if blender else "-", fixed["cg"], adaptive["cg"],
        fixed["unconverged"], adaptive["unconverged"]))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
