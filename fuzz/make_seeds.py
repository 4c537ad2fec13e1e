#!/usr/bin/env python3
"""Writes the fuzzer's seed inputs into a folder (default: build-fuzz/seeds).

Seeds: data/cornell_box.gltf; the analytic scenes of `irad scene` (written by the irad binary
given with --irad, when it exists); and small hand-made scenes that reach every part of the
loader: GLB with a BIN chunk, an embedded PNG texture (bufferView and data URI), the external
files the fuzz target provides (buffer.bin, image.png), sparse accessors, strips and fans,
u8/u16 indices and normalized texcoords, a node hierarchy with TRS and matrix, cameras,
KHR_lights_punctual and KHR_materials_emissive_strength. Each .gltf seed also goes in as GLB.
"""
import argparse
import base64
import json
import pathlib
import struct
import subprocess
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent


def png_rgba(w, h, pixels):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\x00" + bytes(pixels[y * w * 4:(y + 1) * w * 4]) for y in range(h))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Doc:
    def __init__(self):
        self.d = {"asset": {"version": "2.0"}}
        self.bin = bytearray()

    def push(self, array, value):
        self.d.setdefault(array, []).append(value)
        return len(self.d[array]) - 1

    def view(self, data, stride=0):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.bin += data
        return self.push("bufferViews", v)

    def accessor(self, view, ctype, count, kind, **extra):
        a = {"componentType": ctype, "count": count, "type": kind}
        if view is not None:
            a["bufferView"] = view
        a.update(extra)
        return self.push("accessors", a)

    def floats(self, values, kind):
        n = {"VEC2": 2, "VEC3": 3}[kind]
        return self.accessor(self.view(struct.pack("<%df" % len(values), *values)), 5126,
                             len(values) // n, kind)

    def indices(self, values, ctype=5123):
        fmt = {5121: "B", 5123: "H", 5125: "I"}[ctype]
        return self.accessor(self.view(struct.pack("<%d%s" % (len(values), fmt), *values)), ctype,
                             len(values), "SCALAR")

    def gltf(self):
        d = dict(self.d)
        d["buffers"] = [{"byteLength": len(self.bin),
                         "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}]
        return json.dumps(d, separators=(",", ":")).encode()

    def glb(self):
        d = dict(self.d)
        d["buffers"] = [{"byteLength": len(self.bin)}]
        return glb(json.dumps(d, separators=(",", ":")).encode(), bytes(self.bin))


def glb(text, binary):
    text += b" " * (-len(text) % 4)
    out = struct.pack("<I4s", len(text), b"JSON") + text
    if binary:
        binary += b"\x00" * (-len(binary) % 4)
        out += struct.pack("<I4s", len(binary), b"BIN\x00") + binary
    return b"glTF" + struct.pack("<II", 2, 12 + len(out)) + out


def gltf_to_glb(text):
    d = json.loads(text)
    binary = b""
    buffers = d.get("buffers", [])
    if buffers and buffers[0].get("uri", "").startswith("data:"):
        binary = base64.b64decode(buffers[0]["uri"].split(",", 1)[1])
        del buffers[0]["uri"]
    return glb(json.dumps(d, separators=(",", ":")).encode(), binary)


QUAD = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
UP = [0, 0, 1] * 4


def lit_quad(doc, material_extra=None):
    m = {"emissiveFactor": [1, 0.5, 0.25]}
    m.update(material_extra or {})
    mat = doc.push("materials", m)
    prim = {"attributes": {"POSITION": doc.floats(QUAD, "VEC3"), "NORMAL": doc.floats(UP, "VEC3")},
            "indices": doc.indices([0, 1, 2, 0, 2, 3]), "material": mat}
    mesh = doc.push("meshes", {"primitives": [prim]})
    node = doc.push("nodes", {"mesh": mesh})
    doc.d["scenes"] = [{"nodes": [node]}]
    doc.d["scene"] = 0
    return prim


def textured():
    doc = Doc()
    prim = lit_quad(doc)
    prim["attributes"]["TEXCOORD_0"] = doc.floats([0, 0, 1, 0, 1, 1, 0, 1], "VEC2")
    pixels = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128]
    img = doc.push("images", {"bufferView": doc.view(png_rgba(2, 2, pixels)), "mimeType": "image/png"})
    img2 = doc.push("images", {"uri": "data:image/png;base64," +
                               base64.b64encode(png_rgba(1, 1, [9, 99, 199, 255])).decode()})
    smp = doc.push("samplers", {"wrapS": 33648, "wrapT": 33071})
    t0 = doc.push("textures", {"source": img, "sampler": smp})
    t1 = doc.push("textures", {"source": img2})
    doc.d["materials"][0]["pbrMetallicRoughness"] = {"baseColorFactor": [1, 1, 1, 1],
                                                     "baseColorTexture": {"index": t0}}
    doc.d["materials"][0]["emissiveTexture"] = {"index": t1}
    return doc


def external():
    # buffer.bin and image.png are the files the fuzz target writes beside every input.
    d = {"asset": {"version": "2.0"},
         "buffers": [{"byteLength": 64, "uri": "buffer.bin"}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}],
         "images": [{"uri": "image.png"}],
         "textures": [{"source": 0}],
         "materials": [{"emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 6, "material": 0}]}],
         "nodes": [{"mesh": 0}]}
    return json.dumps(d, separators=(",", ":")).encode()


def sparse_strips():
    doc = Doc()
    prim = lit_quad(doc)
    base = doc.floats(QUAD, "VEC3")
    idx = doc.view(struct.pack("<2B", 1, 3))
    val = doc.view(struct.pack("<6f", 2, 0, 0, 0, 2, 0))
    doc.d["accessors"][base]["sparse"] = {"count": 2, "indices": {"bufferView": idx, "componentType": 5121},
                                          "values": {"bufferView": val}}
    zero = doc.accessor(None, 5126, 4, "VEC3", sparse={
        "count": 1, "indices": {"bufferView": idx, "componentType": 5121},
        "values": {"bufferView": val}})
    uv8 = doc.accessor(doc.view(bytes([0, 0, 255, 0, 255, 255, 0, 255])), 5121, 4, "VEC2", normalized=True)
    strip = {"attributes": {"POSITION": base, "TEXCOORD_0": uv8}, "mode": 5,
             "indices": doc.indices([0, 1, 3, 2], 5121)}
    fan = {"attributes": {"POSITION": zero}, "mode": 6}
    lines = {"attributes": {"POSITION": base}, "mode": 1}
    doc.d["meshes"][0]["primitives"] += [strip, fan, lines]
    return doc


def hierarchy():
    doc = Doc()
    lit_quad(doc, {"doubleSided": True, "extensions": {
        "KHR_materials_emissive_strength": {"emissiveStrength": 4}}})
    doc.d["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_lights_punctual"]
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 1, 1], "intensity": 3},
        {"type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.6}},
        {"type": "directional"}]}}
    doc.d["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "zfar": 100,
                                                                "aspectRatio": 1.5}},
                        {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 1}}]
    nodes = doc.d["nodes"]
    nodes[0].update({"translation": [1, 2, 3], "rotation": [0, 0, 0.7071068, 0.7071068],
                     "scale": [1, -1, 2], "children": [1, 2, 3]})
    nodes.append({"camera": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1]})
    nodes.append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 0, 1]})
    nodes.append({"extensions": {"KHR_lights_punctual": {"light": 1}}, "children": [4]})
    nodes.append({"camera": 1, "mesh": 0})
    return doc


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("out", nargs="?", default=str(ROOT / "build-fuzz" / "seeds"))
    parser.add_argument("--irad", default=str(ROOT / "build" / "bin" / "irad"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    seeds = {"cornell_box.gltf": (ROOT / "data" / "cornell_box.gltf").read_bytes()}
    if pathlib.Path(args.irad).exists():
        for name, extra in [("furnace-box", []), ("square-light", []),
                            ("integrating-sphere", ["--subdivisions", "0"])]:
            path = out / (name + ".gltf")
            subprocess.run([args.irad, "scene", name, "-o", str(path)] + extra, check=True,
                           stdout=subprocess.DEVNULL)
            seeds[path.name] = path.read_bytes()
    for name, doc in [("textured", textured()), ("sparse_strips", sparse_strips()),
                      ("hierarchy", hierarchy())]:
        seeds[name + ".gltf"] = doc.gltf()
        seeds[name + ".glb"] = doc.glb()
    seeds["external.gltf"] = external()
    for name in list(seeds):
        if name.endswith(".gltf") and not name.startswith("external"):
            seeds.setdefault(name[:-5] + ".glb", gltf_to_glb(seeds[name]))
    for name, data in seeds.items():
        (out / name).write_bytes(data)
    print(f"{len(seeds)} seeds in {out}")


if __name__ == "__main__":
    main()
