#!/usr/bin/env python3
"""Generate two mirror scenes from the Cornell box (data/cornell_box.gltf), for seed section 5.1.2
(docs/ext/specular.md):

data/cornell_mirror.gltf: the left (red) wall turned into a perfect mirror.
data/cornell_mirror_panel.gltf: the box unchanged plus a mirror panel of the light's size lying on
the floor (1 mm above it, facing up, in front of the tall block), which throws the light's image
onto the ceiling and the tall block: the pyramid of the mirrored VPLs made visible. The panel
reuses the light's vertex data, placed by a node that turns it 180 degrees about x (a rotation:
the winding and the normals stay consistent) and moves it to x in [0.300, 0.430], z in [0.130,
0.235], between the blocks.

The red material becomes "mirror": baseColorFactor (0.9, 0.9, 0.9) = the mirror's reflectance,
metallicFactor 1 and roughnessFactor 0, which irad reads as a perfect mirror (metallicFactor >= 0.9
and roughnessFactor <= 0.1, core/gltf/read/materials.h). Everything else is unchanged. The measured
left wall is slightly non-planar, so its two triangles are two mirror planes that meet at a
0.47-degree kink.

Usage: python3 data/make_cornell_mirror.py
Writes both files next to this script. Standard library only; deterministic.
"""

import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


MIRROR = {
    "baseColorFactor": [0.9, 0.9, 0.9, 1.0],
    "metallicFactor": 1.0,
    "roughnessFactor": 0.0,
}


def load_box():
    with open(os.path.join(HERE, "cornell_box.gltf"), encoding="utf-8") as f:
        return json.load(f)


def save(doc, name):
    doc["asset"]["generator"] = "data/make_cornell_mirror.py"
    out = os.path.join(HERE, name)
    with open(out, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {out}")


def mirror_wall():
    doc = load_box()
    (red,) = [m for m in doc["materials"] if m["name"] == "red"]
    red["name"] = "mirror"
    red["pbrMetallicRoughness"] = dict(MIRROR)
    for node in doc["nodes"]:
        if node.get("name") == "red_wall":
            node["name"] = "mirror_wall"
    save(doc, "cornell_mirror.gltf")


def mirror_panel():
    doc = load_box()
    doc["materials"].append({"name": "mirror", "pbrMetallicRoughness": dict(MIRROR),
                             "doubleSided": False})
    (light,) = [m for m in doc["meshes"] if m["name"] == "light"]
    primitive = dict(light["primitives"][0])
    primitive["material"] = len(doc["materials"]) - 1
    doc["meshes"].append({"name": "mirror_panel", "primitives": [primitive]})
    # (x, y, z) -> (x + 0.087, 0.5497 - y, 0.462 - z): the light at y = 0.5487 lands at y = 0.001.
    doc["nodes"].append({"name": "mirror_panel", "mesh": len(doc["meshes"]) - 1,
                         "matrix": [1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0, 0.087, 0.5497, 0.462, 1]})
    doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    save(doc, "cornell_mirror_panel.gltf")


if __name__ == "__main__":
    mirror_wall()
    mirror_panel()
