#!/usr/bin/env python3
"""Generate data/cornell_animated.gltf: the Cornell box (data/cornell_box.gltf) with a 10-second
animation exercising every glTF interpolation on meshes, a light and a camera.

* short block: turns 90 degrees about its own vertical axis (CUBICSPLINE rotation of a pivot
  node at the block's centre, with zero tangents: an ease-in/ease-out turn) while sliding
  towards the green wall and back (LINEAR translation of the same pivot); the mesh hangs below
  the pivot on a child node translated by minus the centre, so the hierarchy is exercised too.
* tall block: jumps 8 cm towards the red wall at t = 5 s (STEP translation).
* ceiling light: slides 10 cm along x and back (LINEAR translation), staying on the ceiling.
* camera: a fly-through from the box's opening towards the back wall and out, with a slow yaw
  (LINEAR translation and rotation, slerped by the renderer).

Usage: /usr/bin/python3 data/make_cornell_animated.py [OUT]  (reads cornell_box.gltf next to
this script; standard library only; byte-for-byte deterministic.)
"""

import base64
import json
import math
import os
import struct
import sys

FLOAT = 5126
DURATION = 10.0
HERE = os.path.dirname(os.path.abspath(__file__))


def quat_y(degrees):
    a = math.radians(degrees) / 2.0
    return [0.0, math.sin(a), 0.0, math.cos(a)]


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


class Blob:
    """Appends float accessors to the file's single buffer."""

    def __init__(self, gltf):
        self.gltf = gltf
        uri = gltf["buffers"][0]["uri"]
        self.data = bytearray(base64.b64decode(uri.split(",", 1)[1]))

    def accessor(self, rows, type_, name, minmax=False):
        while len(self.data) % 4:
            self.data.append(0)
        offset = len(self.data)
        flat = [v for row in rows for v in (row if isinstance(row, (list, tuple)) else [row])]
        self.data += struct.pack("<%df" % len(flat), *flat)
        views = self.gltf["bufferViews"]
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": 4 * len(flat)})
        acc = {"name": name, "bufferView": len(views) - 1, "componentType": FLOAT,
               "count": len(rows), "type": type_}
        if minmax:  # glTF requires min/max on animation inputs
            acc["min"] = [min(rows)]
            acc["max"] = [max(rows)]
        self.gltf["accessors"].append(acc)
        return len(self.gltf["accessors"]) - 1

    def finish(self):
        buf = self.gltf["buffers"][0]
        buf["byteLength"] = len(self.data)
        buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.data)).decode()


def block_centre(gltf, mesh_name):
    mesh = next(m for m in gltf["meshes"] if m["name"] == mesh_name)
    acc = gltf["accessors"][mesh["primitives"][0]["attributes"]["POSITION"]]
    return [0.5 * (a + b) for a, b in zip(acc["min"], acc["max"])]


def node_index(gltf, name):
    return next(i for i, n in enumerate(gltf["nodes"]) if n["name"] == name)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "cornell_animated.gltf")
    with open(os.path.join(HERE, "cornell_box.gltf")) as f:
        gltf = json.load(f)
    blob = Blob(gltf)
    nodes = gltf["nodes"]
    samplers, channels = [], []

    def animate(node, path, times, values, interpolation, type_):
        t = blob.accessor(times, "SCALAR", "%s_%s_t" % (nodes[node]["name"], path), True)
        v = blob.accessor(values, type_, "%s_%s_v" % (nodes[node]["name"], path))
        samplers.append({"input": t, "output": v, "interpolation": interpolation})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})

    # Short block: pivot at its centre (floor level), the mesh on a child node.
    short = node_index(gltf, "short_block")
    c = block_centre(gltf, "short_block")
    pivot_at = [c[0], 0.0, c[2]]
    nodes[short]["translation"] = [-v for v in pivot_at]
    nodes.append({"name": "short_block_pivot", "translation": pivot_at, "children": [short]})
    pivot = len(nodes) - 1
    roots = gltf["scenes"][0]["nodes"]
    roots[roots.index(short)] = pivot
    keys = [0.0, 5.0, 10.0]
    zero = [0.0, 0.0, 0.0, 0.0]
    turn = []
    for angle in (0.0, 90.0, 0.0):  # CUBICSPLINE: (in-tangent, value, out-tangent) per key
        turn += [zero, quat_y(angle), zero]
    animate(pivot, "rotation", keys, turn, "CUBICSPLINE", "VEC4")
    slide = [pivot_at, [pivot_at[0] - 0.06, 0.0, pivot_at[2] + 0.04], pivot_at]
    animate(pivot, "translation", keys, slide, "LINEAR", "VEC3")

    # Tall block: a jump at t = 5 s.
    tall = node_index(gltf, "tall_block")
    animate(tall, "translation", [0.0, 5.0], [[0.0, 0.0, 0.0], [0.08, 0.0, 0.0]], "STEP", "VEC3")

    # Ceiling light: slides along x and back.
    light = node_index(gltf, "light")
    animate(light, "translation", [0.0, 2.5, 7.5, 10.0],
            [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.0]], "LINEAR", "VEC3")

    # Camera: into the box and out again, with a slow yaw.
    cam = node_index(gltf, "cornell_camera")
    start = nodes[cam]["translation"]
    base = nodes[cam]["rotation"]
    times = [0.0, 3.0, 6.0, 10.0]
    path = [start, [0.20, 0.26, -0.45], [0.36, 0.30, -0.30], start]
    yaw = [0.0, 12.0, -15.0, 0.0]
    animate(cam, "translation", times, path, "LINEAR", "VEC3")
    animate(cam, "rotation", times, [quat_mul(quat_y(a), base) for a in yaw], "LINEAR", "VEC4")

    gltf["animations"] = [{"name": "walkthrough", "samplers": samplers, "channels": channels}]
    blob.finish()
    with open(out, "w") as f:
        json.dump(gltf, f, indent=1, sort_keys=False)
        f.write("\n")
    print("wrote %s (%.0f s animation, %d channels)" % (out, DURATION, len(channels)))


if __name__ == "__main__":
    main()
