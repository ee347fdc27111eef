#!/usr/bin/env python3
"""Writes furnished_room.gltf (+ .bin): default_room with 216 576 triangles of furniture.

The bundled room has 32 triangles, so Embree's traversal there costs next to nothing and any
shading work weighs heavily against it. This scene keeps the same walls, boxes, materials and
emissive panel, and adds 24 finely tessellated spheres (9 024 triangles each, smooth normals) on
the floor and hanging under the ceiling: closer to the geometric load of a game level, for
measuring bake throughput against Embree's limit (bench/bench_bake) where traversal is not free.

Usage: python3 data/tools/make_furnished_room.py OUT_DIR
Only the standard library is used, and the output is byte-for-byte reproducible. Not shipped:
at 4 MB it is generated where it is needed.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_default_room import room_parts, write_scene  # noqa: E402

SEGMENTS, RINGS = 96, 48  # around and from pole to pole: 2 * 96 * 47 = 9 024 triangles
RADIUS = 0.22


def sphere(cx, cy, cz, r):
    """A UV sphere as (vertices, normals, indices), counter-clockwise seen from outside."""
    verts, norms, idx = [], [], []
    for i in range(RINGS + 1):
        theta = math.pi * i / RINGS
        for j in range(SEGMENTS + 1):
            phi = 2.0 * math.pi * j / SEGMENTS
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            norms.append(n)
            verts.append((cx + r * n[0], cy + r * n[1], cz + r * n[2]))
    row = SEGMENTS + 1
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b = i * row + j, (i + 1) * row + j
            if i > 0:
                idx += [a, b, a + 1]
            if i < RINGS - 1:
                idx += [a + 1, b, b + 1]
    return verts, norms, idx


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", help="where to write furnished_room.gltf and .bin")
    out_dir = parser.parse_args().out_dir
    parts = room_parts()
    pieces = {0: [], 1: [], 2: []}
    # On the floor, clear of the two boxes (x -1.3..-0.3, z 0.8..1.8 and x 0.3..1.3, z 1.8..2.8).
    floor = [(-1.6, 0.4), (-0.9, 0.4), (0.0, 0.4), (0.9, 0.4), (1.6, 0.4), (1.6, 1.2), (0.0, 1.2),
             (-1.6, 2.2), (-0.9, 2.4), (0.0, 3.2), (-1.6, 3.4), (1.6, 3.4), (0.9, 3.4), (-0.9, 3.4)]
    for k, (x, z) in enumerate(floor):
        pieces[k % 3].append(sphere(x, RADIUS, z, RADIUS))
    # Hanging below the ceiling, around the panel (x -0.5..0.5, z 1.5..2.5).
    hanging = [(-1.2, 0.8), (0.0, 0.8), (1.2, 0.8), (-1.2, 2.0), (1.2, 2.0), (-1.2, 3.2), (0.0, 3.2), (1.2, 3.2),
               (-0.6, 3.6), (0.6, 3.6)]
    for k, (x, z) in enumerate(hanging):
        pieces[k % 3].append(sphere(x, 2.3, z, RADIUS))
    parts = [(material, quads + pieces.get(material, [])) for material, quads in parts]
    write_scene(out_dir, "furnished_room", parts, "baker data/tools/make_furnished_room.py",
                {"probe_hint": [[0.0, 1.5, 2.0], [0.0, 0.5, 3.5], [1.5, 2.5, 0.5]]})


if __name__ == "__main__":
    main()
