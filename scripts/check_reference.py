#!/usr/bin/env python3
"""Compare `baker probe` irradiance with Blender Cycles reference irradiance.

    scripts/check_reference.py REF_DIR [SCENE] [--baker build/baker] [--bounces B]
        [--tolerance 0.02] [--negligible 0.01] [--json OUT.json] [-- EXTRA BAKER ARGS ...]

REF_DIR is what scripts/render_references.sh writes for one scene: either one directory holding
probes.json (../shared/tools/reference_probe.py) and irradiance.json (../shared/tools/panorama_sh.py
--json), or a directory of such directories (seed0/, seed1/, ...: same probes, independent seeds),
which are averaged (weighted by samples per pixel); their spread gives the reference noise (standard
error of the mean). If irradiance.json is missing but the panoramas are there, it is computed with
Blender + panorama_sh.py (needs `blender` on PATH and ../shared/tools).

SCENE defaults to ../shared/data/scenes/<name>/<name>.gltf for the scene named in probes.json.
The baker is run once for all probes:

    BAKER probe SCENE --at=x,y,z [--at=...] --json --no direct-punctual --bounces B [env args] [EXTRA]

B defaults to the reference's Cycles bounces + 1 (Cycles --bounces n allows n+1 diffuse
reflections). If the reference used an environment map and EXTRA has no --env/--sky, the script adds
--env <hdri-dir>/<file> --env-intensity S --env-rotation R from the reference settings (a constant
non-black --background becomes --sky r,g,b). Panoramas never see punctual lights directly, hence
--no direct-punctual.

For each probe and normal n in ±X, ±Y, ±Z it compares the baker's `irradiance_from_samples` (gated)
and `irradiance` (the basis reconstruction, reported; gated too with --gate both|basis) with the
reference E(n): relative error of the sum of r, g, b, and of each channel. Normals whose reference
sum is below --negligible times the probe's largest axis sum are reported but not gated; with
--channels, channels are gated too (a channel is negligible below --negligible times the probe's
largest value of that channel). Exit status: 0 all gated errors within --tolerance, 1 some error
beyond it (or a probe the baker reports invalid), 2 the comparison could not be made.

--probe-json FILE reads a saved `baker probe --json` output instead of running the baker.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AXES = ["+X", "-X", "+Y", "-Y", "+Z", "-Z"]
KEY_SAMPLES = "irradiance_from_samples"
KEY_BASIS = "irradiance"


class Failure(Exception):
    """The comparison cannot be made (exit 2)."""


def rel(path):
    """A default path given relative to the repository root."""
    return os.path.normpath(os.path.join(ROOT, path))


def fmt_vec(v):
    return ",".join(repr(float(x)) for x in v)


# ----------------------------------------------------------------------------- reference
def reference_sets(ref_dir):
    if os.path.isfile(os.path.join(ref_dir, "probes.json")):
        return [ref_dir]
    if not os.path.isdir(ref_dir):
        raise Failure("%s: no such directory" % ref_dir)
    subs = sorted(os.path.join(ref_dir, d) for d in os.listdir(ref_dir)
                  if os.path.isfile(os.path.join(ref_dir, d, "probes.json")))
    if not subs:
        raise Failure("%s: no probes.json in it or in any subdirectory (render with scripts/render_references.sh)"
                      % ref_dir)
    return subs


def compute_irradiance(d, tools_dir):
    """Run panorama_sh.py on a reference directory that has panoramas but no irradiance.json."""
    blender = shutil.which("blender")
    script = os.path.join(tools_dir, "panorama_sh.py")
    if blender is None or not os.path.isfile(script):
        raise Failure("%s: no irradiance.json, and it cannot be computed (%s)" % (
            d, "blender not on PATH" if blender is None else "no " + script))
    out = os.path.join(d, "irradiance.json")
    env = dict(os.environ)
    env["PATH"] = "/usr/bin" + os.pathsep + env.get("PATH", "")   # Blender needs Debian's python3 (NumPy)
    print("computing %s with panorama_sh.py" % out, file=sys.stderr)
    r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "3", "--python", script,
                        "--", d, "--json", out], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    if r.returncode != 0 or not os.path.isfile(out):
        raise Failure("panorama_sh.py failed on %s:\n%s" % (d, r.stdout[-2000:]))


def load_set(d, tools_dir):
    with open(os.path.join(d, "probes.json")) as f:
        meta = json.load(f)
    irr_path = os.path.join(d, "irradiance.json")
    if not os.path.isfile(irr_path):
        compute_irradiance(d, tools_dir)
    with open(irr_path) as f:
        irr = json.load(f)
    if isinstance(irr, dict):
        irr = [irr]
    by_file = {e["file"]: e["irradiance_axes"] for e in irr}
    probes = []
    for p in meta["probes"]:
        if p["file"] not in by_file:
            raise Failure("%s: %s has no entry for %s" % (d, irr_path, p["file"]))
        axes = by_file[p["file"]]
        probes.append({"position": [float(x) for x in p["position_gltf"]],
                       "E": {a: [float(x) for x in axes[a]] for a in AXES},
                       "seconds": p.get("seconds")})
    return {"dir": d, "meta": meta, "settings": meta.get("settings", {}), "probes": probes}


def load_reference(ref_dir, tools_dir):
    sets = [load_set(d, tools_dir) for d in reference_sets(ref_dir)]
    first = sets[0]
    comparable = ("width", "height", "bounces", "lighting_mode", "shading", "albedo", "backface", "spot_model",
                  "light_radius", "sun_angle_deg", "env", "env_strength", "env_rotation_deg", "background",
                  "transparent_bounces", "filter_width")
    for s in sets[1:]:
        if s["meta"].get("scene") != first["meta"].get("scene"):
            raise Failure("%s and %s are different scenes" % (first["dir"], s["dir"]))
        if len(s["probes"]) != len(first["probes"]) or any(
                max(abs(a - b) for a, b in zip(p["position"], q["position"])) > 1e-9
                for p, q in zip(s["probes"], first["probes"])):
            raise Failure("%s and %s have different probe positions" % (first["dir"], s["dir"]))
        for k in comparable:
            if s["settings"].get(k) != first["settings"].get(k):
                raise Failure("%s and %s differ in %s (%r vs %r)" % (
                    first["dir"], s["dir"], k, first["settings"].get(k), s["settings"].get(k)))
        if s["settings"].get("seed") == first["settings"].get("seed"):
            print("warning: %s and %s use the same seed; their spread is not a noise estimate"
                  % (first["dir"], s["dir"]), file=sys.stderr)
    weights = [float(s["settings"].get("spp", 1)) for s in sets]
    wsum = sum(weights)
    probes = []
    for i, p0 in enumerate(first["probes"]):
        E, noise = {}, {}
        for a in AXES:
            vals = [s["probes"][i]["E"][a] for s in sets]
            mean = [sum(w * v[c] for w, v in zip(weights, vals)) / wsum for c in range(3)]
            E[a] = mean
            if len(sets) > 1:
                # standard error of the (weighted) mean from the spread of the sets, per channel and for the sum
                def sem(xs):
                    m = sum(w * x for w, x in zip(weights, xs)) / wsum
                    var = sum(w * (x - m) ** 2 for w, x in zip(weights, xs)) / wsum * len(xs) / (len(xs) - 1)
                    return math.sqrt(var * sum(w * w for w in weights) / (wsum * wsum))
                noise[a] = {"rgb": [sem([v[c] for v in vals]) for c in range(3)], "sum": sem([sum(v) for v in vals])}
        probes.append({"position": p0["position"], "E": E, "noise": noise or None,
                       "seconds": [s["probes"][i]["seconds"] for s in sets]})
    settings = dict(first["settings"])
    settings["spp_total"] = int(wsum)
    settings["seeds"] = [s["settings"].get("seed") for s in sets]
    return {"dirs": [s["dir"] for s in sets], "scene": first["meta"].get("scene"), "settings": settings,
            "probes": probes}


# ----------------------------------------------------------------------------- baker
def baker_command(args, ref, scene, extra):
    st = ref["settings"]
    if any(x.split("=", 1)[0] in ("--bounces", "--at", "--json") for x in extra):
        raise Failure("give --bounces to check_reference.py itself; --at and --json are set from the reference")
    bounces = args.bounces if args.bounces is not None else int(st.get("bounces", 0)) + 1
    cmd = [args.baker, "probe", scene]
    cmd += ["--at=" + fmt_vec(p["position"]) for p in ref["probes"]]
    cmd += ["--json", "--no", "direct-punctual", "--bounces", str(bounces)]
    has_light_arg = any(x.split("=", 1)[0] in ("--env", "--sky") for x in extra)
    if st.get("env") and not has_light_arg:
        env_path = os.path.join(args.hdri_dir, st["env"])
        if not os.path.isfile(env_path):
            raise Failure("the reference was lit by %s, not found in %s: pass --hdri-dir or `-- --env FILE`"
                          % (st["env"], args.hdri_dir))
        cmd += ["--env", env_path, "--env-intensity", repr(float(st.get("env_strength", 1.0))),
                "--env-rotation", repr(float(st.get("env_rotation_deg", 0.0)))]
    elif not st.get("env") and st.get("background") and any(st["background"]) and not has_light_arg:
        cmd += ["--sky", fmt_vec(st["background"])]
    if st.get("lighting_mode", "COMPAT") != "COMPAT":
        print("warning: the reference used --lighting-mode %s; the baker uses glTF numbers as they are"
              % st["lighting_mode"], file=sys.stderr)
    return cmd + extra, bounces


def parse_probe_json(text, source):
    try:
        return json.loads(text)
    except ValueError:
        start, end = text.find("{"), text.rfind("}")
        if start >= 0 and end > start:
            try:
                return json.loads(text[start:end + 1])
            except ValueError:
                pass
    raise Failure("%s: output is not JSON:\n%s" % (source, text[:2000]))


def run_baker(cmd):
    if not (os.path.isfile(cmd[0]) and os.access(cmd[0], os.X_OK)) and shutil.which(cmd[0]) is None:
        raise Failure("baker binary %s not found (build it, or pass --baker)" % cmd[0])
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if r.stderr.strip():
        sys.stderr.write(r.stderr if r.stderr.endswith("\n") else r.stderr + "\n")
    if r.returncode != 0:
        raise Failure("baker exited with %d: %s" % (r.returncode, " ".join(cmd)))
    return parse_probe_json(r.stdout, "baker probe")


# ----------------------------------------------------------------------------- comparison
def rel_err(b, r):
    if r == 0.0:
        return 0.0 if b == 0.0 else math.copysign(math.inf, b)
    return (b - r) / r


def compare(ref, out, args):
    bp = out.get("probes")
    if not isinstance(bp, list):
        raise Failure("baker JSON has no \"probes\" list")
    if len(bp) != len(ref["probes"]):
        raise Failure("baker returned %d probes, the reference has %d" % (len(bp), len(ref["probes"])))
    gate_keys = {"samples": [KEY_SAMPLES], "basis": [KEY_BASIS], "both": [KEY_SAMPLES, KEY_BASIS]}[args.gate]
    result, problems = [], []
    worst = {KEY_SAMPLES: None, KEY_BASIS: None, "channel": None}

    def note_worst(key, val, where):
        if val is not None and (worst[key] is None or abs(val) > abs(worst[key][0])):
            worst[key] = (val, where)

    for i, (rp, p) in enumerate(zip(ref["probes"], bp)):
        pos = p.get("position")
        if pos is None or max(abs(a - b) for a, b in zip(pos, rp["position"])) > 1e-4:
            raise Failure("baker probe %d is at %s, the reference probe at %s" % (i, pos, rp["position"]))
        valid = bool(p.get("valid", True))
        bpos = p.get("baked_position")
        if bpos is not None and max(abs(a - b) for a, b in zip(bpos, rp["position"])) > 1e-6:
            print("note: probe %d was baked at %s, not at %s" % (i, fmt_vec(bpos), fmt_vec(rp["position"])),
                  file=sys.stderr)
        if not valid:
            problems.append("probe %d at %s: the baker reports it invalid" % (i, fmt_vec(rp["position"])))
        for key in (KEY_SAMPLES, KEY_BASIS):
            if not isinstance(p.get(key), dict) or any(a not in p[key] for a in AXES):
                raise Failure("baker probe %d has no \"%s\" with keys %s" % (i, key, " ".join(AXES)))
        max_sum = max(sum(rp["E"][a]) for a in AXES)
        max_ch = [max(rp["E"][a][c] for a in AXES) for c in range(3)]
        axes = {}
        for a in AXES:
            r = rp["E"][a]
            rs = sum(r)
            negl = not (rs > args.negligible * max_sum)
            e = {"reference": r, "reference_sum": rs, "negligible": negl}
            if rp["noise"]:
                e["reference_noise"] = rp["noise"][a]["rgb"]
                e["reference_noise_sum"] = rp["noise"][a]["sum"]
            for key in (KEY_SAMPLES, KEY_BASIS):
                b = [float(x) for x in p[key][a]]
                rel_rgb = [rel_err(b[c], r[c]) for c in range(3)]
                ch_negl = [not (r[c] > args.negligible * max_ch[c]) for c in range(3)]
                e[key] = {"rgb": b, "sum": sum(b), "rel_sum": rel_err(sum(b), rs), "rel_rgb": rel_rgb,
                          "channel_negligible": ch_negl}
                gated = key in gate_keys
                where = "probe %d %s (%s)" % (i, a, key)
                if not negl:
                    note_worst(key, e[key]["rel_sum"], where)
                    if gated and not abs(e[key]["rel_sum"]) <= args.tolerance:
                        problems.append("probe %d %s %s: sum rgb %.6g vs reference %.6g, rel. error %+.4f"
                                        % (i, a, key, sum(b), rs, e[key]["rel_sum"]))
                for c in range(3):
                    if ch_negl[c]:
                        continue
                    if gated:
                        note_worst("channel", rel_rgb[c], "probe %d %s %s (%s)" % (i, a, "rgb"[c], key))
                    if gated and args.channels and not abs(rel_rgb[c]) <= args.tolerance:
                        problems.append("probe %d %s %s channel %s: %.6g vs reference %.6g, rel. error %+.4f"
                                        % (i, a, key, "rgb"[c], b[c], r[c], rel_rgb[c]))
            if rp["noise"] and not negl and rs > 0 and rp["noise"][a]["sum"] / rs > args.tolerance / 3:
                print("warning: probe %d %s: reference noise %.2f%% is not small against the tolerance %.2f%%"
                      % (i, a, 100 * rp["noise"][a]["sum"] / rs, 100 * args.tolerance), file=sys.stderr)
            axes[a] = e
        result.append({"index": i, "position": rp["position"], "baked_position": p.get("baked_position"),
                       "valid": valid, "sky_visibility": p.get("sky_visibility"), "axes": axes})
    return result, problems, worst


def finite(x):
    """JSON has no infinities: a relative error against a zero reference becomes null."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite(v) for v in x]
    return x


def fmt_rel(x):
    if x is None:
        return "—"
    if math.isinf(x):
        return "inf"
    return "%+.2f%%" % (100 * x)


def markdown(scene_name, result, worst, args):
    lines = ["| scene | probe | normal | reference E (sum rgb) | ref. noise | baker E samples | rel. error "
             "| r / g / b rel. error | baker E basis | rel. error |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for p in result:
        label = "%d (%s)" % (p["index"], fmt_vec(p["position"]))
        if not p["valid"]:
            label += " INVALID"
        for a in AXES:
            e = p["axes"][a]
            s, b = e[KEY_SAMPLES], e[KEY_BASIS]
            noise = ("±%.2f%%" % (100 * e["reference_noise_sum"] / e["reference_sum"])
                     if "reference_noise_sum" in e and e["reference_sum"] > 0 else "—")
            mark = " (negligible)" if e["negligible"] else ""
            ch = " / ".join("(%s)" % fmt_rel(x) if n else fmt_rel(x)
                            for x, n in zip(s["rel_rgb"], s["channel_negligible"]))
            lines.append("| %s | %s | %s | %.6g%s | %s | %.6g | %s | %s | %.6g | %s |" % (
                scene_name, label, a, e["reference_sum"], mark, noise, s["sum"], fmt_rel(s["rel_sum"]), ch,
                b["sum"], fmt_rel(b["rel_sum"])))
    return "\n".join(lines)


# ----------------------------------------------------------------------------- main
def main(argv):
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(description="Compare `baker probe` irradiance with Cycles reference irradiance "
                                             "(see the module docstring).")
    ap.add_argument("ref_dir", help="reference directory (probes.json + irradiance.json, or seed subdirectories)")
    ap.add_argument("scene", nargs="?", help="glTF scene; default ../shared/data/scenes/<name>/<name>.gltf")
    ap.add_argument("--baker", default=rel("build/baker"), help="baker binary (default build/baker)")
    ap.add_argument("--bounces", type=int, help="baker --bounces (default: the reference's Cycles bounces + 1)")
    ap.add_argument("--tolerance", type=float, default=0.02, help="max |relative error| (default 0.02)")
    ap.add_argument("--negligible", type=float, default=0.01,
                    help="normals with reference E below this fraction of the probe's largest axis E are not "
                         "gated (default 0.01)")
    ap.add_argument("--gate", choices=["samples", "basis", "both"], default="samples",
                    help="which baker irradiance must meet the tolerance: irradiance_from_samples (default), "
                         "irradiance (basis reconstruction) or both")
    ap.add_argument("--channels", action="store_true", help="gate each channel too, not only the sum of r, g, b")
    ap.add_argument("--json", metavar="OUT", help="write the numbers as JSON")
    ap.add_argument("--hdri-dir", default=rel("../shared/data/hdri"),
                    help="where the reference's environment map is (default ../shared/data/hdri)")
    ap.add_argument("--tools-dir", default=rel("../shared/tools"),
                    help="reference tools, for computing a missing irradiance.json (default ../shared/tools)")
    ap.add_argument("--probe-json", metavar="FILE", help="use this saved `baker probe --json` output instead "
                                                          "of running the baker")
    ap.add_argument("--print-command", action="store_true", help="print the baker command and exit")
    args = ap.parse_args(argv)

    try:
        ref = load_reference(args.ref_dir, args.tools_dir)
        scene = args.scene
        if scene is None:
            name = ref["scene"]
            if not name:
                raise Failure("the reference has no scene (empty scene): give SCENE")
            stem = os.path.splitext(name)[0]
            scene = rel(os.path.join("../shared/data/scenes", stem, name))
        if not os.path.isfile(scene):
            raise Failure("scene %s not found" % scene)
        if ref["scene"] and os.path.basename(scene) != ref["scene"]:
            print("warning: the reference was rendered from %s, comparing with %s" % (ref["scene"], scene),
                  file=sys.stderr)
        cmd, bounces = baker_command(args, ref, scene, extra)
        if args.print_command:
            print(" ".join(cmd))
            return 0
        if args.probe_json:
            with open(args.probe_json) as f:
                out = parse_probe_json(f.read(), args.probe_json)
        else:
            print("running: " + " ".join(cmd), file=sys.stderr)
            out = run_baker(cmd)
        result, problems, worst = compare(ref, out, args)
    except Failure as e:
        print("check_reference.py: error: %s" % e, file=sys.stderr)
        return 2
    except (OSError, ValueError, KeyError) as e:
        print("check_reference.py: error: %s: %s" % (type(e).__name__, e), file=sys.stderr)
        return 2

    scene_name = os.path.splitext(os.path.basename(scene))[0]
    st = ref["settings"]
    print("Reference: %s (Cycles %s, %s, %d spp total, seeds %s, Cycles bounces %s; env %s x%s rot %s). "
          "Baker: bounces %d, rays %s, basis %s, seed %s." % (
              ", ".join(ref["dirs"]), st.get("blender"), "%sx%s" % (st.get("width"), st.get("height")),
              st["spp_total"], st["seeds"], st.get("bounces"), st.get("env"), st.get("env_strength"),
              st.get("env_rotation_deg"), bounces, out.get("rays"), out.get("basis"), out.get("seed")))
    if out.get("bounces") is not None and out.get("bounces") != bounces:
        problems.append("the baker reports bounces %s, asked for %d" % (out.get("bounces"), bounces))
    print()
    print(markdown(scene_name, result, worst, args))
    print()

    def w(key):
        return ("%s at %s" % (fmt_rel(worst[key][0]), worst[key][1])) if worst[key] else "—"
    passed = not problems
    print("Summary %s: max |rel. error| of sum rgb, irradiance_from_samples %s; irradiance (basis) %s; "
          "per channel (gated kind) %s; tolerance %.2f%% on %s%s -> %s" % (
              scene_name, w(KEY_SAMPLES), w(KEY_BASIS), w("channel"), 100 * args.tolerance, args.gate,
              " + channels" if args.channels else "", "PASS" if passed else "FAIL (%d)" % len(problems)))
    for msg in problems:
        print("  " + msg)

    if args.json:
        doc = {"scene": scene_name, "scene_path": scene, "reference_dirs": ref["dirs"],
               "reference_settings": st, "baker_command": cmd, "baker_bounces": bounces,
               "baker": {k: out.get(k) for k in ("scene", "basis", "rays", "bounces", "seed")},
               "tolerance": args.tolerance, "negligible": args.negligible, "gate": args.gate,
               "gate_channels": args.channels, "probes": result,
               "summary": {"max_rel_error_samples": worst[KEY_SAMPLES][0] if worst[KEY_SAMPLES] else None,
                           "max_rel_error_samples_at": worst[KEY_SAMPLES][1] if worst[KEY_SAMPLES] else None,
                           "max_rel_error_basis": worst[KEY_BASIS][0] if worst[KEY_BASIS] else None,
                           "max_rel_error_basis_at": worst[KEY_BASIS][1] if worst[KEY_BASIS] else None,
                           "max_rel_error_channel": worst["channel"][0] if worst["channel"] else None,
                           "max_rel_error_channel_at": worst["channel"][1] if worst["channel"] else None,
                           "problems": problems, "pass": passed}}
        with open(args.json, "w") as f:
            json.dump(finite(doc), f, indent=1)
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
