#!/usr/bin/env python3
"""Regenerates docs/leaks/report.md: irradiance sampled beside walls, trilinear against leak-aware
(`baker sample --leak-aware`), each against the point's own traced irradiance (`baker probe` at the
point, 8192 rays). Scenes: the shipped thin walls (a quarter, a half and one probe spacing thick,
data/thin_walls, light on one side only) and ../shared/data/scenes/two_rooms when it is there.
Errors are given as a share of the lit side's level at the mirrored point. Then whole views of
each wall from both sides (`baker render`), their pictures written beside the report.

    python3 scripts/leak_report.py [--baker build/baker]
"""
import argparse
import json
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "leaks" / "render"
SHARED = ROOT.parent / "shared" / "data" / "scenes" / "two_rooms" / "two_rooms.gltf"
REFERENCE_RAYS = 8192


def run(baker, *args):
    result = subprocess.run([baker, *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed: {result.stderr}")
    return result.stdout


def sample(baker, volume, at, normal, leak_aware):
    args = ["sample", volume, "--at=" + ",".join(map(str, at)), "--normal=" + ",".join(map(str, normal)), "--json"]
    out = json.loads(run(baker, *args, *(["--leak-aware"] if leak_aware else [])))
    return sum(out["irradiance"]) / 3.0


AXES = {(1, 0, 0): "+X", (-1, 0, 0): "-X", (0, 1, 0): "+Y"}


def traced(baker, scene, bake_args, at, normal):
    out = json.loads(run(baker, "probe", scene, *bake_args, "--rays", str(REFERENCE_RAYS),
                         "--at=" + ",".join(map(str, at)), "--json"))
    return sum(out["probes"][0]["irradiance_from_samples"][AXES[normal]]) / 3.0


def measure(baker, scene, bake_args, points, work):
    volume = str(work / (Path(scene).stem + ".vdb"))
    run(baker, scene, *bake_args, "--rays", "256", "--out", volume, "--quiet")
    rows = []
    for at, normal in points:
        mirror, mirrored = (-at[0], at[1], at[2]), (-normal[0], normal[1], normal[2])
        lit = traced(baker, scene, bake_args, mirror, mirrored)
        truth = traced(baker, scene, bake_args, at, normal)
        plain, aware = sample(baker, volume, at, normal, False), sample(baker, volume, at, normal, True)
        lit_plain, lit_aware = sample(baker, volume, mirror, mirrored, False), sample(baker, volume, mirror, mirrored, True)
        rows.append((at, normal, lit, truth, (plain - truth) / lit, (aware - truth) / lit,
                     (lit_plain - lit) / lit, (lit_aware - lit) / lit))
    return rows


RENDER_RAYS = 512
RENDER_KEYS = ("mean_error_of_level", "p95_error_of_level", "dark_blotch_share", "leak_share", "seam_share",
               "largest_step_of_level")


def render(baker, scene, bake_args, volume, eye, look_at, out, level=None):
    args = ["render", scene, *bake_args, "--rays", str(RENDER_RAYS), "--volume", volume, "--eye=" + eye,
            "--look-at=" + look_at, "--out", str(out), "--json", "--quiet"]
    return json.loads(run(baker, *args, *(["--level", repr(level)] if level else [])))


def views(baker, scene, bake_args, name, eye, look_at, work):
    """The lit side and the dark side, each looking at the wall; the dark side's errors are shares
    of the lit view's level (no light of its own reaches it)."""
    volume = str(work / (Path(scene).stem + ".vdb"))
    rows = []
    lit = render(baker, scene, bake_args, volume, eye, look_at, IMAGES / f"{name}_lit.png")
    dark_eye = ",".join(str(-float(c)) if i == 0 else c for i, c in enumerate(eye.split(",")))
    dark_look = ",".join(str(-float(c)) if i == 0 else c for i, c in enumerate(look_at.split(",")))
    dark = render(baker, scene, bake_args, volume, dark_eye, dark_look, IMAGES / f"{name}_dark.png", lit["level"])
    for side, view in (("lit", lit), ("dark", dark)):
        for reading in ("trilinear", "leak_aware"):
            e = view["errors"][reading]
            rows.append(f"| {name} | [{side}](render/{name}_{side}.png) | {reading.replace('_', '-')} | "
                        + " | ".join(f"{e[k]:.1%}" if k != "seam_share" else f"{e[k]:.2%}" for k in RENDER_KEYS) + " |")
    pictures = [f"**{name}, {side} side**\n\n![{name}, {side} side: traced, trilinear, leak-aware](render/{name}_{side}.png)"
                for side in ("lit", "dark")]
    return rows, pictures


def table(rows):
    lines = ["| dark-side point | normal | lit level | truth | trilinear | leak-aware | lit side: trilinear | leak-aware |",
             "|---|---|---|---|---|---|---|---|"]
    for at, normal, lit, truth, plain, aware, lit_plain, lit_aware in rows:
        lines.append(f"| ({', '.join(f'{c:g}' for c in at)}) | {AXES[normal]} | {lit:.3f} | {truth:.4f} | "
                     f"{plain:+.1%} | {aware:+.2%} | {lit_plain:+.1%} | {lit_aware:+.1%} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--baker", default=str(ROOT / "build" / "baker"))
    baker = parser.parse_args().baker
    sections, view_rows, pictures = [], [], []
    IMAGES.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name, spacings in (("quarter", 0.25), ("half", 0.5), ("one", 1.0)):
            x = spacings * 0.5 / 2 + 0.02
            points = [((x, 1.25, 0.3), (1, 0, 0)), ((x, 0.6, -1.1), (1, 0, 0)), ((x, 2.0, 1.4), (1, 0, 0)),
                      ((x + 0.08, 0.0, 0.3), (0, 1, 0))]
            scene = str(ROOT / "data" / "thin_walls" / f"thin_wall_{name}.gltf")
            rows = measure(baker, scene, ["--spacing", "0.5"], points, work)
            if name != "one":
                rows_, pictures_ = views(baker, scene, ["--spacing", "0.5"], f"thin_wall_{name}", "-2.8,1.9,1.8",
                                         "0,0.9,-0.6", work)
                view_rows, pictures = view_rows + rows_, pictures + pictures_
            sections.append(f"### Wall {spacings:g} spacing thick (`data/thin_walls/thin_wall_{name}.gltf`, "
                            f"`--spacing 0.5`)\n\n{table(rows)}")
        if SHARED.exists():
            points = [((0.12, 1.5, 1.5), (1, 0, 0)), ((0.12, 0.8, -1.5), (1, 0, 0)), ((0.12, 2.5, 1.0), (1, 0, 0)),
                      ((0.15, 0.0, 1.5), (0, 1, 0))]
            rows = measure(baker, str(SHARED), [], points, work)
            rows_, pictures_ = views(baker, str(SHARED), [], "two_rooms", "-3.7,2.2,1.7", "0,0.9,-0.4", work)
            view_rows, pictures = view_rows + rows_, pictures + pictures_
            sections.append("### two_rooms (`../shared/data/scenes/two_rooms`, default spacing 0.5 m; the dark "
                            "room is lit through the doorway only)\n\n" + table(rows))
    report = f"""# Light through walls: trilinear against leak-aware sampling

Generated by `python3 scripts/leak_report.py`; the method is in [../LEAKS.md](../LEAKS.md).

Each row samples a volume baked at 256 rays per probe (sh-l2, the default distance map of 8 × 8)
at a point just beyond a wall, on the side the light does not reach directly, and compares it
with the point's own irradiance: `baker probe SCENE --at POINT --rays {REFERENCE_RAYS}`, the same
rays without any probe grid ("truth"). Errors are (sampled − truth) divided by the lit side's
level, the truth at the point mirrored through the wall (x → −x). The last two columns sample
that mirrored point on the lit side, against its truth: trilinear sampling darkens the lit side
along the wall as much as it lights the dark side.

{(chr(10) + chr(10)).join(sections)}

## Whole views (`baker render`)

Each wall seen from the lit side and, mirrored through it, from the dark side, 320 × 240 pixels
with a 60° field. Pictures, left to right: each pixel's own traced irradiance ({RENDER_RAYS} rays, the
reference), the volume read trilinearly, read leak-aware; one exposure. Errors are shares of the
lit view's level (its median traced E); columns as in [../COMMANDS.md](../COMMANDS.md#render):
mean and 95th percentile of the error, lit pixels read below half their value (dark blotches),
pixels read brighter by over a quarter of the level (leaks), and neighbouring pixels on one plane
whose readings step by over 2 % of the level and over three times the steps beside them (seams),
with the largest such step.

| scene | view | reading | mean | p95 | dark blotches | leaks | seams | largest step |
|---|---|---|---|---|---|---|---|---|
{chr(10).join(view_rows)}

{(chr(10) + chr(10)).join(pictures)}
"""
    out = ROOT / "docs" / "leaks" / "report.md"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(report)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
