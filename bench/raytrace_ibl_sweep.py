#!/usr/bin/env python3
# The ray tracer under image-based lighting, against a many-sample reference: PSNR and SSIM (as
# `weft diff` computes them) and CPU time, for a few settings, on the gallery's studio-lit sphere
# drape (assets/scenes/sphere_drape.json at rest, frame 96, lit by studio.hdr alone, intensity
# 1.5; gallery/README.md) at each --sizes. docs/benchmarks.md's "Image-based lighting" table.
#
#   bench/raytrace_ibl_sweep.py [--weft build/weft] [--hdr ../shared/hdri/studio.hdr]
#       [--work /tmp/weft_ibl_sweep] [--sizes 320x240,1920x1080] [--reference-samples 512]
#       [--rows default,u16,u16p,a128_4,...] [--threads 0]
#
# Once per --work folder: `weft run` simulates the drape (--save-states, --last) and each size's
# reference is rendered with --reference-samples per pixel, uniform (adaptive_error 0), plain
# (--denoise off), seed 1; a second reference with seed 2 gives the references' own noise
# (PSNR between the two, + 3 dB: the error of one against the noise-free picture; not with
# --one-reference). Every row is
# one `weft render` of frame 96 with seed 0, timed by the CPU time (user + system) of the child
# process, all threads; the states' reading and the map's tables are in it (well under a second).

import argparse
import os
import re
import resource
import subprocess
import sys

# Rows by name: "default" (the scene's settings), "uN" (N samples per pixel, uniform, denoised),
# "uNp" (the same, plain), "aN_E" (adaptive: at most N samples, stopping at E display levels of
# standard error; "aN_E_R": in rounds of R samples), denoised.
DEFAULT_ROWS = "default,u16,u16p,u64,u128,a64_4,a128_4,a256_4,a256_2"


def row(name):
    """(description, extra weft render arguments) of a row name."""
    if name == "default":
        return "defaults", []
    m = re.fullmatch(r"u(\d+)(p?)", name)
    if m:
        plain = m.group(2) == "p"
        return ("%s spp uniform%s" % (m.group(1), ", no denoise" if plain else " + denoise"),
                ["--samples", m.group(1), "--set", "render.raytrace.adaptive_error=0"] +
                (["--denoise", "off"] if plain else []))
    m = re.fullmatch(r"a(\d+)_([0-9.]+)(?:_(\d+))?", name)
    if m:
        rounds = m.group(3) or "16"
        return ("adaptive ≤%s spp, error %s, rounds of %s + denoise" % (m.group(1), m.group(2), rounds),
                ["--samples", m.group(1), "--set", "render.raytrace.adaptive_error=" + m.group(2),
                 "--set", "render.raytrace.adaptive_round=" + rounds])
    sys.exit("unknown row '%s' (default, uN, uNp, aN_E, aN_E_R)" % name)


def children_cpu_s():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(command):
    """Runs `command`, returns its CPU seconds; stops the sweep with its output if it fails."""
    before = children_cpu_s()
    p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(command), p.stdout))
    return children_cpu_s() - before


def render(o, size, out, extra):
    environment = 'render.environment={"file": "%s", "intensity": 1.5}' % os.path.abspath(o.hdr)
    return run([o.weft, "render", os.path.join(o.work, "drape"), "--frames", "96", "--out", out,
                "--renderer", "raytrace", "--size", size, "--threads", str(o.threads),
                "--set", environment, "--set", "render.light.intensity=0"] + extra)


def compare(o, a, b):
    p = subprocess.run([o.weft, "diff", a, b, "--report-only"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    m = re.search(r"PSNR ([0-9.inf]+) dB, SSIM ([0-9.]+)", p.stdout)
    if not m:
        sys.exit("weft diff said:\n" + p.stdout)
    return float(m.group(1)), float(m.group(2))


def frame(folder):
    return os.path.join(folder, "frame_0096.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--weft", default="build/weft")
    parser.add_argument("--hdr", default="../shared/hdri/studio.hdr")
    parser.add_argument("--work", default="/tmp/weft_ibl_sweep")
    parser.add_argument("--sizes", default="320x240,1920x1080")
    parser.add_argument("--reference-samples", type=int, default=512)
    parser.add_argument("--rows", default=DEFAULT_ROWS)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--one-reference", action="store_true",
                        help="no second reference (its noise unmeasured): half the reference time")
    o = parser.parse_args()
    os.makedirs(o.work, exist_ok=True)
    states = os.path.join(o.work, "drape")
    if not os.path.exists(os.path.join(states, "state_0096.npy")):
        run([o.weft, "run", "assets/scenes/sphere_drape.json", "--out", states, "--save-states",
             "--last", "--size", "160x120"])
    for size in o.sizes.split(","):
        references = []
        for seed in (1,) if o.one_reference else (1, 2):
            out = os.path.join(o.work, "reference_%s_seed%d" % (size, seed))
            if not os.path.exists(frame(out)):
                cpu = render(o, size, out, ["--samples", str(o.reference_samples), "--denoise", "off",
                                            "--set", "render.raytrace.adaptive_error=0",
                                            "--set", "render.raytrace.seed=%d" % seed])
                print("reference %s seed %d: %.1f s CPU" % (size, seed, cpu), flush=True)
            references.append(frame(out))
        print("\n%s, reference %d spp uniform plain" % (size, o.reference_samples))
        if len(references) == 2:
            own_psnr, own_ssim = compare(o, references[0], references[1])
            print("two references (seeds 1, 2): PSNR %.2f dB (one against the noise-free picture "
                  "≈ %.2f dB), SSIM %.4f" % (own_psnr, own_psnr + 3.01, own_ssim))
        print()
        print("| settings | PSNR dB | SSIM | CPU s |")
        print("|---|---:|---:|---:|")
        for name in o.rows.split(","):
            description, extra = row(name)
            out = os.path.join(o.work, "%s_%s" % (size, name))
            cpu = render(o, size, out, extra)
            psnr, ssim = compare(o, frame(out), references[0])
            print("| %s | %.2f | %.4f | %.1f |" % (description, psnr, ssim, cpu), flush=True)


if __name__ == "__main__":
    main()
