#!/usr/bin/env python3
"""Writes open_world.gltf (+ .bin): a kilometre of terrain with thousands of instanced props.

The open-world scene of the scale-out benchmark (bench/bench_scaleout.sh): a 1 km × 1 km ground
of gently rolling terrain (a 128 × 128 height-field grid), and N instances (default 6 000) of four
meshes placed by a fixed pseudo-random sequence: houses (10 × 6 × 8 m boxes with a pitched roof),
trees (a trunk and a crown), rocks and 40 m towers. Every prop is a node that points at one of the
four meshes, so the file stays small while the BVH holds every instance (Embree instancing). A
directional sun (KHR_lights_punctual) and Lambertian-friendly materials; bake it with `--sky` or
`--env` for sky light.

Usage: python3 data/tools/make_open_world.py OUT_DIR [--instances N] [--size METRES]
Only the standard library is used, and the output is byte-for-byte reproducible. Not shipped.
"""
import argparse
import json
import math
import os
import struct


class Lcg:
    """A fixed 64-bit linear congruential sequence: the same scene on every machine."""

    def __init__(self, seed):
        self.state = seed

    def uniform(self):
        self.state = (self.state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        return (self.state >> 11) / float(1 << 53)


def terrain_height(x, z, size):
    return 6.0 * math.sin(x / size * 7.0) * math.cos(z / size * 5.0) + 2.0 * math.sin((x + z) / size * 23.0)


def terrain(size, cells):
    verts, idx = [], []
    for j in range(cells + 1):
        for i in range(cells + 1):
            x, z = (i / cells - 0.5) * size, (j / cells - 0.5) * size
            verts.append((x, terrain_height(x, z, size), z))
    row = cells + 1
    for j in range(cells):
        for i in range(cells):
            a = j * row + i
            idx += [a, a + row, a + 1, a + 1, a + row, a + row + 1]  # counter-clockwise seen from +Y
    return verts, idx


def box(x0, y0, z0, x1, y1, z1):
    """An axis-aligned box, faces counter-clockwise seen from outside."""
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]
    idx = []
    for a, b, cc, d in faces:
        idx += [a, b, cc, a, cc, d]
    return c, idx


def merge(*parts):
    verts, idx = [], []
    for v, i in parts:
        idx += [k + len(verts) for k in i]
        verts += v
    return verts, idx


def roof(w, h, d, y):
    v = [(-w, y, -d), (w, y, -d), (w, y, d), (-w, y, d), (0, y + h, -d), (0, y + h, d)]
    return v, [0, 4, 1, 3, 2, 5, 0, 3, 5, 0, 5, 4, 1, 4, 5, 1, 5, 2]


def props():
    house = merge(box(-5, 0, -4, 5, 6, 4), roof(5.5, 3, 4.5, 6))
    tree = merge(box(-0.3, 0, -0.3, 0.3, 3, 0.3), box(-2, 3, -2, 2, 8, 2))
    rock = box(-1.5, 0, -1.0, 1.5, 1.2, 1.0)
    tower = box(-3, 0, -3, 3, 40, 3)
    return [("house", house, 0), ("tree", tree, 1), ("rock", rock, 2), ("tower", tower, 0)]


def write(out_dir, instances, size):
    buffer, views, accessors, meshes = bytearray(), [], [], []

    def add_mesh(name, verts, idx, material):
        pos = b"".join(struct.pack("<3f", *v) for v in verts)
        ind = b"".join(struct.pack("<I", i) for i in idx)
        for data, target in ((pos, 34962), (ind, 34963)):
            views.append({"buffer": 0, "byteOffset": len(buffer), "byteLength": len(data), "target": target})
            buffer.extend(data)
        lo = [min(v[a] for v in verts) for a in range(3)]
        hi = [max(v[a] for v in verts) for a in range(3)]
        accessors.append({"bufferView": len(views) - 2, "componentType": 5126, "count": len(verts), "type": "VEC3",
                          "min": lo, "max": hi})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                     "indices": len(accessors) - 1, "material": material}]})

    add_mesh("terrain", *terrain(size, 128), 3)
    for name, (verts, idx), material in props():
        add_mesh(name, verts, idx, material)
    rng = Lcg(2026)
    nodes = [{"name": "terrain", "mesh": 0}]
    for n in range(instances):
        x, z = (rng.uniform() - 0.5) * 0.96 * size, (rng.uniform() - 0.5) * 0.96 * size
        # Mesh 1 house, 2 tree, 3 rock, 4 tower: mostly trees and rocks, a tower every 50th prop.
        kind = [1, 2, 2, 3, 3, 3, 2, 3, 3, 1][int(rng.uniform() * 10)] if n % 50 else 4
        angle = rng.uniform() * math.pi
        scale = 0.7 + 0.6 * rng.uniform()
        nodes.append({"name": f"prop{n}", "mesh": kind, "translation": [x, terrain_height(x, z, size) - 0.2, z],
                      "rotation": [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)], "scale": [scale] * 3})
    sun_dir = (-0.4, -0.8, -0.45)
    yaw, pitch = math.atan2(-sun_dir[0], -sun_dir[2]), math.asin(max(-1.0, min(1.0, sun_dir[1])))
    sun_q = [math.sin(pitch / 2) * math.cos(yaw / 2), math.cos(pitch / 2) * math.sin(yaw / 2),
             -math.sin(pitch / 2) * math.sin(yaw / 2), math.cos(pitch / 2) * math.cos(yaw / 2)]
    nodes.append({"name": "sun", "rotation": sun_q, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    material = lambda name, rgb: {"name": name, "doubleSided": True, "pbrMetallicRoughness": {
        "baseColorFactor": rgb + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
    gltf = {
        "asset": {"version": "2.0", "generator": "baker data/tools/make_open_world.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1.0, 0.95, 0.85],
                                                           "intensity": 3.0}]}},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
        "materials": [material("plaster", [0.7, 0.68, 0.62]), material("foliage", [0.2, 0.4, 0.15]),
                      material("stone", [0.45, 0.45, 0.43]), material("grass", [0.3, 0.45, 0.2])],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"uri": "open_world.bin", "byteLength": len(buffer)}],
    }
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "open_world.bin"), "wb") as f:
        f.write(buffer)
    with open(os.path.join(out_dir, "open_world.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", help="where to write open_world.gltf and .bin")
    parser.add_argument("--instances", type=int, default=6000, help="props placed on the terrain")
    parser.add_argument("--size", type=float, default=1000.0, help="side of the square world, metres")
    args = parser.parse_args()
    write(args.out_dir, args.instances, args.size)


if __name__ == "__main__":
    main()
