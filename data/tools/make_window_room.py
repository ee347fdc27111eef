#!/usr/bin/env python3
"""Writes window_room.gltf (+ .bin, + a .png texture): a closed room lit only through one window.

The room is 5 m wide (x -2.5..2.5), 3 m high (y 0..3) and 4 m deep (z 0..4) inside, with 0.2 m
thick walls, floor and ceiling as closed geometry: inner faces, outer faces and the four reveal
faces of a 1.2 x 1.2 m window (x -0.6..0.6, y 1.0..2.2) through the -Z wall. Textured floor
(a 64 x 64 checker PNG, one repeat per metre), off-white walls and ceiling, a pale blue +X wall,
grey outside. Lambertian-friendly materials (metallic 0, roughness 1, doubleSided). No lights
and nothing outside: meant for an environment map, here ../shared/data/hdri/studio_small_03_1k.hdr
at strength 1 and rotation 0, whose small hot light stands 41.6 deg up towards -Z
(d = (-0.114, 0.664, -0.739)), so sky and "sun" enter only through the window and the sun
patch falls on the floor at about x -0.4..0.9, z 1.1..2.4.

scenes[0].extras.probe_hint: (0.2, 0.5, 1.1) beside the sun patch, in the beam (it sees the sun
through the window); (0, 1.5, 2) in the middle of the room; (2, 2.4, 3.5) in the far corner.

Usage: python3 data/tools/make_window_room.py [OUT_DIR]   (default: data/window_room)
Only the standard library is used, and the output is byte-for-byte reproducible (for a given
zlib). Shares make_sunlit_yard.py's quads, PNG and glTF writer.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_sunlit_yard import png_rgb, quad, write_textured_scene  # noqa: E402

X0, X1, Y0, Y1, Z0, Z1 = -2.5, 2.5, 0.0, 3.0, 0.0, 4.0   # inside
T = 0.2                                                  # wall, floor and ceiling thickness
WX0, WX1, WY0, WY1 = -0.6, 0.6, 1.0, 2.2                 # window opening in the -Z wall
MATERIALS = [
    ("floor_checker", (1.0, 1.0, 1.0), 0),
    ("wall_white", (0.78, 0.76, 0.72), None),
    ("wall_blue", (0.45, 0.58, 0.75), None),
    ("outside_grey", (0.4, 0.4, 0.4), None),
]
PROBES = [[0.2, 0.5, 1.1], [0.0, 1.5, 2.0], [2.0, 2.4, 3.5]]


def checker_png():
    """8 x 8 squares of 8 px: warm oak and teal."""
    colours = [(190, 140, 88), (58, 122, 120)]
    return png_rgb(64, 64, lambda x, y: colours[(x // 8 + y // 8) % 2])


def wall_with_window(z, x0, x1, y0, y1, facing):
    """The plane z = const from x0..x1, y0..y1 minus the window, as four quads facing +Z or -Z."""
    rects = [(x0, WX0, y0, y1), (WX1, x1, y0, y1), (WX0, WX1, y0, WY0), (WX0, WX1, WY1, y1)]
    out = []
    for a0, a1, b0, b1 in rects:
        if facing > 0:
            out.append(quad((a0, b0, z), (a1, b0, z), (a1, b1, z), (a0, b1, z)))
        else:
            out.append(quad((a1, b0, z), (a0, b0, z), (a0, b1, z), (a1, b1, z)))
    return out


def room_objects():
    x0, x1, y0, y1, z0, z1 = X0, X1, Y0, Y1, Z0, Z1
    # Inside: faces point into the room.
    floor = [quad((x0, y0, z0), (x0, y0, z1), (x1, y0, z1), (x1, y0, z0), 1.0)]              # +Y
    white = [quad((x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)),                  # ceiling, -Y
             quad((x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1)),                  # back wall, -Z
             quad((x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1))]                  # -X wall, +X
    white += wall_with_window(z0, x0, x1, y0, y1, +1)                                          # window wall, +Z
    blue = [quad((x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0))]                   # +X wall, -X
    # Window reveals: sill (+Y), lintel (-Y), jambs (+X at WX0, -X at WX1), from z0 - T to z0.
    za, zb = z0 - T, z0
    reveals = [quad((WX0, WY0, za), (WX0, WY0, zb), (WX1, WY0, zb), (WX1, WY0, za)),          # sill, +Y
               quad((WX0, WY1, za), (WX1, WY1, za), (WX1, WY1, zb), (WX0, WY1, zb)),          # lintel, -Y
               quad((WX0, WY0, zb), (WX0, WY0, za), (WX0, WY1, za), (WX0, WY1, zb)),          # left jamb, +X
               quad((WX1, WY0, za), (WX1, WY0, zb), (WX1, WY1, zb), (WX1, WY1, za))]          # right jamb, -X
    # Outside: faces point away from the room.
    ox0, ox1, oy0, oy1, oz0, oz1 = x0 - T, x1 + T, y0 - T, y1 + T, z0 - T, z1 + T
    outside = [quad((ox0, oy1, oz0), (ox0, oy1, oz1), (ox1, oy1, oz1), (ox1, oy1, oz0)),      # roof, +Y
               quad((ox0, oy0, oz0), (ox1, oy0, oz0), (ox1, oy0, oz1), (ox0, oy0, oz1)),      # underside, -Y
               quad((ox0, oy0, oz1), (ox1, oy0, oz1), (ox1, oy1, oz1), (ox0, oy1, oz1)),      # back, +Z
               quad((ox1, oy0, oz1), (ox1, oy0, oz0), (ox1, oy1, oz0), (ox1, oy1, oz1)),      # +X
               quad((ox0, oy0, oz0), (ox0, oy0, oz1), (ox0, oy1, oz1), (ox0, oy1, oz0))]      # -X
    outside += wall_with_window(oz0, ox0, ox1, oy0, oy1, -1)                                   # window side, -Z
    return [("room", [(0, floor), (1, white + reveals), (2, blue), (3, outside)])]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "window_room"),
                        help="where to write window_room.gltf, .bin and the PNG (default: data/window_room)")
    out_dir = parser.parse_args().out_dir
    write_textured_scene(out_dir, "window_room", room_objects(), MATERIALS,
                         [("window_room_floor.png", checker_png())],
                         "baker data/tools/make_window_room.py", {"probe_hint": PROBES})


if __name__ == "__main__":
    main()
