#!/usr/bin/env python3
"""Generate data/cornell_glossy.gltf: the Cornell box (data/cornell_box.gltf) with glTF
metallic-roughness materials (docs/materials.md): the tall block rough metal (metallicFactor 1,
roughnessFactor 0.3), the short block glossy plastic (metallicFactor 0, roughnessFactor 0.2) and
the floor semi-gloss (metallicFactor 0, roughnessFactor 0.45), all three with the white's base
colour and glTF's default specular (no KHR_materials_specular: specularFactor 1, ior 1.5). The
walls, the ceiling and the light stay Lambertian by declaration.

Usage: python3 data/make_cornell_glossy.py
Writes the file next to this script. Standard library only; deterministic.
"""

import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))

# mesh name -> (material name, metallicFactor, roughnessFactor)
GLOSSY = {
    "tall_block": ("rough_metal", 1.0, 0.3),
    "short_block": ("glossy_plastic", 0.0, 0.2),
    "floor": ("semi_gloss_floor", 0.0, 0.45),
}


def main():
    with open(os.path.join(HERE, "cornell_box.gltf"), encoding="utf-8") as f:
        doc = json.load(f)
    (white,) = [m for m in doc["materials"] if m["name"] == "white"]
    for mesh in doc["meshes"]:
        if mesh["name"] not in GLOSSY:
            continue
        name, metallic, roughness = GLOSSY[mesh["name"]]
        m = copy.deepcopy(white)
        m["name"] = name
        m["pbrMetallicRoughness"]["metallicFactor"] = metallic
        m["pbrMetallicRoughness"]["roughnessFactor"] = roughness
        del m["extensions"]  # glTF's specular: specularFactor 1
        doc["materials"].append(m)
        for primitive in mesh["primitives"]:
            primitive["material"] = len(doc["materials"]) - 1
    doc["asset"]["generator"] = "data/make_cornell_glossy.py"
    out = os.path.join(HERE, "cornell_glossy.gltf")
    with open(out, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
