#!/usr/bin/env python3
"""Time per probe to reach a relative irradiance error, the baker against scripting Blender Cycles.

    scripts/cycles_time_to_error.py [--scene cornell_box] [--baker build/baker] [--threads 2]
        [--rays 4096,8192,16384,32768,65536] [--seeds 32] [--spp 2,4,8,16,32] [--cycles-seeds 8]
        [--res 128x64] [--target 0.01] [--volume-spacing 0.7] [--converged-rays 1048576] [--correct-pixel-bias]
        [--share-reflections SIZE] [--json OUT.json]

Both renderers are measured against the same truth: the Cycles reference irradiance of
../shared/data/reference/<scene>.json (its setting with --cycles-bounces, default 2: 2 x 1024
samples per pixel, seed-to-seed noise under 0.3 %), at its probes, for the six axis normals.
That reference carries a bias of its own where a bright emitter's edge crosses its panoramas'
pixels (scripts/reference_pixel_bias.py: +0.6 % on the Cornell box's centre probe looking up);
with --correct-pixel-bias the baker is measured against the reference less that bias, worked out
without noise from the scene, while Cycles, whose renders carry the same bias, is measured against
the reference as it is.

Error of one probe: the RMSE of its six axis irradiances (r + g + b) divided by their mean, the
probe's "relative irradiance RMSE". For every ray count (baker) or sample count (Cycles), each seed
draws its own samples (the baker's seed turns its lattices and its paths; Cycles' seed its pixel
samples; the Cycles seeds are not the reference's), and a probe's error is the RMS over seeds. A
setting reaches the target when every probe's error is at most --target. Where the two renderers
disagree (their converged answers differ), that difference is part of the baker's error; the baker
is also measured against its own converged answer (--converged-rays, another seed), which leaves
its noise alone, as the Cycles renders are against the Cycles reference.

Time per probe:
  baker   `baker SCENE --rays R --spacing S --json`: the volume bake's trace-and-project seconds
          divided by its probes: what a probe costs in a bake. The operators, worked out once per
          bake whatever its size, and the load and write are left out (reported as
          operators_seconds).
          With --share-reflections SIZE the baker's probes share their reflections
          (docs/SAMPLING.md): `baker probe` with each probe's brick of the grid at
          --volume-spacing about it, the volume bake within its bricks.
  Cycles  reference_probe.py's per-probe wall seconds (Blender's start-up and the scene import
          are left out), the panorama at --res and the given samples per pixel.
Both use --threads threads. Between two settings on either side of the target, error and time are
interpolated on log scales (error falls as a power of the work).

Needs ../shared beside the checkout (scene, reference, tools) and `blender` on PATH with NumPy
(Debian: blender python3-numpy). Scenes with an environment map are not handled (cornell_box and
cornell_lights have none). Exit status: 0 measured, 2 could not measure.
"""
import argparse
import json
import math
import os
import tempfile

import reference_pixel_bias
from probe_runs import ROOT, SHARED, TOOLS, baker_axes, cycles_axes, fail, lower_keys, require_blender, run

AXES = ["+x", "-x", "+y", "-y", "+z", "-z"]


def probe_error(measured, reference):
    """Relative irradiance RMSE of one probe: six axis sums of r, g, b against the reference's."""
    got = [sum(measured[a]) for a in AXES]
    want = [sum(reference[a]) for a in AXES]
    rmse = math.sqrt(sum((g - w) ** 2 for g, w in zip(got, want)) / len(AXES))
    return rmse / (sum(want) / len(AXES))


def seed_rms(errors_by_seed):
    """Per probe: the RMS over seeds of its error."""
    probes = len(errors_by_seed[0])
    return [math.sqrt(sum(e[p] ** 2 for e in errors_by_seed) / len(errors_by_seed)) for p in range(probes)]


def baker_row(args, scene, probes, reference, converged, bounces, rays):
    errors, noise = [], []
    for seed in range(args.seeds):
        measured = baker_axes(args.baker, scene, probes, rays, bounces, seed, args.threads, sharing(args, True))
        errors.append([probe_error(m, ref) for m, ref in zip(measured, reference)])
        noise.append([probe_error(m, ref) for m, ref in zip(measured, converged)])
    with tempfile.TemporaryDirectory() as tmp:
        bake = json.loads(run([args.baker, scene, "--rays", str(rays), "--bounces", str(bounces), "--no",
                               "direct-punctual", "--spacing", str(args.volume_spacing), "--threads", str(args.threads),
                               "--out", os.path.join(tmp, "volume.vdb"), "--json"] + sharing(args, False)))
    per_probe, own = seed_rms(errors), seed_rms(noise)
    return {"rays": rays, "probe_relative_rmse": per_probe, "worst_probe_relative_rmse": max(per_probe),
            "probe_relative_rmse_against_own_converged": own, "worst_probe_against_own_converged": max(own),
            "seconds_per_probe": bake["seconds"]["trace_and_project"] / bake["probes"],
            "operators_seconds": bake["seconds"]["operators"], "volume_probes": bake["probes"]}


def sharing(args, probe):
    """The baker's flags for shared reflections. `baker probe` (`probe`) then shares with the
    probes of a brick of the grid at --volume-spacing about each probe, as the volume bake timed
    beside it does (which is given --spacing already)."""
    if not args.share_reflections:
        return []
    return ["--share-reflections", str(args.share_reflections)] + (
        ["--spacing", str(args.volume_spacing)] if probe else [])


def cycles_row(args, scene, probes, reference, bounces, spp):
    errors, seconds = [], []
    for k in range(args.cycles_seeds):
        measured, render_seconds = cycles_axes(scene, probes, args.res, spp, bounces, 101 + k, args.threads)
        errors.append([probe_error(m, ref) for m, ref in zip(measured, reference)])
        seconds += render_seconds
    per_probe = seed_rms(errors)
    return {"spp": spp, "res": args.res, "probe_relative_rmse": per_probe, "worst_probe_relative_rmse": max(per_probe),
            "seconds_per_probe": sum(seconds) / len(seconds)}


def time_to_target(rows, target, work_key):
    """Seconds per probe (and work) where the worst probe's error reaches the target, log-interpolated."""
    for before, after in zip([None] + rows[:-1], rows):
        if after["worst_probe_relative_rmse"] > target:
            continue
        if before is None:
            return {work_key: after[work_key], "seconds_per_probe": after["seconds_per_probe"], "interpolated": False,
                    "note": "the smallest setting already reaches the target: an upper bound"}
        e0, e1 = math.log(before["worst_probe_relative_rmse"]), math.log(after["worst_probe_relative_rmse"])
        f = (math.log(target) - e0) / (e1 - e0) if e1 != e0 else 1.0
        lerp = lambda a, b: math.exp(math.log(a) + f * (math.log(b) - math.log(a)))
        return {work_key: lerp(before[work_key], after[work_key]),
                "seconds_per_probe": lerp(before["seconds_per_probe"], after["seconds_per_probe"]), "interpolated": True}
    return None


def speedup(cycles_at, baker_at):
    """Cycles' time over the baker's at the target; None unless both were bracketed by two settings
    (a smallest setting that already reaches it gives only a bound: add smaller ones)."""
    if not (cycles_at and baker_at and cycles_at["interpolated"] and baker_at["interpolated"]):
        return None
    return cycles_at["seconds_per_probe"] / baker_at["seconds_per_probe"]


def numbers(text):
    return [int(v) for v in text.split(",") if v]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--baker", default=os.path.join(ROOT, "build", "baker"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rays", type=numbers, default=numbers("4096,8192,16384,32768,65536"))
    ap.add_argument("--seeds", type=int, default=32)
    ap.add_argument("--spp", type=numbers, default=numbers("2,4,8,16,32"))
    ap.add_argument("--cycles-seeds", type=int, default=8)
    ap.add_argument("--cycles-bounces", type=int, default=2)
    ap.add_argument("--res", default="128x64")
    ap.add_argument("--target", type=float, default=0.01)
    ap.add_argument("--volume-spacing", type=float, default=0.7)
    ap.add_argument("--converged-rays", type=int, default=1 << 20)
    ap.add_argument("--share-reflections", type=float, default=0.0,
                    help="the baker's --share-reflections SIZE (metres); its converged answer shares nothing")
    ap.add_argument("--correct-pixel-bias", action="store_true",
                    help="measure the baker against the reference less its panoramas' pixel bias on emitters "
                         "(scripts/reference_pixel_bias.py); Cycles, whose renders carry it too, against the reference")
    ap.add_argument("--json", help="write the results here as well")
    args = ap.parse_args()

    reference_path = os.path.join(SHARED, "data", "reference", args.scene + ".json")
    scene = os.path.join(SHARED, "data", "scenes", args.scene, args.scene + ".gltf")
    for path in (reference_path, scene, os.path.join(TOOLS, "reference_probe.py"), os.path.join(TOOLS, "panorama_sh.py")):
        if not os.path.exists(path):
            fail("missing %s: the scenes, references and tools live in ../shared beside the checkout" % path)
    require_blender()
    if not os.access(args.baker, os.X_OK):
        fail("no baker at %s (build it, or pass --baker)" % args.baker)
    reference = json.load(open(reference_path))
    if reference.get("env"):
        fail("%s uses an environment map, which this script does not pass on" % args.scene)
    settings = [s for s in reference["settings"] if s["cycles_bounces"] == args.cycles_bounces]
    if not settings:
        fail("%s has no setting with %d Cycles bounces" % (reference_path, args.cycles_bounces))
    setting = settings[0]
    truth = [lower_keys(axes) for axes in setting["irradiance_axes"]]
    probes = reference["probes"]
    baker_truth, bias = truth, None
    if args.correct_pixel_bias:
        # At the size the reference was rendered at, not --res (the size of the renders timed here).
        reference_res = reference["renderer"]["res"]
        width, height = (int(v) for v in reference_res.lower().split("x"))
        bias = reference_pixel_bias.pixel_bias(scene, probes, width, height)
        baker_truth = [{a: [v - d for v, d in zip(t[a], b[a])] for a in AXES} for t, b in zip(truth, bias)]

    # The baker's own converged answer (another seed), against which its error is noise alone.
    converged = baker_axes(args.baker, scene, probes, args.converged_rays, setting["baker_bounces"], 1000, args.threads)
    baker_rows = [baker_row(args, scene, probes, baker_truth, converged, setting["baker_bounces"], r) for r in sorted(args.rays)]
    cycles_rows = [cycles_row(args, scene, probes, truth, args.cycles_bounces, s) for s in sorted(args.spp)]
    baker_at = time_to_target(baker_rows, args.target, "rays")
    noise_rows = [dict(row, worst_probe_relative_rmse=row["worst_probe_against_own_converged"]) for row in baker_rows]
    baker_noise_at = time_to_target(noise_rows, args.target, "rays")
    cycles_at = time_to_target(cycles_rows, args.target, "spp")
    result = {
        "scene": args.scene, "probes": probes, "threads": args.threads, "target_relative_rmse": args.target,
        "reference": {"file": os.path.relpath(reference_path, ROOT), "cycles_bounces": args.cycles_bounces,
                      "pixel_bias_removed_for_the_baker": bias and {
                          "per_probe": bias, "res": reference["renderer"]["res"],
                          "cells": reference_pixel_bias.CELLS, "supersample": reference_pixel_bias.SUPERSAMPLE},
                      "spp_total": setting["spp_total"], "seed_to_seed_max_rel_diff": setting["seed_to_seed_max_rel_diff"]},
        "baker": {"rows": baker_rows, "at_target": baker_at, "seeds": args.seeds, "converged_rays": args.converged_rays,
                  "at_target_against_own_converged": baker_noise_at},
        "cycles": {"rows": cycles_rows, "at_target": cycles_at, "seeds": args.cycles_seeds},
        "speedup_at_target": speedup(cycles_at, baker_at),
        "speedup_at_target_noise_alone": speedup(cycles_at, baker_noise_at),
    }
    print("%s, %d threads, worst probe's relative irradiance RMSE (RMS over seeds) against %s" %
          (args.scene, args.threads, result["reference"]["file"]))
    for name, rows, key in (("baker", baker_rows, "rays"), ("Cycles", cycles_rows, "spp")):
        for row in rows:
            own = row.get("worst_probe_against_own_converged")
            print("  %-6s %-5s %7d  worst %.4f%s  %.3g s per probe" %
                  (name, key, row[key], row["worst_probe_relative_rmse"],
                   "" if own is None else " (%.4f against its own converged)" % own, row["seconds_per_probe"]))
    for name, at in (("baker", baker_at), ("baker, noise alone", baker_noise_at), ("Cycles", cycles_at)):
        print("  %s at %.1f %%: %s" % (name, 100 * args.target, "not reached" if at is None else "%.3g s per probe%s" % (
            at["seconds_per_probe"], "" if at["interpolated"] else " or less (its smallest setting reaches it)")))
    for label, key in (("", "speedup_at_target"), (" (the baker's noise alone)", "speedup_at_target_noise_alone")):
        print("  Cycles' time / the baker's%s: %s" % (label, "not bracketed by the settings" if result[key] is None
                                                        else "%.0f" % result[key]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
