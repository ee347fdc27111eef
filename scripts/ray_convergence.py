#!/usr/bin/env python3
"""How the error of a probe's irradiance falls as --rays grows.

Bakes the same probes with `baker probe` at increasing ray counts and compares the irradiance
for the six axis normals with a converged bake of the same probes (many more rays, another
seed), both as the samples give it (irradiance_from_samples) and as the basis reconstructs it
(irradiance, against the reference's reconstruction: the noise, not the basis's own error). Prints a Markdown table of relative RMSE over probes × normals × channels, each
normalised by the probe's mean axis irradiance.

    scripts/ray_convergence.py SCENE --at x,y,z [--at ...] [--rays 64,256,1024,4096,16384]
        [--reference-rays 1048576] [--baker build/baker] [-- extra baker args]
"""
import argparse
import json
import math
import subprocess
import sys

AXES = ["+X", "-X", "+Y", "-Y", "+Z", "-Z"]


def bake(baker, scene, positions, rays, seed, extra):
    cmd = [baker, "probe", scene, "--rays", str(rays), "--seed", str(seed), "--json"]
    cmd += [f"--at={p}" for p in positions] + extra
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)["probes"]


def relative_rmse(probes, reference, key):
    total, count = 0.0, 0
    for p, r in zip(probes, reference):
        scale = sum(sum(r["irradiance_from_samples"][a]) for a in AXES) / (3 * len(AXES))
        for a in AXES:
            for c in range(3):
                d = (p[key][a][c] - r[key][a][c]) / scale
                total += d * d
                count += 1
    return math.sqrt(total / count)


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("--at", action="append", required=True)
    ap.add_argument("--rays", default="64,256,1024,4096,16384")
    ap.add_argument("--reference-rays", type=int, default=1 << 20)
    ap.add_argument("--baker", default="build/baker")
    ap.add_argument("--seeds", type=int, default=4, help="seeds averaged per ray count")
    a = ap.parse_args(argv)
    reference = bake(a.baker, a.scene, a.at, a.reference_rays, 1000, extra)
    print(f"scene {a.scene}, {len(a.at)} probe(s), reference {a.reference_rays} rays (seed 1000), "
          f"{a.seeds} seeds per row; extra args: {' '.join(extra) or 'none'}\n")
    print("| rays | rel. RMSE, samples | rel. RMSE, basis reconstruction |")
    print("|---|---|---|")
    for rays in [int(r) for r in a.rays.split(",")]:
        samples = basis = 0.0
        for seed in range(a.seeds):
            probes = bake(a.baker, a.scene, a.at, rays, seed, extra)
            samples += relative_rmse(probes, reference, "irradiance_from_samples") ** 2
            basis += relative_rmse(probes, reference, "irradiance") ** 2
        print(f"| {rays} | {math.sqrt(samples / a.seeds):.4f} | {math.sqrt(basis / a.seeds):.4f} |")


if __name__ == "__main__":
    main()
