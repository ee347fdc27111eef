#!/usr/bin/env python3
"""Writes data/default_room/default_room.gltf (+ .bin): the scene the Quick start bakes.

A Cornell-style room, 4 m wide, 3 m high and 4 m deep, open towards +Z: white floor,
ceiling and back wall, a red wall at -X, a green wall at +X, two white boxes, and a warm
emissive panel just under the ceiling. Lambertian-friendly materials (metallic 0,
roughness 1, doubleSided) so every renderer agrees on what it means.

Usage: python3 data/tools/make_default_room.py [OUT_DIR]   (default: data/default_room)
Only the standard library is used, and the output is byte-for-byte reproducible.
"""
import argparse
import json
import math
import os
import struct

WIDTH, HEIGHT, DEPTH = 4.0, 3.0, 4.0
MATERIALS = [
    ("white", (0.73, 0.71, 0.68), None, None),
    ("red", (0.63, 0.065, 0.05), None, None),
    ("green", (0.14, 0.45, 0.091), None, None),
    ("panel", (0.78, 0.78, 0.78), (1.0, 0.85, 0.6), 12.0),
]


def quad(p0, p1, p2, p3):
    """Two triangles p0 p1 p2 / p0 p2 p3, counter-clockwise seen from the side the normal faces."""
    e1 = [p1[i] - p0[i] for i in range(3)]
    e2 = [p3[i] - p0[i] for i in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    length = math.sqrt(sum(c * c for c in n))
    n = [c / length for c in n]
    return [p0, p1, p2, p3], [n] * 4, [0, 1, 2, 0, 2, 3]


def box(x0, x1, y0, y1, z0, z1):
    """An axis-aligned box with outward-facing quads (no bottom: it stands on the floor)."""
    faces = [
        quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)),  # top, +Y
        quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)),  # +Z
        quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)),  # -Z
        quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)),  # +X
        quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)),  # -X
    ]
    return faces


def room_parts():
    """The room as (material index, list of quads) pairs; room walls face inwards."""
    hw, d, h = WIDTH / 2, DEPTH, HEIGHT
    return [
        (0, [quad((-hw, 0, 0), (-hw, 0, d), (hw, 0, d), (hw, 0, 0)),          # floor, +Y
             quad((-hw, h, 0), (hw, h, 0), (hw, h, d), (-hw, h, d)),          # ceiling, -Y
             quad((-hw, 0, 0), (hw, 0, 0), (hw, h, 0), (-hw, h, 0))]          # back wall, +Z
         + box(-1.3, -0.3, 0.0, 2.0, 0.8, 1.8)                                 # tall box
         + box(0.3, 1.3, 0.0, 1.0, 1.8, 2.8)),                                 # short box
        (1, [quad((-hw, 0, 0), (-hw, h, 0), (-hw, h, d), (-hw, 0, d))]),      # left wall, +X
        (2, [quad((hw, 0, 0), (hw, 0, d), (hw, h, d), (hw, h, 0))]),          # right wall, -X
        (3, [quad((-0.5, h - 0.01, 1.5), (0.5, h - 0.01, 1.5), (0.5, h - 0.01, 2.5), (-0.5, h - 0.01, 2.5))]),  # panel, -Y
    ]


def write_scene(out_dir, name, parts, generator, extras):
    """Writes OUT_DIR/NAME.gltf and NAME.bin: one mesh, a primitive per (material, pieces) part,
    where each piece is (vertices, normals, indices) with indices local to the piece."""
    blob = bytearray()
    buffer_views, accessors, primitives = [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        buffer_views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(buffer_views) - 1

    for material, pieces in parts:
        positions, normals, indices = [], [], []
        for verts, norms, idx in pieces:
            base = len(positions)
            positions += verts
            normals += norms
            indices += [base + i for i in idx]
        wide = len(positions) > 65535
        pos_view = add_view(b"".join(struct.pack("<3f", *p) for p in positions), 34962)
        nrm_view = add_view(b"".join(struct.pack("<3f", *n) for n in normals), 34962)
        idx_view = add_view(b"".join(struct.pack("<I" if wide else "<H", i) for i in indices), 34963)
        lo = [min(p[i] for p in positions) for i in range(3)]
        hi = [max(p[i] for p in positions) for i in range(3)]
        accessors.append({"bufferView": pos_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": lo, "max": hi})
        accessors.append({"bufferView": nrm_view, "componentType": 5126, "count": len(normals), "type": "VEC3"})
        accessors.append({"bufferView": idx_view, "componentType": 5125 if wide else 5123, "count": len(indices),
                          "type": "SCALAR"})
        n = len(accessors)
        primitives.append({"attributes": {"POSITION": n - 3, "NORMAL": n - 2}, "indices": n - 1,
                           "material": material, "mode": 4})

    materials = []
    for material_name, albedo, emission, strength in MATERIALS:
        m = {"name": material_name, "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorFactor": list(albedo) + [1.0], "metallicFactor": 0.0,
                                      "roughnessFactor": 1.0}}
        if emission:
            m["emissiveFactor"] = list(emission)
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        materials.append(m)

    gltf = {
        "asset": {"version": "2.0", "generator": generator},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": name, "nodes": [0], "extras": extras}],
        "nodes": [{"name": "room", "mesh": 0}],
        "meshes": [{"name": "room", "primitives": primitives}],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"uri": name + ".bin", "byteLength": len(blob)}],
    }
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
        f.write(bytes(blob))
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "default_room"),
                        help="where to write default_room.gltf and .bin (default: data/default_room)")
    out_dir = parser.parse_args().out_dir
    write_scene(out_dir, "default_room", room_parts(), "baker data/tools/make_default_room.py",
                {"probe_hint": [[0.0, 1.5, 2.0], [0.0, 0.5, 3.5], [1.5, 2.5, 0.5]]})


if __name__ == "__main__":
    main()
