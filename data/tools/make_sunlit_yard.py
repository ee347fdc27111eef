#!/usr/bin/env python3
"""Writes sunlit_yard.gltf (+ .bin, + two .png textures): a textured exterior lit by an HDR sun.

A 30 m square paved ground (textured), a free-standing concrete wall 6 m long and 2.5 m high
(0.25 m thick) casting a shadow, a low brick building (textured, 5 x 3 x 6 m) and two plain
crates. Lambertian-friendly materials (metallic 0, roughness 1, doubleSided). No lights: the
scene is meant to be lit only by an environment map with a small bright "sun", here
../shared/data/hdri/studio_small_03_1k.hdr at strength 1 and rotation 0, whose hot light
(0.0074 sr, peak ~3.4k, ~62 % of the map's flux) stands 41.6 deg above the horizon towards
d = (-0.114, 0.664, -0.739) in the glTF frame (towards -Z). The wall runs along X, so its
shadow falls on its +Z side. Nothing closes the scene: probes see the sun and the sky.

scenes[0].extras.probe_hint: three probes, (-1, 1, 1) in the wall's shadow, (-3, 1.5, -6) in the
open, (6.5, 1.2, -4) 1 m in front of the building's sunlit -Z face.

Textures: 64 x 64 RGB PNGs generated here (sRGB base colour, written with zlib), sampled NEAREST
with REPEAT wrapping, so renderers that interpolate in different colour spaces still agree. Each
quad gets planar UVs along its edges: one texture repeat per TILE metres (2 m on the ground,
1 m on the building).

Usage: python3 data/tools/make_sunlit_yard.py [OUT_DIR]   (default: data/sunlit_yard)
Only the standard library is used, and the output is byte-for-byte reproducible (for a given
zlib). The writer here (quads with UVs, PNG, textured glTF) is shared with make_window_room.py.
"""
import argparse
import json
import math
import os
import struct
import zlib

NEAREST, REPEAT = 9728, 10497


# ----------------------------------------------------------------------------- geometry
def quad(p0, p1, p2, p3, tile=None):
    """Two triangles p0 p1 p2 / p0 p2 p3, counter-clockwise seen from the side the normal faces.
    With tile (metres per texture repeat), planar UVs: u along p0->p1, v along p0->p3."""
    e1 = [p1[i] - p0[i] for i in range(3)]
    e2 = [p3[i] - p0[i] for i in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    length = math.sqrt(sum(c * c for c in n))
    n = [c / length for c in n]
    if tile:
        a = math.sqrt(sum(c * c for c in e1)) / tile
        b = math.sqrt(sum(c * c for c in e2)) / tile
        uvs = [(0.0, 0.0), (a, 0.0), (a, b), (0.0, b)]
    else:
        uvs = None
    return [p0, p1, p2, p3], [n] * 4, uvs, [0, 1, 2, 0, 2, 3]


def box(x0, x1, y0, y1, z0, z1, tile=None, bottom=False):
    """An axis-aligned box with outward-facing quads (no bottom unless asked: it stands on the ground).
    Side quads start at a bottom corner, so u runs along the ground and v upwards."""
    faces = [
        quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0), tile),  # top, +Y
        quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), tile),  # +Z
        quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), tile),  # -Z
        quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), tile),  # +X
        quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), tile),  # -X
    ]
    if bottom:
        faces.append(quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1), tile))  # -Y
    return faces


# ----------------------------------------------------------------------------- images
def png_rgb(width, height, pixel):
    """An 8-bit RGB PNG (no ancillary chunks) of pixel(x, y) -> (r, g, b), row 0 at the top."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)  # filter: none
        for x in range(width):
            raw.extend(bytes(pixel(x, y)))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


def paving_png():
    """4 x 4 slabs of 16 px (one grout line), three distinct stone colours."""
    colours = [(201, 172, 120), (104, 118, 146), (172, 88, 58)]
    grout = (62, 58, 52)

    def pixel(x, y):
        if x % 16 == 15 or y % 16 == 15:
            return grout
        return colours[(x // 16 + 2 * (y // 16)) % 3]
    return png_rgb(64, 64, pixel)


def brick_png():
    """Running-bond bricks 16 x 8 px, rows offset by 8 px, light mortar, three brick colours."""
    colours = [(150, 62, 44), (118, 48, 38), (176, 96, 60)]
    mortar = (206, 202, 192)

    def pixel(x, y):
        row = y // 8
        xs = (x + 8 * (row % 2)) % 64
        if y % 8 == 7 or xs % 16 == 15:
            return mortar
        return colours[(xs // 16 + row) % 3]
    return png_rgb(64, 64, pixel)


# ----------------------------------------------------------------------------- writer
def f32(v):
    """v as the float32 the binary buffer stores (exact min/max)."""
    return struct.unpack("<f", struct.pack("<f", v))[0]


def write_textured_scene(out_dir, name, objects, materials, images, generator, extras):
    """Writes OUT_DIR/NAME.gltf, NAME.bin and the images.

    objects: [(node name, [(material index, pieces)])], a node and a mesh per object, a primitive
      per (material, pieces); a piece is (vertices, normals, uvs or None, indices), indices local
      to the piece. A primitive has TEXCOORD_0 when its material has a texture.
    materials: [(name, base colour factor (r, g, b), image index or None)], all Lambertian-friendly.
    images: [(file name, PNG bytes)], each used through one NEAREST / REPEAT sampler.
    """
    blob = bytearray()
    buffer_views, accessors, meshes, nodes = [], [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        buffer_views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(buffer_views) - 1

    def add_accessor(view, component, count, kind, values=None):
        acc = {"bufferView": view, "componentType": component, "count": count, "type": kind}
        if values is not None:
            acc["min"] = [f32(min(v[i] for v in values)) for i in range(3)]
            acc["max"] = [f32(max(v[i] for v in values)) for i in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    for node_name, parts in objects:
        primitives = []
        for material, pieces in parts:
            textured = materials[material][2] is not None
            positions, normals, uvs, indices = [], [], [], []
            for verts, norms, tex, idx in pieces:
                base = len(positions)
                positions += verts
                normals += norms
                if textured:
                    uvs += tex
                indices += [base + i for i in idx]
            wide = len(positions) > 65535
            attributes = {
                "POSITION": add_accessor(add_view(b"".join(struct.pack("<3f", *p) for p in positions), 34962),
                                         5126, len(positions), "VEC3", positions),
                "NORMAL": add_accessor(add_view(b"".join(struct.pack("<3f", *n) for n in normals), 34962),
                                       5126, len(normals), "VEC3"),
            }
            if textured:
                attributes["TEXCOORD_0"] = add_accessor(
                    add_view(b"".join(struct.pack("<2f", *t) for t in uvs), 34962), 5126, len(uvs), "VEC2")
            idx_acc = add_accessor(add_view(b"".join(struct.pack("<I" if wide else "<H", i) for i in indices), 34963),
                                   5125 if wide else 5123, len(indices), "SCALAR")
            primitives.append({"attributes": attributes, "indices": idx_acc, "material": material, "mode": 4})
        meshes.append({"name": node_name, "primitives": primitives})
        nodes.append({"name": node_name, "mesh": len(meshes) - 1})

    gltf_materials = []
    for material_name, albedo, image in materials:
        pbr = {"baseColorFactor": list(albedo) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}
        if image is not None:
            pbr["baseColorTexture"] = {"index": image, "texCoord": 0}
        gltf_materials.append({"name": material_name, "doubleSided": True, "pbrMetallicRoughness": pbr})

    gltf = {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0,
        "scenes": [{"name": name, "nodes": list(range(len(nodes))), "extras": extras}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": gltf_materials,
        "textures": [{"sampler": 0, "source": i} for i in range(len(images))],
        "images": [{"uri": file_name, "mimeType": "image/png"} for file_name, _ in images],
        "samplers": [{"magFilter": NEAREST, "minFilter": NEAREST, "wrapS": REPEAT, "wrapT": REPEAT}],
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"uri": name + ".bin", "byteLength": len(blob)}],
    }
    os.makedirs(out_dir, exist_ok=True)
    for file_name, data in images:
        with open(os.path.join(out_dir, file_name), "wb") as f:
            f.write(data)
    with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
        f.write(bytes(blob))
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


# ----------------------------------------------------------------------------- the yard
GROUND_HALF = 15.0
MATERIALS = [
    ("paving", (1.0, 1.0, 1.0), 0),      # textured ground
    ("brick", (1.0, 1.0, 1.0), 1),       # textured building
    ("concrete", (0.5, 0.5, 0.48), None),
    ("crate_blue", (0.18, 0.3, 0.6), None),
    ("crate_yellow", (0.75, 0.6, 0.16), None),
]
PROBES = [[-1.0, 1.0, 1.0], [-3.0, 1.5, -6.0], [6.5, 1.2, -4.0]]


def yard_objects():
    g = GROUND_HALF
    return [
        ("ground", [(0, [quad((-g, 0.0, -g), (-g, 0.0, g), (g, 0.0, g), (g, 0.0, -g), 2.0)])]),  # +Y
        ("wall", [(2, box(-4.0, 2.0, 0.0, 2.5, 0.0, 0.25))]),
        ("building", [(1, box(4.0, 9.0, 0.0, 3.0, -3.0, 3.0, 1.0))]),
        ("crates", [(3, box(-7.0, -5.8, 0.0, 1.2, 4.0, 5.2)), (4, box(-9.0, -8.0, 0.0, 1.0, -3.0, -2.0))]),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "sunlit_yard"),
                        help="where to write sunlit_yard.gltf, .bin and the PNGs (default: data/sunlit_yard)")
    out_dir = parser.parse_args().out_dir
    images = [("sunlit_yard_paving.png", paving_png()), ("sunlit_yard_brick.png", brick_png())]
    write_textured_scene(out_dir, "sunlit_yard", yard_objects(), MATERIALS, images,
                         "baker data/tools/make_sunlit_yard.py", {"probe_hint": PROBES})


if __name__ == "__main__":
    main()
