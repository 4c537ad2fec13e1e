#!/usr/bin/env python3
"""Writes a synthetic equirectangular studio environment as a Radiance .hdr (flat RGBE scanlines),
standard library only, for the docs' images and for trying --env without a downloaded map:
    python3 scripts/make_studio_env.py OUT.hdr [WIDTH]
Orientation as irad reads maps (docs/environment.md): column u = 0.5 + atan2(z, x) / (2 pi), row
v = acos(y) / pi from the top, +Y up. The map: a sky gradient above the horizon, a dark floor
below, a warm key light (a soft box 24 x 16 degrees, radiance 16) up toward +X+Z and a cool fill
(radiance 3) low toward -X."""
import math
import struct
import sys


def softbox(d, centre, half_w, half_h, radiance):
    """radiance inside the box of angular half sizes (radians) around unit `centre`, else 0."""
    az = math.atan2(d[2], d[0]) - math.atan2(centre[2], centre[0])
    az = (az + math.pi) % (2 * math.pi) - math.pi
    el = math.asin(max(-1.0, min(1.0, d[1]))) - math.asin(centre[1])
    return radiance if abs(az) <= half_w and abs(el) <= half_h else None


def direction(az_deg, el_deg):
    a, e = math.radians(az_deg), math.radians(el_deg)
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))


KEY = (direction(45, 35), math.radians(12), math.radians(8), (16.0, 14.5, 12.0))
FILL = (direction(190, 15), math.radians(20), math.radians(6), (2.2, 2.6, 3.0))


def radiance(d):
    for centre, hw, hh, value in (KEY, FILL):
        if softbox(d, centre, hw, hh, value) is not None:
            return value
    if d[1] >= 0.0:  # sky: white at the horizon to pale blue at the zenith
        t = d[1] ** 0.5
        return (1.0 - 0.45 * t, 1.0 - 0.3 * t, 1.0 - 0.05 * t)
    return (0.18, 0.16, 0.14)  # floor


def rgbe(rgb):
    m = max(rgb)
    if m < 1e-32:
        return b"\0\0\0\0"
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(c * scale) for c in rgb] + [exponent + 128])


def main():
    out = sys.argv[1]
    width = int(sys.argv[2]) if len(sys.argv) > 2 else 1024
    height = width // 2
    rows = []
    for j in range(height):
        theta = math.pi * (j + 0.5) / height
        row = bytearray()
        for i in range(width):
            phi = 2.0 * math.pi * ((i + 0.5) / width - 0.5)
            d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            row += rgbe(radiance(d))
        rows.append(bytes(row))
    with open(out, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        for r in rows:
            f.write(r)


if __name__ == "__main__":
    main()
