#!/usr/bin/env python3
"""Where a probe's noise comes from: variance per ray by the reflections a path may make, and with
the scene's emitters made single-sided.

    scripts/noise_sources.py [--scene cornell_box] [--baker build/baker] [--rays 16384] [--seeds 32]
        [--threads 2] [--json OUT.json]

At each probe of ../shared/data/reference/<scene>.json, `baker probe --rays R --no direct-punctual`
runs once per seed (each seed draws its own lattice rotations and paths) with --bounces 1, 2 and 3,
and again with 3 on a copy of the scene whose emissive materials are single-sided. A seed's error
at a probe is the RMSE of its six axis irradiances (r + g + b) against their mean over the seeds,
over that mean's average (the error of scripts/cycles_time_to_error.py, its noise alone); the
variance per ray is R times its mean square over the seeds (with seeds − 1 degrees of freedom): a
probe whose variance per ray is v reaches 1 % at v / 0.01² rays. The difference between bounce
counts is the noise the added reflection brings; the single-sided copy takes out the light a
double-sided emitter sheds on the surfaces just behind it (the Cornell box's ceiling around its
light, 1 mm above it).

Needs ../shared beside the checkout. Exit status: 0 measured, 2 could not measure.
"""
import argparse
import json
import math
import os
import shutil
import tempfile

from probe_runs import ROOT, SHARED, baker_axes, fail

AXES = ["+x", "-x", "+y", "-y", "+z", "-z"]


def variance_per_ray(runs, rays):
    """Per probe: R · Σ_seeds (relative RMSE against the seeds' mean)² / (seeds − 1)."""
    seeds, out = len(runs), []
    for p in range(len(runs[0])):
        sums = [[sum(run[p][a]) for a in AXES] for run in runs]
        mean = [sum(s[a] for s in sums) / seeds for a in range(len(AXES))]
        scale = sum(mean) / len(AXES)
        squares = [sum((s[a] - mean[a]) ** 2 for a in range(len(AXES))) / len(AXES) / scale ** 2 for s in sums]
        out.append(rays * sum(squares) / (seeds - 1))
    return out


def single_sided_copy(scene, directory):
    """The scene's folder copied, with every emissive material single-sided."""
    copy = os.path.join(directory, "scene")
    shutil.copytree(os.path.dirname(scene), copy)
    path = os.path.join(copy, os.path.basename(scene))
    if not path.endswith(".gltf"):
        fail("%s: only .gltf scenes are copied" % scene)
    gltf = json.load(open(path))
    for material in gltf.get("materials", []):
        if any(material.get("emissiveFactor", [0, 0, 0])):
            material["doubleSided"] = False
    json.dump(gltf, open(path, "w"))
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--baker", default=os.path.join(ROOT, "build", "baker"))
    ap.add_argument("--rays", type=int, default=16384)
    ap.add_argument("--seeds", type=int, default=32)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json")
    args = ap.parse_args()
    if args.seeds < 2:
        fail("--seeds must be at least 2")
    reference_path = os.path.join(SHARED, "data", "reference", args.scene + ".json")
    if not os.path.isfile(reference_path):
        fail("%s not found (needs ../shared beside the checkout)" % reference_path)
    reference = json.load(open(reference_path))
    scene = os.path.join(SHARED, "data", "scenes", args.scene, reference["gltf"])
    probes = reference["probes"]

    def measure(path, bounces):
        runs = [baker_axes(args.baker, path, probes, args.rays, bounces, 1000 + seed, args.threads)
                for seed in range(args.seeds)]
        return variance_per_ray(runs, args.rays)

    rows = [{"setting": "bounces %d" % b, "variance_per_ray": measure(scene, b)} for b in (1, 2, 3)]
    with tempfile.TemporaryDirectory() as tmp:
        rows.append({"setting": "bounces 3, emitters single-sided",
                     "variance_per_ray": measure(single_sided_copy(scene, tmp), 3)})

    print("variance per ray (R x relative variance of one seed), %d rays, %d seeds" % (args.rays, args.seeds))
    print("| setting | " + " | ".join("probe %s" % ", ".join("%g" % x for x in p) for p in probes) + " |")
    print("|---" * (len(probes) + 1) + "|")
    for row in rows:
        print("| %s | " % row["setting"] + " | ".join("%.2f" % v for v in row["variance_per_ray"]) + " |")
    # Chi-squared with seeds − 1 degrees of freedom: the estimates' own spread.
    print("each figure is known to about ±%.0f %% (one standard deviation, if the noise were normal)"
          % (100 * math.sqrt(2.0 / (args.seeds - 1))))
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"scene": args.scene, "rays": args.rays, "seeds": args.seeds, "probes": probes, "rows": rows},
                      out, indent=1)


if __name__ == "__main__":
    main()
