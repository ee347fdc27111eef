#!/usr/bin/env python3
"""Regenerates docs/bases/report.md: every basis scored by `baker bases --signal` on radiance,
irradiance and self-occlusion with RMAE, RMSE and SSIM (docs/BASES.md), and the thesis' findings
checked against the numbers. Needs ../shared/data (the paper's light probes, the shared HDRs and
scenes). A few minutes on 2 cores.

    python3 scripts/bases_report.py
"""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(ROOT, "..", "shared", "data")
BAKER = os.path.join(ROOT, "build", "baker")
# Linear SG with the thesis' coefficient counts (4, 9, 16, 25, 36, 49 per channel), beside every
# registered basis, so that SG and SH compare at equal storage.
EXTRA_SG = ["sg-4", "sg-25", "sg-36", "sg-49"]
SH_BY_COUNT = {4: "sh-l1", 9: "sh-l2", 16: "sh-l3", 25: "sh-l4", 36: "sh-l5", 49: "sh-l6"}


def baker(args):
    return json.loads(subprocess.run([BAKER] + args + ["--json"], check=True, capture_output=True, text=True).stdout)


def inputs(signal):
    if signal == "occlusion":
        scenes = [os.path.join(ROOT, "data", s, s + ".gltf") for s in ("sunlit_yard", "window_room", "default_room")]
        scenes += [os.path.join(SHARED, "scenes", s, s + ".gltf") for s in ("two_rooms", "alpha_fence", "sun_ground", "cornell_box")]
        return scenes
    probes = [os.path.join(SHARED, "probes", p) for p in ("ennis.hdr", "grace.hdr")]
    hdri = sorted(os.path.join(SHARED, "hdri", f) for f in os.listdir(os.path.join(SHARED, "hdri")) if f.endswith(".hdr"))
    return probes + hdri


def main():
    if not os.path.isdir(SHARED):
        sys.exit("scripts/bases_report.py needs ../shared/data beside the checkout")
    names = [b["name"] for b in baker(["bases"])["bases"]] + EXTRA_SG
    basis_args = [a for n in names for a in ("--basis", n)]
    results = {}
    for signal in ("radiance", "irradiance", "occlusion"):
        for metric in ("rmae", "rmse", "ssim"):
            results[(signal, metric)] = baker(["bases", "--signal", signal, "--metric", metric] + basis_args + inputs(signal))
    write(results, names)


def cell(score):
    return "{:.4g} ± {:.2g}".format(score["mean"], score["standard_deviation"])


def table(results, signal, names):
    lines = ["| basis | bytes | RMAE linear | RMAE non-negative | RMSE linear | RMSE non-negative | SSIM linear | SSIM non-negative |",
             "|---|---|---|---|---|---|---|---|"]
    for name in names:
        row = ["`{}`".format(name), ""]
        for metric in ("rmae", "rmse", "ssim"):
            scores = {s["fit"]: s for s in results[(signal, metric)]["scores"] if s["basis"] == name}
            row[1] = str(scores["linear"]["bytes_per_probe"])
            row += [cell(scores["linear"]), cell(scores["non_negative"]) if "non_negative" in scores else "—"]
        lines.append("| " + " | ".join(row) + " |")
    return lines


def linear(results, signal, metric, name):
    return next(s for s in results[(signal, metric)]["scores"] if s["basis"] == name and s["fit"] == "linear")["mean"]


def findings(results):
    lines = []
    for signal in ("radiance", "occlusion", "irradiance"):
        wins, pairs = 0, []
        for count, sh in SH_BY_COUNT.items():
            sg = "sg-{}".format(count)
            a, b = linear(results, signal, "rmae", sg), linear(results, signal, "rmae", sh)
            wins += a < b
            pairs.append("{} {:.4g} vs {} {:.4g}".format(sg, a, sh, b))
        lines.append("- **SG against SH at equal storage, {}** (RMAE, linear fits): SG lower in {} of {} pairs ({}).".format(
            signal, wins, len(SH_BY_COUNT), "; ".join(pairs)))
    for family, members in (("SH", list(SH_BY_COUNT.values())), ("SG", ["sg-{}".format(c) for c in SH_BY_COUNT])):
        values = [linear(results, "radiance", "rmae", m) for m in members]
        rises = sum(b > a for a, b in zip(values, values[1:]))
        lines.append("- **Radiance RMAE against storage, {}** ({}): {}; it rises in {} of {} steps.".format(
            family, " → ".join(members), " → ".join("{:.4g}".format(v) for v in values), rises, len(values) - 1))
    return lines


def write(results, names):
    first = results[("radiance", "rmae")]
    occlusion = results[("occlusion", "rmae")]
    out = [
        "# Every basis on radiance, irradiance and self-occlusion",
        "",
        "Made by `scripts/bases_report.py` with `baker bases --signal S --metric M` ({} on {} cores). What",
        "each signal, fit and metric is: [BASES.md](../BASES.md#every-basis-on-three-kinds-of-signal-baker-bases---signal).",
        "Mean ± standard deviation over the signals; bytes per probe at 32-bit floats (RGB; occlusion stores",
        "one channel, a third of it for RGB bases). SG bases use the project's sharpness per lobe count",
        "(`baker bases`), not the thesis' λ = n/k: broad lobes chosen to reproduce low SH bands, which a",
        "linear fit combines with signed coefficients; restricted to non-negative ones they fit far worse",
        "(irradiance RMAE of `sg-9`: {:.3g} linear, {:.3g} non-negative), where the narrower Ambient Dice lobes lose little.".format(
            *[s["mean"] for s in results[("irradiance", "rmae")]["scores"] if s["basis"] == "sg-9"]),
        "",
        "Radiance and irradiance signals: {}.".format(", ".join("`{}`".format(os.path.basename(s)) for s in first["signals"])),
        "",
        "Occlusion signals ({}): {}.".format(len(occlusion["signals"]), "; ".join(
            "`{}`".format(os.path.relpath(s, ROOT).replace("../shared/data/", "shared: ")) for s in occlusion["signals"])),
        "",
        "Left out, not partly occluded: {}.".format("; ".join(
            "`{}`".format(os.path.relpath(s, ROOT).replace("../shared/data/", "shared: ")) for s in occlusion["left_out"]) or "none"),
        "",
        "## What the thesis found, checked",
        "",
    ]
    out[2] = out[2].format(subprocess.run([BAKER, "--version"], capture_output=True, text=True).stdout.split("\n")[0],
                           os.cpu_count())
    out += findings(results)
    for signal in ("radiance", "irradiance", "occlusion"):
        out += ["", "## {}".format(signal.capitalize()), ""] + table(results, signal, names)
    path = os.path.join(ROOT, "docs", "bases", "report.md")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(path + ".tmp", path)
    print("wrote", path)


if __name__ == "__main__":
    main()
