#!/usr/bin/env python3
"""How far `baker probe` lands from Cycles reference irradiance, over independent seeds.

    scripts/reference_misses.py [REF.json ...] [--baker build/baker] [--rays R] [--seeds 1,2,3,4]
        [--setting 0|2|all] [--json OUT.json] [--quiet] [-- EXTRA BAKER ARGS ...]

REF.json is an assembled reference (the format of ../shared/data/reference/*.json and
tests/reference/*.json: probes, and per setting the Cycles irradiance for the six axis normals).
By default every such file is read. For each setting (Cycles bounces n, the baker's n + 1), the
baker runs once per seed:

    BAKER probe SCENE --at P ... --json --no direct-punctual --bounces n+1 --rays R --seed S [--env ...]

and every probe, axis and channel is compared, `irradiance_from_samples` against the reference.
The scale of an entry is S = |E| + ½·(the probe's mean E over the six axes, that channel), so that
the acceptance band of the issue, 2 % of |E| + 1 % of the mean, is 2 % of S. Per entry it reports:

    miss      (mean over seeds − E) / S
    worst     the largest |single seed − E| / S
    se        standard error of the mean over seeds / S
    pass      |mean − E| ≤ 0.02·S + 3·se·S and se < 0.01

and per setting the worst entries, the ratio of the seed spread to the actual error, and the
variance per ray R·Var(one seed)/S² (the noise a single ray adds, comparable across ray counts).
Exit status: 0 every entry passes, 1 some entry fails, 2 the comparison could not be made.
"""
import argparse
import glob
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))
AXES = ["+x", "-x", "+y", "-y", "+z", "-z"]


def scene_path(ref):
    for d in (os.path.join(ROOT, "data", ref["scene"]), os.path.join(SHARED, "data", "scenes", ref["scene"])):
        p = os.path.join(d, ref["gltf"])
        if os.path.isfile(p):
            return p
    raise SystemExit("reference_misses.py: scene %s (%s) not found in data/ or ../shared/data/scenes" %
                     (ref["scene"], ref["gltf"]))


def env_args(ref):
    env = ref.get("env_settings") or None
    if not ref.get("env") and not env:
        bg = ref.get("background") or [0, 0, 0]
        return ["--sky", ",".join(repr(float(x)) for x in bg)] if any(bg) else []
    name = (env or {}).get("file") or ref["env"]
    path = os.path.join(SHARED, "data", "hdri", name)
    if not os.path.isfile(path):  # one of the project's own maps: data/<its name>/
        path = os.path.join(ROOT, "data", os.path.splitext(name)[0], name)
    return ["--env", path, "--env-intensity", repr(float((env or {}).get("strength", 1.0))),
            "--env-rotation", repr(float((env or {}).get("rotation_deg", 0.0)))]


def run_probe(baker, ref, setting, rays, seed, extra):
    """One `baker probe` run of every probe; rays None: the baker's default."""
    cmd = [baker, "probe", scene_path(ref)]
    cmd += ["--at=" + ",".join(repr(float(x)) for x in p) for p in ref["probes"]]
    cmd += ["--json", "--no", "direct-punctual", "--bounces", str(setting["baker_bounces"]), "--seed", str(seed)]
    cmd += (["--rays", str(rays)] if rays else []) + env_args(ref) + extra
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if r.returncode != 0:
        raise SystemExit("reference_misses.py: %s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stderr[-2000:]))
    out = json.loads(r.stdout)
    return [{a: p["irradiance_from_samples"][a.upper()] for a in AXES} for p in out["probes"]], out["ray_counts"]


def compare(ref, setting, runs, rays):
    entries = []
    for i, expected in enumerate(setting["irradiance_axes"]):
        for c in range(3):
            mean_e = sum(expected[a][c] for a in AXES) / 6.0
            for a in AXES:
                e = expected[a][c]
                scale = abs(e) + 0.5 * mean_e
                if scale <= 0:
                    continue
                values = [run[i][a][c] for run in runs]
                m = statistics.fmean(values)
                sd = statistics.stdev(values) if len(values) > 1 else 0.0
                se = sd / math.sqrt(len(values))
                entries.append({
                    "probe": i, "axis": a, "channel": "rgb"[c], "reference": e, "scale": scale, "mean": m,
                    "miss": (m - e) / scale, "worst_seed_miss": max(abs(v - e) for v in values) / scale,
                    "standard_error": se / scale, "seed_spread": sd / scale,
                    "variance_per_ray": rays * sd * sd / (scale * scale),
                    "pass": abs(m - e) <= 0.02 * scale + 3.0 * se and se < 0.01 * scale})
    return entries


def summary(entries):
    worst = max(entries, key=lambda e: abs(e["miss"]))
    ratios = [e["seed_spread"] / abs(e["miss"]) for e in entries if abs(e["miss"]) > 0.02]
    return {"entries": len(entries), "failing": sum(not e["pass"] for e in entries),
            "worst_miss": worst["miss"], "worst_entry": "probe %d E(%s) %s" % (worst["probe"], worst["axis"],
                                                                              worst["channel"]),
            "worst_single_seed_miss": max(e["worst_seed_miss"] for e in entries),
            "entries_beyond_5_percent_single_seed": sum(e["worst_seed_miss"] > 0.05 for e in entries),
            "max_standard_error": max(e["standard_error"] for e in entries),
            "median_spread_over_error_where_error_above_2_percent": statistics.median(ratios) if ratios else None,
            "max_variance_per_ray": max(e["variance_per_ray"] for e in entries),
            "median_variance_per_ray": statistics.median(e["variance_per_ray"] for e in entries)}


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("refs", nargs="*")
    ap.add_argument("--baker", default=os.path.join(ROOT, "build", "baker"))
    ap.add_argument("--rays", type=int, default=None, help="rays per probe (default: the baker's default)")
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--setting", default="all", help="Cycles bounces of the setting to check, or all")
    ap.add_argument("--json", dest="json_out")
    ap.add_argument("--quiet", action="store_true", help="print the summaries only")
    ap.add_argument("--markdown", metavar="OUT.md", help="also write the summaries as a Markdown table")
    args = ap.parse_args(argv)
    refs = args.refs or sorted(glob.glob(os.path.join(SHARED, "data", "reference", "*.json")) +
                               glob.glob(os.path.join(ROOT, "tests", "reference", "*.json")))
    if not refs:
        print("reference_misses.py: no reference files (../shared/data/reference/ is absent)", file=sys.stderr)
        return 2
    seeds = [int(s) for s in args.seeds.split(",")]
    report, failing = [], 0
    for path in refs:
        with open(path) as f:
            ref = json.load(f)
        for setting in ref["settings"]:
            if args.setting != "all" and int(args.setting) != setting["cycles_bounces"]:
                continue
            runs, counts = [], None
            for s in seeds:
                run, counts = run_probe(args.baker, ref, setting, args.rays, s, extra)
                runs.append(run)
            rays = args.rays or counts["probe"] // len(ref["probes"])
            entries = compare(ref, setting, runs, rays)
            s = summary(entries)
            # Named by the reference file: one scene may have several (sunlit_yard, sunlit_yard_low_sun).
            name = os.path.splitext(os.path.basename(path))[0]
            s.update({"scene": ref["scene"], "reference": name, "baker_bounces": setting["baker_bounces"], "rays": rays,
                      "seeds": seeds, "rays_traced_per_probe": counts["total"] / len(ref["probes"])})
            failing += s["failing"]
            report.append({"summary": s, "entries": entries})
            print("%-20s b%d  R=%-7d worst mean miss %+6.1f %% (%s), worst single seed %5.1f %%, >5 %%: %d/%d, "
                  "fail %d, max se %.2f %%, spread/error %s, var/ray max %.3g median %.3g" % (
                      name, setting["baker_bounces"], rays, 100 * s["worst_miss"], s["worst_entry"],
                      100 * s["worst_single_seed_miss"], s["entries_beyond_5_percent_single_seed"], s["entries"],
                      s["failing"], 100 * s["max_standard_error"],
                      "%.3f" % s["median_spread_over_error_where_error_above_2_percent"]
                      if s["median_spread_over_error_where_error_above_2_percent"] is not None else "-",
                      s["max_variance_per_ray"], s["median_variance_per_ray"]))
            if not args.quiet:
                for e in entries:
                    if not e["pass"]:
                        print("    probe %d E(%s) %s: ref %.5g mean %.5g miss %+.2f %% se %.2f %%" % (
                            e["probe"], e["axis"], e["channel"], e["reference"], e["mean"], 100 * e["miss"],
                            100 * e["standard_error"]))
            sys.stdout.flush()
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write("| reference | reflections | rays | seeds | worst single-seed miss | entries beyond 5 % (one seed) | "
                    "worst miss of the mean | max standard error | variance per ray, max / median | "
                    "rays traced per probe |\n|---|---|---|---|---|---|---|---|---|---|\n")
            for r in report:
                s = r["summary"]
                f.write("| %s | %d | %d | %d | %.1f %% | %d / %d | %+.1f %% | %.2f %% | %.3g / %.3g | %.0f |\n" % (
                    s["reference"], s["baker_bounces"], s["rays"], len(s["seeds"]), 100 * s["worst_single_seed_miss"],
                    s["entries_beyond_5_percent_single_seed"], s["entries"], 100 * s["worst_miss"],
                    100 * s["max_standard_error"], s["max_variance_per_ray"], s["median_variance_per_ray"],
                    s["rays_traced_per_probe"]))
    if args.json_out:
        with open(args.json_out, "w") as f:
            json.dump(report, f, indent=1)
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
