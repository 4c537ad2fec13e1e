#!/usr/bin/env python3
"""Writes a large GLB for `irad bench --load`: a displaced terrain grid of QUADS x QUADS quads
(2 QUADS^2 triangles; --quads 1000 gives 2,000,002 triangles, the "2M" file), with POSITION,
NORMAL (the analytic normals of the height field), TEXCOORD_0 and uint32 indices, lit by an
emissive panel above it (a second primitive, emissiveFactor x KHR_materials_emissive_strength); the terrain's
base colour is a small checkerboard PNG (so the loader keeps TEXCOORD_0),
seen by one perspective camera. The file is written where -o says (the build tree; never commit
it). Plain Python (no numpy): some seconds for the 2M file.

--textures N (1 to QUADS, default 1) splits the terrain into N primitives, contiguous bands of
quad rows as even as possible (each band with its own POSITION/NORMAL/TEXCOORD_0 accessors over
its rows of vertices, the boundary rows duplicated, and uint32 indices), each with its own
material and its own 64 x 64 checkerboard PNG (a per-band hue and cell size), every PNG a
separate image and texture embedded in the binary chunk; TEXCOORD_0 spans the whole grid, so
each band shows its own strip of its texture. --textures 1 writes one terrain primitive with the
16 x 16 checkerboard above.

  python3 scripts/make_large_glb.py -o build/large_2m.glb [--quads 1000]
  python3 scripts/make_large_glb.py -o build/textured_200k.glb --quads 320 --textures 256
"""
import argparse
import colorsys
import math
import json
import pathlib
import struct
import zlib

from array import array


def terrain(q):
    n = q + 1
    # A few octaves of smooth bumps over 20 x 20 units (y up): a real-looking height field.
    octaves = [(0.35, 0.27, 1.0), (0.9, 1.3, 0.35), (2.7, 2.1, 0.12), (7.3, 6.1, 0.03)]
    coords = [20.0 * k / q - 10.0 for k in range(n)]
    sx = [[(a * math.sin(fx * x), a * fx * math.cos(fx * x)) for x in coords]
          for fx, fz, a in octaves]
    cz = [[(math.cos(fz * z), fz * math.sin(fz * z)) for z in coords] for fx, fz, a in octaves]
    pos, nrm, uv = array("f"), array("f"), array("f")
    for r, z in enumerate(coords):
        for c, x in enumerate(coords):
            y = dx = dz = 0.0
            for o in range(len(octaves)):
                s, ds = sx[o][c]
                cc, dc = cz[o][r]
                y += s * cc
                dx += ds * cc
                dz -= s * dc
            inv = 1.0 / math.sqrt(dx * dx + 1.0 + dz * dz)
            pos.extend((x, y, z))
            nrm.extend((-dx * inv, inv, -dz * inv))
            uv.extend((c / q, r / q))
    idx = array("I")
    for r in range(q):
        for c in range(q):
            a = r * n + c
            # Counter-clockwise seen from above (+y).
            idx.extend((a, a + n, a + 1, a + 1, a + n, a + n + 1))
    return pos, nrm, uv, idx


def checker_png(side=16, cell=2, light=(200, 190, 160), dark=(120, 140, 90)):
    """An RGB PNG of side x side texels, a two-tone checkerboard of cell x cell texel squares
    (the terrain's base colour)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    light, dark = bytes(light), bytes(dark)
    # The two kinds of row (filter byte 0, then the texels), by the parity of y // cell.
    kinds = [b"\x00" + b"".join(light if (x // cell + par) % 2 else dark for x in range(side))
             for par in (0, 1)]
    rows = b"".join(kinds[(y // cell) % 2] for y in range(side))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def band_png(k, n):
    """The checkerboard of band k of n: a hue by k / n, a cell of 4, 8 or 16 texels by k."""
    h = k / n
    light = [round(255 * v) for v in colorsys.hsv_to_rgb(h, 0.45, 0.95)]
    dark = [round(255 * v) for v in colorsys.hsv_to_rgb(h, 0.85, 0.6)]
    return checker_png(side=64, cell=4 << (k % 3), light=light, dark=dark)


def bands(pos, nrm, uv, q, n_bands):
    """Splits the terrain's vertex arrays (q + 1 rows of q + 1 vertices) into n_bands contiguous
    bands of quad rows, as even as possible; each band keeps its rows of vertices (both boundary
    rows) and gets its own uint32 indices."""
    n = q + 1
    out = []
    for k in range(n_bands):
        r0, r1 = k * q // n_bands, (k + 1) * q // n_bands
        bp, bn, bu = (pos[r0 * n * 3:(r1 + 1) * n * 3], nrm[r0 * n * 3:(r1 + 1) * n * 3],
                      uv[r0 * n * 2:(r1 + 1) * n * 2])
        idx = array("I")
        for r in range(r1 - r0):
            for c in range(q):
                a = r * n + c
                # Counter-clockwise seen from above (+y).
                idx.extend((a, a + n, a + 1, a + 1, a + n, a + n + 1))
        out.append((bp, bn, bu, idx))
    return out


def panel():
    s, h = 4.0, 6.0
    pos = array("f", [-s, h, -s, s, h, -s, s, h, s, -s, h, s])
    nrm = array("f", [0, -1, 0] * 4)
    uv = array("f", [0, 0, 1, 0, 1, 1, 0, 1])
    idx = array("I", [0, 1, 2, 0, 2, 3])  # counter-clockwise seen from below
    return pos, nrm, uv, idx


def append_view(doc, blob, arr, target=None):
    """Appends arr's bytes (an array, little-endian as on x86 and ARM) to blob, 4-byte aligned, as
    a bufferView of buffer 0 with `target` (None: no target, e.g. an image); returns the view's
    index."""
    while len(blob) % 4:
        blob.append(0)
    data = arr.tobytes()
    v = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
    if target is not None:
        v["target"] = target
    doc["bufferViews"].append(v)
    blob.extend(data)
    return len(doc["bufferViews"]) - 1


def write_glb(doc, blob, out):
    """Writes doc (its buffer 0 the GLB's binary chunk, byteLength set here) and blob (a
    bytearray, padded to 4 bytes here) as a GLB 2.0 file at out, through a temporary file renamed
    into place; returns the file's size."""
    while len(blob) % 4:
        blob.append(0)
    doc["buffers"][0:1] = [{"byteLength": len(blob)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    tmp = pathlib.Path(str(out) + ".tmp")
    with open(tmp, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\x00"))
        f.write(blob)
    tmp.replace(out)
    return total


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--quads", type=int, default=1000, help="grid side in quads (default 1000)")
    p.add_argument("--textures", type=int, default=1,
                   help="terrain bands, each with its own material and PNG (1 to QUADS, default 1)")
    args = p.parse_args()
    if args.quads < 1:
        p.error("--quads must be at least 1")
    if not 1 <= args.textures <= args.quads:
        p.error(f"--textures must be between 1 and QUADS ({args.quads}), not {args.textures}")
    n_tex = args.textures
    if n_tex == 1:
        terrain_mats = [{"name": "terrain", "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.9, 0.9, 1], "baseColorTexture": {"index": 0},
            "metallicFactor": 0,
            "roughnessFactor": 1}}]
    else:
        terrain_mats = [{"name": f"terrain {k}", "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.9, 0.9, 1], "baseColorTexture": {"index": k},
            "metallicFactor": 0,
            "roughnessFactor": 1}} for k in range(n_tex)]

    doc = {"asset": {"version": "2.0", "generator": "irad scripts/make_large_glb.py"},
           "extensionsUsed": ["KHR_materials_emissive_strength"],
           "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "materials": terrain_mats + [
               {"name": "panel", "pbrMetallicRoughness": {
                   "baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                "emissiveFactor": [1, 0.95, 0.9],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}]}
    blob = bytearray()

    def accessor(arr, ctype, kind, target, bounds=False):
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[kind]
        a = {"bufferView": append_view(doc, blob, arr, target), "componentType": ctype,
             "count": len(arr) // width, "type": kind}
        if bounds:
            a["min"] = [min(arr[k::width]) for k in range(width)]
            a["max"] = [max(arr[k::width]) for k in range(width)]
        doc["accessors"].append(a)
        return len(doc["accessors"]) - 1

    prims = []
    if n_tex == 1:
        parts = [terrain(args.quads)]
    else:
        parts = bands(*terrain(args.quads)[:3], args.quads, n_tex)
    for material, (pos, nrm, uv, idx) in enumerate(parts + [panel()]):
        prims.append({"attributes": {
            "POSITION": accessor(pos, 5126, "VEC3", 34962, bounds=True),
            "NORMAL": accessor(nrm, 5126, "VEC3", 34962),
            "TEXCOORD_0": accessor(uv, 5126, "VEC2", 34962)},
            "indices": accessor(idx, 5125, "SCALAR", 34963), "material": material, "mode": 4})
    doc["meshes"].append({"name": "terrain", "primitives": prims})
    nverts = sum(len(part[0]) // 3 for part in parts) + 4
    del parts
    doc["images"], doc["textures"] = [], []
    for k in range(n_tex):
        png = array("B", checker_png() if n_tex == 1 else band_png(k, n_tex))
        doc["images"].append({"bufferView": append_view(doc, blob, png), "mimeType": "image/png"})
        doc["textures"].append({"source": k})
    doc["cameras"] = [{"type": "perspective", "perspective": {
        "yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}}]
    # The camera at (0, 9, 17) looking at the origin: a rotation about x by -atan(9/17).
    ang = -math.atan2(9.0, 17.0) / 2.0
    doc["nodes"] = [{"name": "terrain", "mesh": 0},
                    {"name": "camera", "camera": 0, "translation": [0, 9, 17],
                     "rotation": [math.sin(ang), 0, 0, math.cos(ang)]}]
    doc["scenes"] = [{"nodes": [0, 1]}]
    doc["scene"] = 0
    out = pathlib.Path(args.output)
    total = write_glb(doc, blob, out)
    tris = 2 * args.quads * args.quads + 2
    tex = f", {n_tex} textures" if n_tex > 1 else ""
    print(f"{out}: {tris} triangles, {nverts} vertices{tex}, {total} bytes")


if __name__ == "__main__":
    main()
