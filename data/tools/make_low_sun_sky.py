#!/usr/bin/env python3
"""Writes low_sun_sky.hdr: a synthetic 1024 x 512 lat-long sky with a sun 8 deg above the horizon.

None of the maps in ../shared/data/hdri has a sun low over the horizon, and rotating a map about
+Y cannot lower one, so this map supplies the missing case: long shadows, light arriving almost
horizontally on vertical faces and grazing on the ground.

Content (glTF frame, +Y up):
  sky     above the horizon, depends on elevation only: bluish, ~0.42 (luminance) at the zenith,
          ~0.91 at the horizon;
  ground  below the horizon, a constant dim grey-brown (0.09, 0.075, 0.06);
  sun     a disk of angular radius 1.5 deg centred on
          (-sin 7 deg cos 8 deg, sin 8 deg, -cos 7 deg cos 8 deg), i.e. 8 deg up at an azimuth 7 deg
          from -Z towards -X (why not straight towards -Z: SUN_AZIMUTH_DEG below), warm white,
          limb-darkened, with its edge tapered over +-0.2 deg, added on top of the sky. Its
          radiance is scaled so that the sun alone gives a surface facing it 20 times the
          (luminance) irradiance the sky gives an upward-facing surface.

Texel values are means over the texel's (u, v) rectangle, the meaning reference_probe.py gives
to a pixel: the sky is smooth enough to take at the texel centre, the sun is averaged over a
16 x 16 grid of equal-solid-angle sub-cells, since the disk is only ~8.6 texels across.

File: Radiance RGBE, header "#?RADIANCE", "FORMAT=32-bit_rle_rgbe", blank line, "-Y 512 +X 1024",
then 512 flat (not run-length encoded) scanlines, top row first.

Usage: python3 data/tools/make_low_sun_sky.py [OUT_DIR]   (default: data/low_sun_sky)
Only the standard library is used; re-running reproduces the file byte for byte. Prints the sun
direction, its solid angle, the share of the map's flux it carries and the peak value, all taken
from the RGBE values as written.

Licence: CC0 1.0 (public domain dedication), the script and the map it writes.
"""
import argparse
import math
import os

# Lat-long convention, shared by the baker and the Cycles reference tool; checked against
#   ../shared/tools/reference_probe.py: the "Panorama convention" in its docstring (used for
#     --env input too) and ENV_BASE_ROT_Z = 0 in setup_world(), verified there by rendering an
#     empty scene back to the input map;
#   ../shared/tools/panorama_sh.py directions(): the same formulas, pixel centres, exact
#     per-row solid angle (2 pi / W)(cos th0 - cos th1);
#   scene/Environment.cpp Environment::texelOf(): u = 0.5 + atan2(z, x) / 2 pi,
#     v = acos(y) / pi, row 0 at the top; scene/SceneOptions.cpp --env help text.
# Column i, row j:  u = (i + 0.5) / W,  v = (j + 0.5) / H,  phi = 2 pi (u - 0.5),  theta = pi v,
#   d = (sin theta cos phi, cos theta, sin theta sin phi)
# so u = 0.5 looks along +X, u = 0.75 along +Z, u = 0.25 along -Z, v = 0 is +Y.
WIDTH, HEIGHT = 1024, 512

SUN_ELEVATION_DEG = 8.0
# Azimuth of the sun's centre from -Z towards -X. Not 0 (straight towards -Z): that puts the sun on
# the x = 0 plane, where the cosine lobes max(0, +-x) of E(+X) and E(-X) have their kink, and
# the Cycles references integrate their 128 x 64 panoramas with the cosine taken at pixel centres
# (../shared/tools/panorama_sh.py), which there lie 1.41 deg either side of the sun's centre, so
# both axes got the sun's light as if it stood 1.41 deg off the plane: E(+-X) high by ~0.24 (R) at
# the probes that see it. At 7 deg the sun's centre is 6.93 deg from x = 0, the disk (reach 1.7
# deg) 5.2 deg, so every panorama pixel it touches lies wholly on the -X side. It is also clear of
# the other lobe boundaries: 8 deg from y = 0 (the +-Y lobes; the horizon) and 79.4 deg from
# z = 0 (the +-Z lobes). main() checks that the disk keeps >= 2 deg from all three planes.
SUN_AZIMUTH_DEG = 7.0
# Least angle allowed between the disk's edge (radius + taper) and each axis plane x, y, z = 0.
SUN_PLANE_MARGIN_DEG = 2.0
SUN_RADIUS_DEG = 1.5
# A hard-edged disk would alias against 0.35 deg texels and make the Cycles (bilinear) and
# baker (nearest) lookups disagree on the edge texels more than necessary.
SUN_EDGE_DEG = 0.2
SUN_LIMB_DARKENING = 0.6
# Reddened, as direct sunlight is through the long air path at 8 deg; normalised below to
# luminance 1 so that SUN_TO_SKY alone sets the brightness.
SUN_TINT = (1.0, 0.8, 0.6)
SUN_TO_SKY = 20.0
SUN_SUBSAMPLES = 16

SKY_ZENITH = (0.28, 0.42, 0.80)
SKY_HORIZON = (0.85, 0.92, 1.00)
# Exponent of (1 - sin elevation): 3 keeps most of the sky near the zenith colour and brightens
# only the lowest ~20 deg, like a clear sky's horizon band.
SKY_FALLOFF = 3.0
GROUND = (0.09, 0.075, 0.06)

# Rec. 709 luminance, the weights the baker's importance sampling uses.
LUMA = (0.2126, 0.7152, 0.0722)


def luminance(c):
    return LUMA[0] * c[0] + LUMA[1] * c[1] + LUMA[2] * c[2]


def direction(u, v):
    phi = 2.0 * math.pi * (u - 0.5)
    theta = math.pi * v
    return (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))


def texel_solid_angle(j):
    return 2.0 * math.pi / WIDTH * (math.cos(math.pi * j / HEIGHT) - math.cos(math.pi * (j + 1) / HEIGHT))


def sky(y):
    # A hard horizon is safe: with an even height it falls on a texel edge, so no texel mixes
    # sky and ground and nearest and bilinear lookups agree on which side each texel is.
    if y <= 0.0:
        return GROUND
    t = (1.0 - y) ** SKY_FALLOFF
    return tuple(z + (h - z) * t for z, h in zip(SKY_ZENITH, SKY_HORIZON))


def sun_profile(cos_angle, radius, edge):
    angle = math.acos(max(-1.0, min(1.0, cos_angle)))
    if angle >= radius + edge:
        return 0.0
    r = min(angle / radius, 1.0)
    limb = 1.0 - SUN_LIMB_DARKENING * (1.0 - math.sqrt(1.0 - r * r))
    if angle <= radius - edge:
        return limb
    s = (angle - (radius - edge)) / (2.0 * edge)
    return limb * (1.0 - s * s * (3.0 - 2.0 * s))


def sun_texels(sun_dir, radius, edge):
    """Mean of the unit-peak sun profile over each texel it touches: {(i, j): value}."""
    reach = radius + edge
    # Half a texel diagonal is ~0.25 deg; 0.5 deg leaves room for it.
    cos_reach = math.cos(reach + math.radians(0.5))
    out = {}
    for j in range(HEIGHT):
        for i in range(WIDTH):
            d = direction((i + 0.5) / WIDTH, (j + 0.5) / HEIGHT)
            if d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2] < cos_reach:
                continue
            # Sub-cells uniform in phi and cos theta have equal solid angles, so a plain mean
            # is the texel's solid-angle mean.
            c0 = math.cos(math.pi * j / HEIGHT)
            c1 = math.cos(math.pi * (j + 1) / HEIGHT)
            total = 0.0
            for b in range(SUN_SUBSAMPLES):
                ct = c0 + (c1 - c0) * (b + 0.5) / SUN_SUBSAMPLES
                st = math.sqrt(max(0.0, 1.0 - ct * ct))
                for a in range(SUN_SUBSAMPLES):
                    phi = 2.0 * math.pi * ((i + (a + 0.5) / SUN_SUBSAMPLES) / WIDTH - 0.5)
                    dd = (st * math.cos(phi), ct, st * math.sin(phi))
                    total += sun_profile(dd[0] * sun_dir[0] + dd[1] * sun_dir[1] + dd[2] * sun_dir[2],
                                         radius, edge)
            if total > 0.0:
                out[(i, j)] = total / (SUN_SUBSAMPLES * SUN_SUBSAMPLES)
    return out


def rgbe(c):
    """Ward's encoding (as in Radiance's float2rgbe): shared exponent, mantissas truncated."""
    v = max(c)
    if v < 1e-32:
        return (0, 0, 0, 0)
    m, e = math.frexp(v)
    scale = m * 256.0 / v
    return (int(c[0] * scale), int(c[1] * scale), int(c[2] * scale), e + 128)


def unrgbe(p):
    if p[3] == 0:
        return (0.0, 0.0, 0.0)
    f = math.ldexp(1.0, p[3] - (128 + 8))
    return ((p[0] + 0.5) * f, (p[1] + 0.5) * f, (p[2] + 0.5) * f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "low_sun_sky"),
                        help="where to write low_sun_sky.hdr (default: data/low_sun_sky)")
    out_dir = parser.parse_args().out_dir

    el, az = math.radians(SUN_ELEVATION_DEG), math.radians(SUN_AZIMUTH_DEG)
    sun_dir = (-math.sin(az) * math.cos(el), math.sin(el), -math.cos(az) * math.cos(el))
    radius, edge = math.radians(SUN_RADIUS_DEG), math.radians(SUN_EDGE_DEG)
    # Angle between the sun's centre and each axis plane (the lobe boundaries of the six axes).
    plane_deg = [math.degrees(math.asin(abs(c))) for c in sun_dir]
    assert min(plane_deg) >= SUN_RADIUS_DEG + SUN_EDGE_DEG + SUN_PLANE_MARGIN_DEG, plane_deg
    tint_luma = luminance(SUN_TINT)
    tint = tuple(c / tint_luma for c in SUN_TINT)

    rows = [sky(math.cos(math.pi * (j + 0.5) / HEIGHT)) for j in range(HEIGHT)]
    sun = sun_texels(sun_dir, radius, edge)

    # Calibrate with the same sums panorama_sh.py does (texel-centre directions, exact texel
    # solid angles), so the ratio holds for the map as the references integrate it.
    sky_up = 0.0
    for j in range(HEIGHT):
        y = math.cos(math.pi * (j + 0.5) / HEIGHT)
        if y > 0.0:
            sky_up += luminance(rows[j]) * y * texel_solid_angle(j) * WIDTH
    sun_unit = 0.0
    for (i, j), p in sun.items():
        d = direction((i + 0.5) / WIDTH, (j + 0.5) / HEIGHT)
        cos_sun = max(0.0, d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2])
        sun_unit += p * cos_sun * texel_solid_angle(j)
    peak = SUN_TO_SKY * sky_up / sun_unit

    pixels = bytearray()
    for j in range(HEIGHT):
        for i in range(WIDTH):
            c = rows[j]
            p = sun.get((i, j))
            if p is not None:
                c = tuple(k + peak * p * t for k, t in zip(c, tint))
            q = rgbe(c)
            # A flat scanline whose first pixel read (2, 2, <128, ...) would be taken for a
            # run-length-encoded one, and (1, 1, 1, n) for an old-style run; the largest
            # mantissa is always >= 128, so neither can occur, but a reader would fail silently.
            assert max(q[:3]) >= 128 and q[:3] != (1, 1, 1), (i, j, q)
            pixels += bytes(q)

    header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (HEIGHT, WIDTH)
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.normpath(os.path.join(out_dir, "low_sun_sky.hdr"))
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(bytes(pixels))

    # Report from the values as written (quantised), not from the floats above.
    total_flux = sun_flux = e_sun = e_sky_up = 0.0
    peak_rgb, peak_max = (0.0, 0.0, 0.0), 0.0
    for j in range(HEIGHT):
        dom = texel_solid_angle(j)
        y = math.cos(math.pi * (j + 0.5) / HEIGHT)
        for i in range(WIDTH):
            t = 4 * (j * WIDTH + i)
            c = unrgbe(pixels[t:t + 4])
            total_flux += luminance(c) * dom
            if max(c) > peak_max:
                peak_max, peak_rgb = max(c), c
            if (i, j) in sun:
                s = luminance(c) - luminance(rows[j])
                d = direction((i + 0.5) / WIDTH, (j + 0.5) / HEIGHT)
                sun_flux += s * dom
                e_sun += s * max(0.0, d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2]) * dom
            elif y > 0.0:
                e_sky_up += luminance(c) * y * dom
    # The sky behind the sun lights an upward surface too; count it as sky.
    for (i, j) in sun:
        y = math.cos(math.pi * (j + 0.5) / HEIGHT)
        e_sky_up += luminance(rows[j]) * max(0.0, y) * texel_solid_angle(j)
    print("wrote %s (%d x %d, flat RGBE)" % (path, WIDTH, HEIGHT))
    print("sun direction (glTF): (%.6f, %.6f, %.6f), %.1f deg above the horizon, azimuth %.1f deg from -Z "
          "towards -X" % (sun_dir + (SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG)))
    print("sun centre from the planes x = 0, y = 0, z = 0: %.2f, %.2f, %.2f deg (disk edge %.2f deg closer)"
          % tuple(plane_deg + [SUN_RADIUS_DEG + SUN_EDGE_DEG]))
    print("sun disk: radius %.2f deg (edge taper +-%.2f deg), solid angle 2 pi (1 - cos r) = %.6f sr; "
          "%d texels; effective solid angle E_sun / L_peak = %.6f sr"
          % (SUN_RADIUS_DEG, SUN_EDGE_DEG, 2.0 * math.pi * (1.0 - math.cos(radius)), len(sun), e_sun / peak))
    print("sun radiance at the disk centre: luminance %.1f, RGB (%.1f, %.1f, %.1f)"
          % ((peak,) + tuple(peak * t for t in tint)))
    print("irradiance (luminance): sun on a surface facing it %.4f, sky on an upward surface %.4f, ratio %.2f"
          % (e_sun, e_sky_up, e_sun / e_sky_up))
    print("sun's share of the map's flux (luminance x solid angle): %.4f (map total %.4f)"
          % (sun_flux / total_flux, total_flux))
    print("peak texel: (%.1f, %.1f, %.1f)" % peak_rgb)


if __name__ == "__main__":
    main()
