#!/usr/bin/env python3
"""Generate data/cornell_mirror.gltf: the Cornell box (data/cornell_box.gltf) with its left
(red) wall turned into a perfect mirror (seed section 5.1.2, docs/ext/specular.md).

The red material becomes "mirror": baseColorFactor (0.9, 0.9, 0.9) = the mirror's reflectance,
metallicFactor 1 and roughnessFactor 0, which irad reads as a perfect mirror (metallicFactor >= 0.9
and roughnessFactor <= 0.1, core/gltf_materials.h). Everything else is unchanged. The measured
left wall is slightly non-planar, so its two triangles are two mirror planes that meet at a
0.3-degree kink.

Usage: python3 data/make_cornell_mirror.py [OUT]
OUT defaults to cornell_mirror.gltf next to this script. Standard library only; deterministic.
"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "cornell_mirror.gltf")
    with open(os.path.join(HERE, "cornell_box.gltf"), encoding="utf-8") as f:
        doc = json.load(f)
    (red,) = [m for m in doc["materials"] if m["name"] == "red"]
    red["name"] = "mirror"
    red["pbrMetallicRoughness"] = {
        "baseColorFactor": [0.9, 0.9, 0.9, 1.0],
        "metallicFactor": 1.0,
        "roughnessFactor": 0.0,
    }
    for node in doc["nodes"]:
        if node.get("name") == "red_wall":
            node["name"] = "mirror_wall"
    doc["asset"]["generator"] = "data/make_cornell_mirror.py"
    with open(out, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
