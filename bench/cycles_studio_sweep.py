#!/usr/bin/env python3
# Cycles' PSNR-vs-CPU-time curve on the studio-lit sphere drape (bench/cycles_studio.py draws
# it): one Cycles reference with --reference-samples, then each of --samples, PSNR and SSIM
# against that reference (`weft diff`), and the CPU time (user + system) of the whole Blender
# process, all threads, and of the same process drawing 1 sample (start-up, scene, BVH: its
# floor). docs/benchmarks.md's "Image-based lighting" table, Cycles' rows.
#
#   bench/cycles_studio_sweep.py --mesh DIR/mesh_0096.obj [--hdr ../shared/hdri/studio.hdr]
#       [--weft build/weft] [--blender blender] [--size 320x240] [--samples 16,32,64,128,256]
#       [--reference-samples 1024] [--work /tmp/weft_cycles_sweep] [--threads N]
#
# --threads N fixes Cycles' thread count (0, the default: all cores); with 1, pinned to a core
# (taskset), the sweep leaves the other core to other work and its CPU times stay comparable.
#
# The mesh: `weft run assets/scenes/sphere_drape.json --last --export-meshes obj --up z`.

import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from raytrace_ibl_sweep import children_cpu_s, compare  # noqa: E402


def cycles(o, samples, out):
    before = children_cpu_s()
    p = subprocess.run([o.blender, "-b", "--factory-startup", "-P",
                        os.path.join(HERE, "cycles_studio.py"), "--", o.mesh, o.hdr, out, o.size,
                        str(samples), "--threads", str(o.threads)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0 or not os.path.exists(out):
        sys.exit("blender failed:\n" + p.stdout[-3000:])
    return children_cpu_s() - before


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--hdr", default="../shared/hdri/studio.hdr")
    parser.add_argument("--weft", default="build/weft")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--size", default="320x240")
    parser.add_argument("--samples", default="16,32,64,100,128,256")
    parser.add_argument("--reference-samples", type=int, default=1024)
    parser.add_argument("--work", default="/tmp/weft_cycles_sweep")
    parser.add_argument("--threads", type=int, default=0)
    o = parser.parse_args()
    o.hdr = os.path.abspath(o.hdr)
    o.mesh = os.path.abspath(o.mesh)
    os.makedirs(o.work, exist_ok=True)
    reference = os.path.join(o.work, "cycles_%s_%d.png" % (o.size, o.reference_samples))
    if not os.path.exists(reference):
        cpu = cycles(o, o.reference_samples, reference)
        print("Cycles reference %s, %d samples: %.1f s CPU" % (o.size, o.reference_samples, cpu),
              flush=True)
    floor = cycles(o, 1, os.path.join(o.work, "cycles_%s_1.png" % o.size))
    print("Blender with 1 sample (start-up, scene, BVH): %.1f s CPU\n" % floor)
    print("| Cycles samples | PSNR dB | SSIM | CPU s (whole process) |")
    print("|---:|---:|---:|---:|")
    for samples in (int(s) for s in o.samples.split(",")):
        out = os.path.join(o.work, "cycles_%s_%d.png" % (o.size, samples))
        cpu = cycles(o, samples, out)
        psnr, ssim = compare(o, out, reference)
        print("| %d | %.2f | %.4f | %.1f |" % (samples, psnr, ssim, cpu), flush=True)


if __name__ == "__main__":
    main()
