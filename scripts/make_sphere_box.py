#!/usr/bin/env python3
"""Writes a large GLB test scene: the Cornell box of data/cornell_box.gltf (all its meshes,
materials and camera, unchanged) plus a finely tessellated UV sphere of about TRIANGLES
triangles (--triangles 2100000 gives 2,099,600, the "2M" file) floating in front of the tall
block. The sphere has POSITION (with min/max), analytic unit NORMALs, uint32 indices and a white
Lambertian material (baseColorFactor 0.8, metallic 0, roughness 1, KHR_materials_specular
specularFactor 0 like the box's materials), and its node is appended to the default scene.

Placement: the centre (0.3, 0.33, 0.3) with radius 0.09 is used when that sphere lies inside the
box's bounds (the union of the POSITION accessors' min/max) and clear of every mesh's bounds;
otherwise (0.3, 1/3, 0.3) of the box's extent from its min corner with radius 9% of its
smallest side; otherwise that sphere in front of the tall block (centred on the block's bounds
in x, one radius plus a 10% gap before its near side in z, same height). --center and --radius
override the placement. The chosen placement is printed.

The output has one binary buffer: the box's buffer (decoded from its data URI) followed by the
sphere's data, 4-byte aligned; the box's buffer views keep their offsets. The file is written
where -o says (the build tree; never commit it). Plain Python (no numpy): some seconds for the
2M file.

  python3 scripts/make_sphere_box.py -o build/sphere_box_2m.glb [--triangles 2100000]
"""
import argparse
import base64
import json
import math
import pathlib
import struct
import sys

from make_large_glb import append_view, write_glb

from array import array

BOX = pathlib.Path(__file__).resolve().parent.parent / "data" / "cornell_box.gltf"


def sphere(center, radius, rings, segments):
    """A UV sphere (+y poles): rings latitude bands, segments longitude steps. One vertex per
    pole and segments vertices on each of the rings - 1 inner latitude circles; each pole is a
    fan of segments triangles. Counter-clockwise seen from outside. 2 segments (rings - 1)
    triangles."""
    cx, cy, cz = center
    ring_cs = [(math.cos(math.pi * i / rings), math.sin(math.pi * i / rings))
               for i in range(1, rings)]
    seg_cs = [(math.cos(2.0 * math.pi * j / segments), math.sin(2.0 * math.pi * j / segments))
              for j in range(segments)]
    nrm = array("f", (0.0, 1.0, 0.0))
    for ct, st in ring_cs:
        row = []
        for cp, sp in seg_cs:
            row += (st * cp, ct, st * sp)
        nrm.extend(row)
    nrm.extend((0.0, -1.0, 0.0))
    pos = array("f", (c + radius * n for c, n in zip((cx, cy, cz) * (len(nrm) // 3), nrm)))

    s = segments
    south = 1 + (rings - 1) * s
    idx = array("I")
    # North fan: vertex 0, then ring 0 (vertices 1..s).
    for j in range(s):
        idx.extend((0, 1 + (j + 1) % s, 1 + j))
    for i in range(rings - 2):
        a0, b0 = 1 + i * s, 1 + (i + 1) * s
        row = []
        for j in range(s):
            j1 = (j + 1) % s
            a, a1, b, b1 = a0 + j, a0 + j1, b0 + j, b0 + j1
            row += (a, a1, b, a1, b1, b)
        idx.extend(row)
    last = 1 + (rings - 2) * s
    for j in range(s):
        idx.extend((last + j, last + (j + 1) % s, south))
    return pos, nrm, idx


def grid_for(triangles):
    """rings, segments (segments ~ 2 rings) giving 2 segments (rings - 1) ~ triangles."""
    rings = max(2, round(math.sqrt(triangles / 4.0)))
    segments = max(3, round(triangles / (2.0 * (rings - 1))))
    return rings, segments


def clear_of(center, radius, lo, hi, gap):
    """Whether the sphere is at least gap away from the box [lo, hi]."""
    d2 = sum(max(l - c, 0.0, c - h) ** 2 for c, l, h in zip(center, lo, hi))
    return d2 > (radius + gap) ** 2


def place(doc, args):
    """(center, radius, reason) for the sphere, from the box's POSITION bounds."""
    bounds = {}
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            acc = doc["accessors"][prim["attributes"]["POSITION"]]
            lo, hi = bounds.get(mesh.get("name"), (acc["min"], acc["max"]))
            bounds[mesh.get("name")] = ([min(a, b) for a, b in zip(lo, acc["min"])],
                                        [max(a, b) for a, b in zip(hi, acc["max"])])
    lo = [min(b[0][k] for b in bounds.values()) for k in range(3)]
    hi = [max(b[1][k] for b in bounds.values()) for k in range(3)]
    ext = [h - l for l, h in zip(lo, hi)]
    print(f"box bounds: min {[round(v, 4) for v in lo]}, max {[round(v, 4) for v in hi]}",
          file=sys.stderr)

    def fits(center, radius):
        inside = all(l + radius < c < h - radius for c, l, h in zip(center, lo, hi))
        # Walls, floor and ceiling are the box's faces; every other mesh is inside it.
        hits = [n for n, (ml, mh) in bounds.items() if not clear_of(center, radius, ml, mh, 0.0)]
        return inside, hits

    if args.center is not None or args.radius is not None:
        center = args.center or [l + e * f for l, e, f in zip(lo, ext, (0.3, 1 / 3, 0.3))]
        radius = args.radius or 0.09 * min(ext)
        inside, hits = fits(center, radius)
        return center, radius, "from --center/--radius" + (
            "" if inside and not hits else f" (overlaps: {'outside the box ' if not inside else ''}"
                                           f"{', '.join(hits)})")
    candidates = [((0.3, 0.33, 0.3), 0.09, "absolute (0.3, 0.33, 0.3), radius 0.09"),
                  ([l + e * f for l, e, f in zip(lo, ext, (0.3, 1 / 3, 0.3))], 0.09 * min(ext),
                   "(0.3, 1/3, 0.3) of the box's extent, radius 9% of its smallest side")]
    for center, radius, why in candidates:
        inside, hits = fits(center, radius)
        if inside and not hits:
            return list(center), radius, why
        print(f"rejected {why}: centre {[round(v, 4) for v in center]} radius {radius:.4f}: "
              f"{'outside the box' if not inside else 'overlaps ' + ', '.join(hits)}",
              file=sys.stderr)
    center, radius, _ = candidates[1]
    if "tall_block" not in bounds:
        sys.exit("no placement found (no mesh named tall_block); use --center/--radius")
    tl, th = bounds["tall_block"]
    center = [(tl[0] + th[0]) / 2, center[1], tl[2] - 1.1 * radius]
    inside, hits = fits(center, radius)
    if not inside or hits:
        sys.exit(f"sphere in front of the tall block at {center} does not fit; use --center/--radius")
    return center, radius, "in front of the tall block, radius 9% of the box's smallest side"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--triangles", type=int, default=2100000,
                   help="about how many sphere triangles (default 2100000)")
    p.add_argument("--center", type=float, nargs=3, metavar=("X", "Y", "Z"),
                   help="sphere centre (default: chosen from the box's bounds, see above)")
    p.add_argument("--radius", type=float, help="sphere radius (default: see above)")
    args = p.parse_args()

    doc = json.loads(BOX.read_text())
    # One buffer: every box buffer (data URIs) concatenated, 4-byte aligned, views shifted.
    blob = bytearray()
    starts = []
    for buf in doc["buffers"]:
        uri = buf.get("uri", "")
        if not uri.startswith("data:") or ";base64," not in uri:
            sys.exit(f"{BOX}: buffer is not a base64 data URI")
        data = base64.b64decode(uri.split(";base64,", 1)[1])
        if len(data) < buf["byteLength"]:
            sys.exit(f"{BOX}: buffer shorter than its byteLength")
        while len(blob) % 4:
            blob.append(0)
        starts.append(len(blob))
        blob.extend(data[:buf["byteLength"]])
    for bv in doc["bufferViews"]:
        bv["byteOffset"] = bv.get("byteOffset", 0) + starts[bv["buffer"]]
        bv["buffer"] = 0
    base_tris = sum(doc["accessors"][prim["indices"]]["count"] // 3
                    for mesh in doc["meshes"] for prim in mesh["primitives"])
    base_verts = sum(doc["accessors"][prim["attributes"]["POSITION"]]["count"]
                     for mesh in doc["meshes"] for prim in mesh["primitives"])

    center, radius, why = place(doc, args)
    rings, segments = grid_for(args.triangles)
    print(f"sphere: centre {[round(v, 4) for v in center]}, radius {radius:.4f} ({why}); "
          f"{rings} rings x {segments} segments", file=sys.stderr)
    pos, nrm, idx = sphere(center, radius, rings, segments)

    def accessor(arr, ctype, kind, target, name, bounds=False):
        width = {"SCALAR": 1, "VEC3": 3}[kind]
        a = {"name": name, "bufferView": append_view(doc, blob, arr, target),
             "componentType": ctype, "count": len(arr) // width, "type": kind}
        if bounds:
            a["min"] = [min(arr[k::width]) for k in range(width)]
            a["max"] = [max(arr[k::width]) for k in range(width)]
        doc["accessors"].append(a)
        return len(doc["accessors"]) - 1

    doc["materials"].append({
        "name": "sphere_white", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "doubleSided": False, "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
    used = doc.setdefault("extensionsUsed", [])
    if "KHR_materials_specular" not in used:
        used.append("KHR_materials_specular")
    doc["meshes"].append({"name": "sphere", "primitives": [{
        "attributes": {"POSITION": accessor(pos, 5126, "VEC3", 34962, "sphere_POSITION", True),
                       "NORMAL": accessor(nrm, 5126, "VEC3", 34962, "sphere_NORMAL")},
        "indices": accessor(idx, 5125, "SCALAR", 34963, "sphere_indices"),
        "material": len(doc["materials"]) - 1, "mode": 4}]})
    doc["nodes"].append({"name": "sphere", "mesh": len(doc["meshes"]) - 1})
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(len(doc["nodes"]) - 1)
    doc["asset"]["generator"] = "irad scripts/make_sphere_box.py (data/cornell_box.gltf + sphere)"

    doc["buffers"] = [{}]
    out = pathlib.Path(args.output)
    total = write_glb(doc, blob, out)
    tris = base_tris + len(idx) // 3
    print(f"{out}: {tris} triangles ({len(idx) // 3} in the sphere), "
          f"{base_verts + len(pos) // 3} vertices, {total} bytes")


if __name__ == "__main__":
    main()
