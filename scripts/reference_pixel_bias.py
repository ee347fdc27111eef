#!/usr/bin/env python3
"""How far a reference panorama's pixel integration is from the exact direct light of small emitters.

    scripts/reference_pixel_bias.py [--scene cornell_box] [--res WxH] [--cells 200] [--supersample 8]
        [--baker build/baker] [--rays 262144] [--seeds 4] [--cycles-spp 0] [--json OUT.json]

reference_probe.py renders each probe's panorama with a one-pixel box filter in (u, v), and
panorama_sh.py sums E(n) = sum over pixels of L * max(0, n.d) * dOmega with d at the pixel's
centre. A pixel's value is then its average over (u, v), not over solid angle: where an emitter's
edge crosses a pixel, the part nearer the pole counts for more than the solid angle it covers.
Around a bright emitter near a pole of the panorama (a ceiling light above a probe) every edge
pixel has the emitter on its pole side, so the sum comes out high.

For each probe of ../shared/data/reference/<scene>.json this script works out, for the six axis
normals, the irradiance the scene's emissive triangles send straight to the probe:
  exact      the integral over each emitter (a grid of --cells^2 sub-triangles per triangle, each
             seen or hidden by the scene's triangles from its centre): no sampling, no pixels;
  panorama   what that pipeline gives without any noise: each pixel at --res averaged over
             --supersample^2 points of its (u, v) rectangle, summed with its centre's cosine;
  baker      `baker probe --bounces 0` (direct light only) over --seeds seeds: mean and standard error;
  cycles     with --cycles-spp N > 0: reference_probe.py and panorama_sh.py themselves, on a copy of
             the scene whose surfaces reflect nothing (so only the emitters' direct light is left).
Values are r + g + b. Emitters follow the glTF file's sidedness (reference_probe.py renders back
faces too, a difference of its own for single-sided emitters). Scenes whose emitters are textured,
.glb files and buffers inside the file are refused. Needs ../shared beside the
checkout; Cycles needs `blender` (Debian: apt-get install blender python3-numpy). Exit 0 measured,
2 could not measure.
"""
import argparse
import json
import math
import os
import shutil
import struct
import tempfile

from probe_runs import ROOT, SHARED, baker_axes, cycles_axes, fail, require_blender

AXES = {"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0), "+z": (0, 0, 1), "-z": (0, 0, -1)}
CELLS = 200  # sub-triangles per emitter edge: the integral to better than 0.01 %
SUPERSAMPLE = 8  # points per pixel side: the sum within 0.05 % (facing the light) to 0.15 % (grazing) of 32


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def node_matrix(node):
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    t = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    s = node.get("scale", [1, 1, 1])
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]] for i in range(3)] + [[0, 0, 0, 1]]


def load_triangles(path):
    """World-space triangles as (a, b, c, emission rgb or None, double_sided), front counter-clockwise."""
    if not path.endswith(".gltf"):
        fail("%s: this check reads .gltf files with external buffers" % path)
    gltf = json.load(open(path))
    if any(b.get("uri", "data:").startswith("data:") for b in gltf["buffers"]):
        fail("%s: a buffer inside the file (data: URI); this check reads external buffers" % path)
    buffers = [open(os.path.join(os.path.dirname(path), b["uri"]), "rb").read() for b in gltf["buffers"]]

    def accessor(index):
        a = gltf["accessors"][index]
        view = gltf["bufferViews"][a["bufferView"]]
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
        fmt = {5126: "f", 5125: "I", 5123: "H", 5121: "B"}[a["componentType"]]
        stride = view.get("byteStride", width * struct.calcsize(fmt))
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        data = buffers[view["buffer"]]
        return [struct.unpack_from("<" + fmt * width, data, start + i * stride) for i in range(a["count"])]

    triangles = []

    def visit(index, parent):
        node = gltf["nodes"][index]
        world = mat_mul(parent, node_matrix(node))
        if "mesh" in node:
            # A mirroring transform turns counter-clockwise corners clockwise.
            det = sum(world[0][i] * (world[1][(i + 1) % 3] * world[2][(i + 2) % 3] -
                                     world[1][(i + 2) % 3] * world[2][(i + 1) % 3]) for i in range(3))
            for primitive in gltf["meshes"][node["mesh"]]["primitives"]:
                if primitive.get("mode", 4) != 4:
                    fail("%s: a primitive of mode %d; this check reads triangles (mode 4)" % (path, primitive["mode"]))
                material = gltf["materials"][primitive["material"]] if "material" in primitive else {}
                if "emissiveTexture" in material:
                    fail("%s: an emissive texture; this check handles emitters of one colour" % path)
                strength = material.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get(
                    "emissiveStrength", 1.0)
                emission = tuple(c * strength for c in material.get("emissiveFactor", [0, 0, 0]))
                points = [tuple(sum(world[r][k] * (list(p) + [1])[k] for k in range(4)) for r in range(3))
                          for p in accessor(primitive["attributes"]["POSITION"])]
                order = [i[0] for i in accessor(primitive["indices"])] if "indices" in primitive else range(len(points))
                order = list(order)
                for k in range(0, len(order), 3):
                    a, b, c = (points[order[k + i]] for i in ((0, 1, 2) if det > 0 else (0, 2, 1)))
                    triangles.append((a, b, c, emission if max(emission) > 0 else None,
                                      material.get("doubleSided", False)))
        for child in node.get("children", []):
            visit(child, world)

    identity = [[1 if r == c else 0 for c in range(4)] for r in range(4)]
    for root in gltf["scenes"][gltf.get("scene", 0)]["nodes"]:
        visit(root, identity)
    return triangles


class Scene:
    def __init__(self, triangles):
        self.triangles = [(t[0], sub(t[1], t[0]), sub(t[2], t[0]), t[3], t[4]) for t in triangles]
        self.emitters = [k for k, t in enumerate(self.triangles) if t[3] is not None]

    def hit(self, origin, direction, k):
        """Distance along the ray to triangle k, or None (Moller-Trumbore)."""
        v0, e1, e2 = self.triangles[k][:3]
        pv = cross(direction, e2)
        det = dot(e1, pv)
        if abs(det) < 1e-15:
            return None
        tv = sub(origin, v0)
        u = dot(tv, pv) / det
        if u < 0 or u > 1:
            return None
        qv = cross(tv, e1)
        v = dot(direction, qv) / det
        if v < 0 or u + v > 1:
            return None
        t = dot(e2, qv) / det
        return t if t > 1e-9 else None

    def closest(self, origin, direction, candidates=None):
        best, which = math.inf, None
        for k in candidates if candidates is not None else range(len(self.triangles)):
            t = self.hit(origin, direction, k)
            if t is not None and t < best:
                best, which = t, k
        return best, which

    def radiance(self, origin, direction, k):
        """Emission of triangle k seen along the ray (0 from the back of a single-sided emitter)."""
        v0, e1, e2, emission, double_sided = self.triangles[k]
        if emission is None:
            return None
        if not double_sided and dot(cross(e1, e2), direction) > 0:
            return None
        return emission


def exact_direct(scene, probe, cells):
    """E(n) from every emitter, integrated over sub-triangles with visibility from each centre."""
    totals = {axis: [0.0, 0.0, 0.0] for axis in AXES}
    for k in scene.emitters:
        v0, e1, e2, emission, double_sided = scene.triangles[k]
        normal = cross(e1, e2)
        area = 0.5 * math.sqrt(dot(normal, normal))
        unit = tuple(c / (2 * area) for c in normal)
        piece = area / (cells * cells)
        # The centroids of the cells^2 equal sub-triangles: upright ones at ((i, j) + 1/3) / cells,
        # i + j < cells, and the inverted ones beside them at ((i, j) + 2/3) / cells, i + j < cells - 1.
        centroids = [((i + 1 / 3) / cells, (j + 1 / 3) / cells) for i in range(cells) for j in range(cells - i)]
        centroids += [((i + 2 / 3) / cells, (j + 2 / 3) / cells) for i in range(cells) for j in range(cells - i - 1)]
        for a, b in centroids:
            point = tuple(v0[c] + a * e1[c] + b * e2[c] for c in range(3))
            d = sub(point, probe)
            r = math.sqrt(dot(d, d))
            direction = tuple(c / r for c in d)
            cos_light = -dot(unit, direction)
            if cos_light <= 0 and not double_sided:
                continue
            t, which = scene.closest(probe, direction)
            if which != k:
                continue
            weight = abs(cos_light) / (r * r) * piece
            for axis, n in AXES.items():
                c = max(0.0, dot(n, direction)) * weight
                for ch in range(3):
                    totals[axis][ch] += emission[ch] * c
    return totals


def panorama_direct(scene, probe, width, height, samples):
    """What a noiseless (u, v) box-filtered panorama and panorama_sh.py's sum make of the same light."""
    emitters = [scene.triangles[k] for k in scene.emitters]
    corners = [t[0] for t in emitters] + [tuple(t[0][i] + t[1][i] for i in range(3)) for t in emitters] + \
              [tuple(t[0][i] + t[2][i] for i in range(3)) for t in emitters]
    middle = tuple(sum(p[i] for p in corners) / len(corners) for i in range(3))
    reach = max(math.sqrt(dot(sub(p, middle), sub(p, middle))) for p in corners)
    to_middle = sub(middle, probe)
    distance = math.sqrt(dot(to_middle, to_middle))
    cone = math.asin(min(1.0, reach / distance)) if distance > reach else math.pi
    margin = 2 * math.pi / width + math.pi / height  # more than any pixel's angular size
    totals = {axis: [0.0, 0.0, 0.0] for axis in AXES}
    for row in range(height):
        th0, th1 = math.pi * row / height, math.pi * (row + 1) / height
        d_omega = (2 * math.pi / width) * (math.cos(th0) - math.cos(th1))
        for column in range(width):
            th, ph = 0.5 * (th0 + th1), 2 * math.pi * ((column + 0.5) / width - 0.5)
            centre = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            if math.acos(max(-1.0, min(1.0, dot(centre, to_middle) / distance))) > cone + margin:
                continue
            value = [0.0, 0.0, 0.0]
            for a in range(samples):
                for b in range(samples):
                    t = math.pi * (row + (a + 0.5) / samples) / height
                    p = 2 * math.pi * ((column + (b + 0.5) / samples) / width - 0.5)
                    d = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
                    _, which = scene.closest(probe, d)
                    if which is not None:
                        emission = scene.radiance(probe, d, which)
                        if emission:
                            value = [v + e for v, e in zip(value, emission)]
            for axis, n in AXES.items():
                weight = max(0.0, dot(n, centre)) * d_omega / (samples * samples)
                totals[axis] = [t + v * weight for t, v in zip(totals[axis], value)]
    return totals


def pixel_bias(scene_path, probes, width, height, cells=CELLS, supersample=SUPERSAMPLE):
    """Per probe and axis, RGB: what the panorama pipeline adds to the emitters' direct light."""
    scene = Scene(load_triangles(scene_path))
    biases = []
    for probe in probes:
        exact = exact_direct(scene, probe, cells)
        model = panorama_direct(scene, probe, width, height, supersample)
        biases.append({axis: [m - e for m, e in zip(model[axis], exact[axis])] for axis in AXES})
    return biases


def baker_direct(args, scene_path, probes):
    per_seed = []
    for seed in range(1, args.seeds + 1):
        per_seed.append([{axis: sum(rgb) for axis, rgb in probe.items()}
                         for probe in baker_axes(args.baker, scene_path, probes, args.rays, 0, seed)])
    out = []
    for p in range(len(probes)):
        entry = {}
        for axis in AXES:
            values = [s[p][axis] for s in per_seed]
            mean = sum(values) / len(values)
            spread = sum((v - mean) ** 2 for v in values) / max(1, len(values) - 1)
            entry[axis] = {"mean": mean, "standard_error": math.sqrt(spread / len(values))}
        out.append(entry)
    return out


def cycles_direct(args, scene_path, probes):
    """reference_probe.py on a copy of the scene whose surfaces reflect nothing."""
    require_blender()
    with tempfile.TemporaryDirectory() as tmp:
        gltf = json.load(open(scene_path))
        for material in gltf.get("materials", []):
            material.setdefault("pbrMetallicRoughness", {})["baseColorFactor"] = [0, 0, 0, 1]
        for resource in gltf["buffers"] + gltf.get("images", []):
            if "uri" in resource:
                copy = os.path.join(tmp, resource["uri"])
                os.makedirs(os.path.dirname(copy), exist_ok=True)
                shutil.copy(os.path.join(os.path.dirname(scene_path), resource["uri"]), copy)
        black = os.path.join(tmp, "black.gltf")
        json.dump(gltf, open(black, "w"))
        irradiance, _ = cycles_axes(black, probes, args.res, args.cycles_spp, 0, 5)
    return [{axis: sum(rgb) for axis, rgb in probe.items()} for probe in irradiance]

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--res", help="panorama size WxH; default: the reference's")
    ap.add_argument("--cells", type=int, default=CELLS, help="sub-triangles per emitter edge for the exact integral")
    ap.add_argument("--supersample", type=int, default=SUPERSAMPLE, help="points per pixel side for the panorama model")
    ap.add_argument("--baker", default=os.path.join(ROOT, "build", "baker"))
    ap.add_argument("--rays", type=int, default=262144)
    ap.add_argument("--seeds", type=int, default=4, help="baker seeds; 0 leaves the baker out")
    ap.add_argument("--cycles-spp", type=int, default=0, help="render Cycles at this many samples per pixel; 0: not")
    ap.add_argument("--json", help="write the results here as well")
    args = ap.parse_args()

    reference_path = os.path.join(SHARED, "data", "reference", args.scene + ".json")
    scene_path = os.path.join(SHARED, "data", "scenes", args.scene, args.scene + ".gltf")
    for path in (reference_path, scene_path):
        if not os.path.exists(path):
            fail("missing %s: the scenes and references live in ../shared beside the checkout" % path)
    if args.seeds > 0 and not os.access(args.baker, os.X_OK):
        fail("no baker at %s (build it, or pass --baker, or --seeds 0)" % args.baker)
    reference = json.load(open(reference_path))
    args.res = args.res or reference["renderer"]["res"]
    width, height = (int(v) for v in args.res.lower().split("x"))
    probes = reference["probes"]
    scene = Scene(load_triangles(scene_path))
    if not scene.emitters:
        fail("%s has no emissive triangles" % scene_path)

    baker = baker_direct(args, scene_path, probes) if args.seeds > 0 else None
    cycles = cycles_direct(args, scene_path, probes) if args.cycles_spp > 0 else None
    results = []
    for p, probe in enumerate(probes):
        exact = {axis: sum(v) for axis, v in exact_direct(scene, probe, args.cells).items()}
        model = {axis: sum(v) for axis, v in panorama_direct(scene, probe, width, height, args.supersample).items()}
        axes = {}
        for axis in AXES:
            entry = {"exact": exact[axis], "panorama_model": model[axis]}
            if baker:
                entry["baker"] = baker[p][axis]
            if cycles:
                entry["cycles"] = cycles[p][axis]
            axes[axis] = entry
        results.append({"probe": probe, "axes": axes})
    report = {"scene": args.scene, "res": args.res, "cells": args.cells, "supersample": args.supersample,
              "rays": args.rays, "seeds": args.seeds, "cycles_spp": args.cycles_spp, "probes": results,
              "values": "r + g + b of the direct irradiance E(n) from the emissive triangles"}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
    print("direct light of %s's emitters at its reference probes (r + g + b); relative to exact" % args.scene)
    for entry in results:
        print("probe %s" % (entry["probe"],))
        for axis, e in entry["axes"].items():
            if e["exact"] <= 0:
                continue
            line = "  %s exact %.5f  panorama %+.2f %%" % (axis, e["exact"], 100 * (e["panorama_model"] / e["exact"] - 1))
            if "baker" in e:
                line += "  baker %+.2f %% (± %.2f)" % (100 * (e["baker"]["mean"] / e["exact"] - 1),
                                                      100 * e["baker"]["standard_error"] / e["exact"])
            if "cycles" in e:
                line += "  cycles %+.2f %%" % (100 * (e["cycles"] / e["exact"] - 1))
            print(line)


if __name__ == "__main__":
    main()
