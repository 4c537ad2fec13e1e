#!/usr/bin/env python3
"""Writes the fuzzer's seed inputs into a folder (default: build-fuzz/seeds).

Seeds: data/cornell_box.gltf; the analytic scenes of `irad scene` (written by the irad binary
given with --irad, when it exists); and small hand-made scenes that reach every part of the
loader: GLB with a BIN chunk, an embedded PNG texture (bufferView and data URI), the external
files the fuzz target provides (buffer.bin, image.png), sparse accessors, strips and fans,
u8/u16 indices and normalized texcoords, a node hierarchy with TRS and matrix, cameras,
KHR_lights_punctual and KHR_materials_emissive_strength. Each .gltf seed also goes in as GLB.

Seeds for the loader's decoders and extensions: a KHR_draco_mesh_compression cube,
an EXT_meshopt_compression cube (ATTRIBUTES with no filter, OCTAHEDRAL and EXPONENTIAL filters,
TRIANGLES; a fallback buffer without data; KHR_mesh_quantization normals), EXT_texture_webp
textures (a 2x2 lossless WebP), KHR_texture_transform with texCoord 1, a skin with morph targets
(one of them a sparse accessor), and KHR_mesh_quantization positions, normals and texcoords.
Python cannot encode Draco, meshopt or WebP: those bytes are SEED_BYTES below, printed by
fuzz/seed_bytes.cpp with the libraries' own encoders (see there how to rebuild them).
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
        self.extra_buffers = []  # buffers after buffer 0 (the one of self.bin)

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

    def floats_kind(self, values, kind):
        return self.accessor(self.view(struct.pack("<%df" % len(values), *values)), 5126,
                             len(values) // {"VEC4": 4, "MAT4": 16}[kind], kind)

    def indices(self, values, ctype=5123):
        fmt = {5121: "B", 5123: "H", 5125: "I"}[ctype]
        return self.accessor(self.view(struct.pack("<%d%s" % (len(values), fmt), *values)), ctype,
                             len(values), "SCALAR")

    def gltf(self):
        d = dict(self.d)
        d["buffers"] = [{"byteLength": len(self.bin),
                         "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}] + self.extra_buffers
        return json.dumps(d, separators=(",", ":")).encode()

    def glb(self):
        d = dict(self.d)
        d["buffers"] = [{"byteLength": len(self.bin)}] + self.extra_buffers
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


# fuzz/seed_bytes.cpp's output (base64): Draco, meshopt and WebP bytes of the seeds below.
SEED_BYTES = json.loads(r"""
{
  "draco": {"bytes": "RFJBQ08CAgEBAAAACAwCCwAAA29bBQEBEFUEQ0W8R1UEQ0W8RwP/AAAAAQABAQABAAkDAAACAQEJAwABAwEDCQIAAgIBAQEAAwMBMAEQAwAoljAYpRgAAAAA/wcAAAAAgL8AAIC/AACAvwAAAEALAAMBAQGBCFk1////////////////////91UFVQUHnK9Q9Wq3nf8HAAD/AwAACwEBAQEBA1UhARCtDguTc1m+dVHhsNj2pwAAAAD/BwAAAAAAAAAAAAAAAIA/Cw==", "points": 24, "faces": 12, "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
  "meshopt": {"count": 24, "triangles": 36, "positions": "oAAAAAUAwAzz//////8zDAAA////AAAABTMMAMD/////DPMAAP////8AAAAFDPMzDP////////8AwAAA/wAAAAAAAAAAAAAAAAAAAAAAAAAAAACAPwAAgL8AAIC/", "normals_oct8": "oAUAwMAABP4AwAAA/gUAAMDA/gTAwAAA/v4AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAB/AH8A", "uvs_exp": "oAAGCAcIBwgHCAczMwAACAcIBwAFIGBgYGBgAAAABgCAcIBwgHCAzMwAAAcIBwgABSBgYGBgYAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA9QAAAPU=", "indices_u16": "4PAA8ADwAPAA8ADwAAB2h1ZneKmGZYlomAFpAAA="},
  "webp": "UklGRjAAAABXRUJQVlA4TCMAAAAvAUAAEB8gEEjeHzqN+RcQFPwfnYCg6LrlImYPwg0YIvofAgA="
}
""")


def b64(name, key=None):
    v = SEED_BYTES[name] if key is None else SEED_BYTES[name][key]
    return base64.b64decode(v)


def uses(doc, *extensions, required=True):
    doc.d.setdefault("extensionsUsed", []).extend(extensions)
    if required:
        doc.d.setdefault("extensionsRequired", []).extend(extensions)


def mesh_node(doc, prim, **node):
    mesh = doc.push("meshes", {"primitives": [prim]})
    node["mesh"] = mesh
    n = doc.push("nodes", node)
    doc.d["scenes"] = [{"nodes": [n]}]
    doc.d["scene"] = 0
    return n


def bounded_quad(doc, material_extra=None):
    prim = lit_quad(doc, material_extra)
    doc.d["accessors"][prim["attributes"]["POSITION"]].update(min=[0, 0, 0], max=[1, 1, 0])
    return prim


def draco():
    doc = Doc()
    dr = SEED_BYTES["draco"]
    view = doc.view(b64("draco", "bytes"))
    points = dr["points"]
    pos = doc.accessor(None, 5126, points, "VEC3", min=[-1, -1, -1], max=[1, 1, 1])
    nrm = doc.accessor(None, 5126, points, "VEC3")
    uv = doc.accessor(None, 5126, points, "VEC2")
    idx = doc.accessor(None, 5123, 3 * dr["faces"], "SCALAR")
    mat = doc.push("materials", {"emissiveFactor": [1, 0.8, 0.6]})
    prim = {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, "indices": idx,
            "material": mat, "extensions": {"KHR_draco_mesh_compression": {
                "bufferView": view, "attributes": {k: dr[k] for k in
                                                   ("POSITION", "NORMAL", "TEXCOORD_0")}}}}
    mesh_node(doc, prim)
    uses(doc, "KHR_draco_mesh_compression")
    return doc


def meshopt():
    doc = Doc()
    mo = SEED_BYTES["meshopt"]
    count, fallback = mo["count"], [0]

    def stream(key, stride, n, mode, filt=None, target_stride=True):
        data = b64("meshopt", key)
        while len(doc.bin) % 4:
            doc.bin.append(0)
        ext = {"buffer": 0, "byteOffset": len(doc.bin), "byteLength": len(data),
               "byteStride": stride, "count": n, "mode": mode}
        if filt:
            ext["filter"] = filt
        doc.bin += data
        v = {"buffer": 1, "byteOffset": fallback[0], "byteLength": n * stride,
             "extensions": {"EXT_meshopt_compression": ext}}
        if target_stride:
            v["byteStride"] = stride
        fallback[0] += (n * stride + 3) // 4 * 4
        return doc.push("bufferViews", v)

    pos = doc.accessor(stream("positions", 12, count, "ATTRIBUTES"), 5126, count, "VEC3",
                       min=[-1, -1, -1], max=[1, 1, 1])
    nrm = doc.accessor(stream("normals_oct8", 4, count, "ATTRIBUTES", "OCTAHEDRAL"), 5120, count,
                       "VEC3", normalized=True)
    uv = doc.accessor(stream("uvs_exp", 8, count, "ATTRIBUTES", "EXPONENTIAL"), 5126, count, "VEC2")
    idx = doc.accessor(stream("indices_u16", 2, mo["triangles"], "TRIANGLES", target_stride=False),
                       5123, mo["triangles"], "SCALAR")
    doc.extra_buffers = [{"byteLength": fallback[0],
                          "extensions": {"EXT_meshopt_compression": {"fallback": True}}}]
    mat = doc.push("materials", {"emissiveFactor": [0.2, 0.9, 0.4]})
    mesh_node(doc, {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv},
                    "indices": idx, "material": mat})
    uses(doc, "EXT_meshopt_compression", "KHR_mesh_quantization")
    return doc


def webp():
    doc = Doc()
    prim = bounded_quad(doc)
    prim["attributes"]["TEXCOORD_0"] = doc.floats([0, 0, 1, 0, 1, 1, 0, 1], "VEC2")
    img = doc.push("images", {"bufferView": doc.view(b64("webp")), "mimeType": "image/webp"})
    png = doc.push("images", {"uri": "data:image/png;base64," +
                              base64.b64encode(png_rgba(1, 1, [9, 99, 199, 255])).decode()})
    t0 = doc.push("textures", {"extensions": {"EXT_texture_webp": {"source": img}}})
    # A PNG fallback beside the WebP source: the loader takes the WebP.
    t1 = doc.push("textures", {"source": png, "extensions": {"EXT_texture_webp": {"source": img}}})
    doc.d["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": t0}}
    doc.d["materials"][0]["emissiveTexture"] = {"index": t1}
    uses(doc, "EXT_texture_webp")
    return doc


def texture_transform():
    doc = Doc()
    prim = bounded_quad(doc)
    prim["attributes"]["TEXCOORD_0"] = doc.floats([0, 0, 1, 0, 1, 1, 0, 1], "VEC2")
    prim["attributes"]["TEXCOORD_1"] = doc.floats([0, 0, 0.5, 0, 0.5, 0.5, 0, 0.5], "VEC2")
    pixels = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]
    img = doc.push("images", {"bufferView": doc.view(png_rgba(2, 2, pixels)), "mimeType": "image/png"})
    tex = doc.push("textures", {"source": img})
    m = doc.d["materials"][0]
    m["pbrMetallicRoughness"] = {"baseColorTexture": {"index": tex, "texCoord": 1, "extensions": {
        "KHR_texture_transform": {"offset": [0.25, 0.5], "rotation": 0.3, "scale": [2, 0.5]}}}}
    # texCoord 1 from the extension, overriding the textureInfo's 0.
    m["emissiveTexture"] = {"index": tex, "texCoord": 0, "extensions": {
        "KHR_texture_transform": {"texCoord": 1, "offset": [0.5, 0], "scale": [1, -1]}}}
    uses(doc, "KHR_texture_transform", required=False)
    return doc


def skin_morph():
    doc = Doc()
    prim = bounded_quad(doc)
    prim["attributes"]["JOINTS_0"] = doc.accessor(doc.view(bytes([0, 1, 0, 0] * 4)), 5121, 4, "VEC4")
    prim["attributes"]["WEIGHTS_0"] = doc.floats_kind([0.75, 0.25, 0, 0] * 4, "VEC4")
    # Target 0: POSITION deltas as a sparse accessor (two vertices moved); target 1: dense
    # POSITION and NORMAL deltas.
    idx = doc.view(struct.pack("<2H", 1, 2))
    val = doc.view(struct.pack("<6f", 0, 0, 0.5, 0, 0, 0.25))
    sparse = doc.accessor(None, 5126, 4, "VEC3", min=[0, 0, 0], max=[0, 0, 0.5], sparse={
        "count": 2, "indices": {"bufferView": idx, "componentType": 5123},
        "values": {"bufferView": val}})
    dense = doc.floats([0.1, 0, 0] * 4, "VEC3")
    doc.d["accessors"][dense].update(min=[0.1, 0, 0], max=[0.1, 0, 0])
    dn = doc.floats([0, 0.1, 0] * 4, "VEC3")
    prim["targets"] = [{"POSITION": sparse}, {"POSITION": dense, "NORMAL": dn}]
    doc.d["meshes"][0]["weights"] = [0.5, 0.25]
    ibm = doc.floats_kind([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1], "MAT4")
    root = doc.push("nodes", {"translation": [0, 0, 0.5], "children": [2]})
    doc.push("nodes", {"translation": [1, 0, 0], "rotation": [0, 0, 0.3826834, 0.9238795]})
    doc.d["skins"] = [{"joints": [root, 2], "inverseBindMatrices": ibm, "skeleton": root}]
    doc.d["nodes"][0].update(skin=0, weights=[0.25, 1])
    doc.d["scenes"][0]["nodes"].append(root)
    return doc


def quantized():
    doc = Doc()
    mat = doc.push("materials", {"emissiveFactor": [1, 1, 0.5]})
    # Positions: SHORT (not normalized; the node scales them), 8-byte stride; normals: normalized
    # BYTE, 4-byte stride; texcoords: normalized UNSIGNED_SHORT; indices u8.
    pos = doc.accessor(doc.view(struct.pack("<16h", 0, 0, 0, 0, 100, 0, 0, 0, 100, 100, 0, 0,
                                            0, 100, 0, 0), 8), 5122, 4, "VEC3",
                       min=[0, 0, 0], max=[100, 100, 0])
    nrm = doc.accessor(doc.view(struct.pack("<16b", *([0, 0, 127, 0] * 4)), 4), 5120, 4, "VEC3",
                       normalized=True)
    uv = doc.accessor(doc.view(struct.pack("<8H", 0, 0, 65535, 0, 65535, 65535, 0, 65535)),
                      5123, 4, "VEC2", normalized=True)
    uv1 = doc.accessor(doc.view(struct.pack("<8B", 0, 0, 255, 0, 255, 255, 0, 255)), 5121, 4,
                       "VEC2", normalized=True)
    prim = {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv, "TEXCOORD_1": uv1},
            "indices": doc.indices([0, 1, 2, 0, 2, 3], 5121), "material": mat}
    mesh_node(doc, prim, scale=[0.01, 0.01, 0.01])
    uses(doc, "KHR_mesh_quantization")
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
                      ("hierarchy", hierarchy()), ("draco", draco()), ("meshopt", meshopt()),
                      ("webp", webp()), ("texture_transform", texture_transform()),
                      ("skin_morph", skin_morph()), ("quantized", quantized())]:
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
