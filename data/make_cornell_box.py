#!/usr/bin/env python3
"""Generate data/cornell_box.gltf: the measured Cornell box as a single glTF 2.0 file.

Source of the data
------------------
Cornell University Program of Computer Graphics, "Cornell Box Data"
(https://www.graphics.cornell.edu/online/box/data.html). Every vertex below is
copied from that table (millimetres) exactly as measured, including the
slightly non-square floor, ceiling and walls (e.g. the floor's far edge is at
x = 549.6 while its near edge is at x = 552.8, and the red wall is not planar).
The blocks keep their top and four side faces; they have no bottom face.
Reflectances and the light's radiance (17, 12, 4) are RGB values commonly used
for this scene in renderer test scenes, chosen for irad; they are not derived
from the spectral measurements on the original page.

Conventions
-----------
* Units: metres (the published millimetres times 0.001). Right-handed, +y up,
  exactly the published frame: the camera is at z = -0.8 looking down +z, so
  +x points to the viewer's left. The green wall is at x = 0 (viewer's right,
  "right wall"), the red wall at x ~ 0.55 (viewer's left, "left wall"), the
  back wall at z = 0.5592 and the open side of the box at z = 0.
* All geometry is stored in world coordinates; mesh nodes have no transform.
* Every quad is wound counter-clockwise when seen from the side it faces
  (walls, floor and ceiling face into the box, block faces face outward, the
  light faces down, -y), and carries a flat per-quad NORMAL consistent with
  that winding (Newell normal of the quad, so it is well defined for the one
  non-planar wall). Quads are split along their 0-2 diagonal. If a published
  quad's vertex order winds the other way it is reversed; this is reported on
  stdout.
* Materials are metallic-roughness with metallicFactor 0, roughnessFactor 1 and
  KHR_materials_specular specularFactor 0: Lambertian by declaration (f_r =
  baseColor/pi exactly), baseColorFactor in linear RGB, single sided.
  The light's radiance (17, 12, 4) is encoded as emissiveFactor
  (1, 12/17, 4/17) times KHR_materials_emissive_strength 17.
* The light quad is moved from y = 548.8 mm (the ceiling) to 548.7 mm so the
  two surfaces do not coincide.
* The camera follows the published data: position (278, 273, -800) mm,
  direction +z, up +y, 35 mm focal length with a 25 mm x 25 mm film, i.e.
  yfov = 2 atan(12.5 / 35), aspect ratio 1. glTF cameras look down their local
  -z, so the node is rotated 180 degrees about +y (quaternion [0, 1, 0, 0]).

Usage: python3 data/make_cornell_box.py [OUT]
OUT defaults to cornell_box.gltf next to this script. Standard library only;
the output is byte-for-byte deterministic. The script validates what it wrote
by reloading and decoding it.
"""

import base64
import json
import math
import os
import struct
import sys

MM_TO_M = 0.001

# ---------------------------------------------------------------------------
# Published measurements (mm). Quads as listed on the Cornell page.
# ---------------------------------------------------------------------------
FLOOR = [
    [(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)],
]
CEILING = [
    [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)],
]
BACK_WALL = [
    [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)],
]
GREEN_WALL = [  # "Right wall -- green"
    [(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)],
]
RED_WALL = [  # "Left wall -- red"
    [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)],
]
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]
LIGHT_Y = 548.7  # published at 548.8 (= ceiling); lowered 0.1 mm
LIGHT = [
    [(343.0, LIGHT_Y, 227.0), (343.0, LIGHT_Y, 332.0), (213.0, LIGHT_Y, 332.0), (213.0, LIGHT_Y, 227.0)],
]

CAMERA_POS_MM = (278.0, 273.0, -800.0)
CAMERA_FOCAL_MM = 35.0
CAMERA_FILM_MM = 25.0

WHITE = (0.725, 0.71, 0.68)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
LIGHT_ALBEDO = (0.78, 0.78, 0.78)
LIGHT_RADIANCE = (17.0, 12.0, 4.0)

# Box interior reference point used to decide which way walls must face.
BOX_CENTER_MM = (278.0, 274.4, 279.6)

# (name, quads, material name, facing rule)
#   "inward":  normal points towards BOX_CENTER_MM
#   "outward": normal points away from the block's own centre
#   "down":    normal has negative y
SURFACES = [
    ("floor", FLOOR, "white", "inward"),
    ("ceiling", CEILING, "white", "inward"),
    ("back_wall", BACK_WALL, "white", "inward"),
    ("red_wall", RED_WALL, "red", "inward"),
    ("green_wall", GREEN_WALL, "green", "inward"),
    ("short_block", SHORT_BLOCK, "white", "outward"),
    ("tall_block", TALL_BLOCK, "white", "outward"),
    ("light", LIGHT, "light", "down"),
]
EXPECTED_TRIANGLES = {
    "floor": 2, "ceiling": 2, "back_wall": 2, "red_wall": 2, "green_wall": 2,
    "short_block": 10, "tall_block": 10, "light": 2,
}

FLOAT = 5126
UNSIGNED_SHORT = 5123
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963
TRIANGLES = 4


# ---------------------------------------------------------------------------
# Small vector helpers
# ---------------------------------------------------------------------------
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    assert n > 0.0, "zero-length vector"
    return (a[0] / n, a[1] / n, a[2] / n)


def mean(points):
    n = float(len(points))
    return tuple(sum(p[i] for p in points) / n for i in range(3))


def f32(x):
    """Round a Python float to the nearest float32 (returned as float)."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def newell_normal(quad):
    n = [0.0, 0.0, 0.0]
    for i, a in enumerate(quad):
        b = quad[(i + 1) % len(quad)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    # "+ 0.0" turns -0.0 into 0.0 so the output has no negative zeros.
    return tuple(c + 0.0 for c in normalize(tuple(n)))


QUAD_TRIANGLES = ((0, 1, 2), (0, 2, 3))


def check_triangle(p0, p1, p2, normal, what):
    """CCW seen from the side `normal` points to, and non-degenerate."""
    c = cross(sub(p1, p0), sub(p2, p0))
    area = 0.5 * length(c)
    assert area > 1e-8, "%s: degenerate triangle (area %g m^2)" % (what, area)
    assert dot(c, normal) > 0.0, "%s: winding disagrees with normal" % what
    # Flat normal should also be close to each triangle's own normal.
    assert dot(normalize(c), normal) > 0.99, "%s: normal far from triangle plane" % what


# ---------------------------------------------------------------------------
# Build the geometry (metres, oriented quads)
# ---------------------------------------------------------------------------
def build_surfaces():
    surfaces = []
    box_center = tuple(c * MM_TO_M for c in BOX_CENTER_MM)
    for name, quads_mm, material, facing in SURFACES:
        quads = [[tuple(c * MM_TO_M for c in v) for v in q] for q in quads_mm]
        if facing == "outward":
            top_y = max(v[1] for q in quads for v in q)
            all_v = [v for q in quads for v in q]
            c = mean(all_v)
            ref = (c[0], 0.5 * top_y, c[2])
        out_quads = []
        for qi, quad in enumerate(quads):
            n = newell_normal(quad)
            centroid = mean(quad)
            if facing == "inward":
                want = sub(box_center, centroid)
            elif facing == "outward":
                want = sub(centroid, ref)
            else:
                want = (0.0, -1.0, 0.0)
            if dot(n, want) <= 0.0:
                print("note: %s quad %d reversed to face %s" % (name, qi, facing))
                quad = [quad[0]] + quad[:0:-1]
                n = newell_normal(quad)
            assert dot(n, want) > 0.0
            for t in QUAD_TRIANGLES:
                check_triangle(quad[t[0]], quad[t[1]], quad[t[2]], n,
                               "%s quad %d" % (name, qi))
            out_quads.append((quad, n))
        surfaces.append((name, out_quads, material))
    return surfaces


# ---------------------------------------------------------------------------
# glTF assembly
# ---------------------------------------------------------------------------
def pad4(data, fill=b"\x00"):
    return data + fill * ((4 - len(data) % 4) % 4)


def material(name, rgb, extra=None):
    m = {
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": [rgb[0], rgb[1], rgb[2], 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
        },
        "doubleSided": False,
        # Lambertian by declaration (design.md 1b): metallic 0 and specular 0 give f_r = rho/pi.
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}},
    }
    if extra:
        extensions = dict(m["extensions"], **extra.pop("extensions", {}))
        m.update(extra)
        m["extensions"] = extensions
    return m


def build_gltf(surfaces):
    peak = max(LIGHT_RADIANCE)
    materials = [
        material("white", WHITE),
        material("red", RED),
        material("green", GREEN),
        material("light", LIGHT_ALBEDO, {
            "emissiveFactor": [c / peak for c in LIGHT_RADIANCE],
            "extensions": {
                "KHR_materials_emissive_strength": {"emissiveStrength": peak},
            },
        }),
    ]
    material_index = {m["name"]: i for i, m in enumerate(materials)}

    blob = bytearray()
    buffer_views, accessors, meshes, nodes = [], [], [], []

    def add_view(data, target):
        assert len(blob) % 4 == 0
        buffer_views.append({
            "buffer": 0,
            "byteOffset": len(blob),
            "byteLength": len(data),
            "target": target,
        })
        blob.extend(pad4(data))
        return len(buffer_views) - 1

    for name, quads, mat in surfaces:
        positions, normals, indices = [], [], []
        for quad, n in quads:
            base = len(positions)
            for v in quad:
                positions.append(tuple(f32(c) for c in v))
                normals.append(tuple(f32(c) for c in n))
            for t in QUAD_TRIANGLES:
                indices.extend(base + i for i in t)
        assert len(positions) < 65535

        pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
        nrm_bytes = b"".join(struct.pack("<3f", *n) for n in normals)
        idx_bytes = struct.pack("<%dH" % len(indices), *indices)

        pos_view = add_view(pos_bytes, ARRAY_BUFFER)
        nrm_view = add_view(nrm_bytes, ARRAY_BUFFER)
        idx_view = add_view(idx_bytes, ELEMENT_ARRAY_BUFFER)

        # positions are already float32-exact, so min/max match the data.
        accessors.append({
            "name": name + "_POSITION",
            "bufferView": pos_view,
            "componentType": FLOAT,
            "count": len(positions),
            "type": "VEC3",
            "min": [min(p[i] for p in positions) for i in range(3)],
            "max": [max(p[i] for p in positions) for i in range(3)],
        })
        accessors.append({
            "name": name + "_NORMAL",
            "bufferView": nrm_view,
            "componentType": FLOAT,
            "count": len(normals),
            "type": "VEC3",
        })
        accessors.append({
            "name": name + "_indices",
            "bufferView": idx_view,
            "componentType": UNSIGNED_SHORT,
            "count": len(indices),
            "type": "SCALAR",
        })
        a = len(accessors)
        meshes.append({
            "name": name,
            "primitives": [{
                "attributes": {"POSITION": a - 3, "NORMAL": a - 2},
                "indices": a - 1,
                "material": material_index[mat],
                "mode": TRIANGLES,
            }],
        })
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    yfov = 2.0 * math.atan(0.5 * CAMERA_FILM_MM / CAMERA_FOCAL_MM)
    cameras = [{
        "name": "cornell_camera",
        "type": "perspective",
        "perspective": {"aspectRatio": 1.0, "yfov": yfov, "znear": 0.01},
    }]
    nodes.append({
        "name": "cornell_camera",
        "camera": 0,
        "translation": [c * MM_TO_M for c in CAMERA_POS_MM],
        "rotation": [0.0, 1.0, 0.0, 0.0],
    })

    uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode("ascii")
    return {
        "asset": {"version": "2.0", "generator": "irad data/make_cornell_box.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_specular"],
        "scene": 0,
        "scenes": [{"name": "cornell_box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": cameras,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"byteLength": len(blob), "uri": uri}],
    }


# ---------------------------------------------------------------------------
# Validation of the written file (independent of the in-memory build)
# ---------------------------------------------------------------------------
def validate(path):
    with open(path, "r", encoding="utf-8") as f:
        g = json.load(f)

    assert g["asset"]["version"] == "2.0"
    assert g["extensionsUsed"] == ["KHR_materials_emissive_strength", "KHR_materials_specular"]
    assert len(g["buffers"]) == 1
    uri = g["buffers"][0]["uri"]
    prefix = "data:application/octet-stream;base64,"
    assert uri.startswith(prefix)
    blob = base64.b64decode(uri[len(prefix):], validate=True)
    assert len(blob) == g["buffers"][0]["byteLength"]

    comp = {FLOAT: ("f", 4), UNSIGNED_SHORT: ("H", 2)}
    ncomp = {"SCALAR": 1, "VEC3": 3}

    def read(ai):
        acc = g["accessors"][ai]
        bv = g["bufferViews"][acc["bufferView"]]
        fmt, size = comp[acc["componentType"]]
        nc = ncomp[acc["type"]]
        off = bv["byteOffset"] + acc.get("byteOffset", 0)
        assert off % 4 == 0 and bv["byteOffset"] % 4 == 0
        assert acc["count"] * nc * size <= bv["byteLength"]
        assert bv["byteOffset"] + bv["byteLength"] <= len(blob)
        vals = struct.unpack_from("<%d%s" % (acc["count"] * nc, fmt), blob, off)
        if nc == 1:
            return list(vals), acc, bv
        return [tuple(vals[i:i + nc]) for i in range(0, len(vals), nc)], acc, bv

    box_center = tuple(c * MM_TO_M for c in BOX_CENTER_MM)
    total = 0
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for mesh in g["meshes"]:
        assert len(mesh["primitives"]) == 1
        prim = mesh["primitives"][0]
        assert prim.get("mode", 4) == TRIANGLES
        pos, pacc, pbv = read(prim["attributes"]["POSITION"])
        nrm, nacc, nbv = read(prim["attributes"]["NORMAL"])
        idx, iacc, ibv = read(prim["indices"])
        assert pbv["target"] == ARRAY_BUFFER and nbv["target"] == ARRAY_BUFFER
        assert ibv["target"] == ELEMENT_ARRAY_BUFFER
        assert pacc["componentType"] == FLOAT and nacc["componentType"] == FLOAT
        assert iacc["componentType"] == UNSIGNED_SHORT
        assert len(pos) == len(nrm) == pacc["count"] == nacc["count"]
        for i in range(3):
            assert pacc["min"][i] == min(p[i] for p in pos), mesh["name"]
            assert pacc["max"][i] == max(p[i] for p in pos), mesh["name"]
            lo[i] = min(lo[i], pacc["min"][i])
            hi[i] = max(hi[i], pacc["max"][i])
        assert len(idx) % 3 == 0 and all(0 <= i < len(pos) for i in idx)
        ntri = len(idx) // 3
        assert ntri == EXPECTED_TRIANGLES[mesh["name"]], (mesh["name"], ntri)
        total += ntri
        for n in nrm:
            assert abs(length(n) - 1.0) < 1e-6
        for t in range(ntri):
            a, b, c = idx[3 * t:3 * t + 3]
            n = nrm[a]
            assert nrm[b] == n and nrm[c] == n, "normal not flat"
            check_triangle(pos[a], pos[b], pos[c], n, "%s tri %d" % (mesh["name"], t))
            centroid = mean([pos[a], pos[b], pos[c]])
            if mesh["name"] == "light":
                assert n[1] < -0.999
            elif not mesh["name"].endswith("_block"):
                assert dot(n, sub(box_center, centroid)) > 0.0, mesh["name"]
    # 5 room surfaces x 2 + light 2 + 2 blocks x 10 = 32
    assert total == sum(EXPECTED_TRIANGLES.values()) == 32, total
    assert sorted(m["name"] for m in g["meshes"]) == sorted(EXPECTED_TRIANGLES)

    # Camera
    cam_nodes = [n for n in g["nodes"] if "camera" in n]
    assert len(cam_nodes) == 1
    cam = g["cameras"][cam_nodes[0]["camera"]]
    assert cam["name"] == "cornell_camera"
    assert abs(cam["perspective"]["yfov"] - 2 * math.atan(12.5 / 35.0)) < 1e-12
    assert g["nodes"].index(cam_nodes[0]) in g["scenes"][g["scene"]]["nodes"]
    # local -z rotated by [0,1,0,0] is +z
    x, y, z, w = cam_nodes[0]["rotation"]
    assert (x, y, z, w) == (0.0, 1.0, 0.0, 0.0)

    light = [m for m in g["materials"] if m["name"] == "light"][0]
    s = light["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"]
    radiance = [c * s for c in light["emissiveFactor"]]
    assert all(abs(r - e) < 1e-12 for r, e in zip(radiance, LIGHT_RADIANCE))
    return total, lo, hi


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print("usage: %s [OUT]" % argv[0])
        return 0 if len(argv) == 2 else 2
    out = argv[1] if len(argv) == 2 else os.path.join(here, "cornell_box.gltf")

    gltf = build_gltf(build_surfaces())
    text = json.dumps(gltf, indent=2, ensure_ascii=True, allow_nan=False) + "\n"
    with open(out, "w", encoding="ascii", newline="\n") as f:
        f.write(text)

    total, lo, hi = validate(out)
    print("wrote %s: %d triangles, bounds min (%.4f, %.4f, %.4f) max (%.4f, %.4f, %.4f) m"
          % (out, total, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
