#!/usr/bin/env python3
"""Writes data/thin_walls/thin_wall_{quarter,half,one}.gltf: a closed room 6 × 2.5 × 4 m split at
x = 0 by a wall a quarter, a half and one probe spacing (0.5 m, bake with --spacing 0.5) thick.
The side x < 0 is lit by a 30 cd point light; the side x > 0 holds no light, so every bit of
light read there has leaked through the wall. Geometry only, grey and double-sided; the buffer
is embedded, so each scene is one file.

    python3 scripts/make_thin_walls.py [OUT_DIR]
"""
import base64
import json
import struct
import sys
from pathlib import Path

SPACING = 0.5
ROOM = ((-3.0, 0.0, -2.0), (3.0, 2.5, 2.0))
THICKNESS = {"quarter": 0.25, "half": 0.5, "one": 1.0}  # in probe spacings


def box_faces(lo, hi):
    """The six faces of an axis-aligned box as quads (corners counter-clockwise seen from outside)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [
        ([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0)),
        ([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)], (1, 0, 0)),
        ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0)),
        ([(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)], (0, 1, 0)),
        ([(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)], (0, 0, -1)),
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
    ]


def scene(thickness):
    half = thickness / 2.0
    (_, ry0, rz0), (_, ry1, rz1) = ROOM
    # The room's faces look inwards and the wall's outwards: a probe in either half sees fronts only.
    room = [(corners[::-1], tuple(-c for c in normal)) for corners, normal in box_faces(ROOM[0], ROOM[1])]
    quads = room + box_faces((-half, ry0, rz0), (half, ry1, rz1))
    positions, normals, indices = [], [], []
    for corners, normal in quads:
        base = len(positions)
        positions += corners
        normals += [normal] * 4
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    data += b"".join(struct.pack("<3f", *n) for n in normals)
    data += b"".join(struct.pack("<H", i) for i in indices)
    vertex_bytes = 12 * len(positions)
    return {
        "asset": {"version": "2.0", "generator": "baker scripts/make_thin_walls.py"},
        "scene": 0,
        "scenes": [{"name": f"thin wall {thickness:g} m", "nodes": [0, 1]}],
        "nodes": [
            {"name": "rooms", "mesh": 0},
            {"name": "lamp", "translation": [-1.5, 1.8, 0.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "plaster", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 30.0}]}},
        "extensionsUsed": ["KHR_lights_punctual"],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": vertex_bytes, "target": 34962},
            {"buffer": 0, "byteOffset": vertex_bytes, "byteLength": vertex_bytes, "target": 34962},
            {"buffer": 0, "byteOffset": 2 * vertex_bytes, "byteLength": 2 * len(indices), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": [min(p[a] for p in positions) for a in range(3)],
             "max": [max(p[a] for p in positions) for a in range(3)]},
            {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "data" / "thin_walls"
    out.mkdir(parents=True, exist_ok=True)
    for name, spacings in THICKNESS.items():
        path = out / f"thin_wall_{name}.gltf"
        path.write_text(json.dumps(scene(spacings * SPACING), indent=1) + "\n")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
