#!/usr/bin/env python3
"""Writes the glTF fuzzers' seed corpus: small models that reach each part of the loader (node
hierarchy, strips and fans, sparse and normalized accessors, strides, materials with a texture and
its transform, cameras, lights), as .gltf with data URIs (tests/fuzz/corpus/gltf) and as .glb
(tests/fuzz/corpus/glb). Files are named by their SHA-1, as libFuzzer names its corpus.

Run by hand when the loader learns something new:  python3 tests/fuzz/gltf_seeds.py
"""
import base64
import hashlib
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png_2x2():
    raw = b"\x00" + bytes([255, 0, 0, 0, 255, 0]) + b"\x00" + bytes([0, 0, 255, 255, 255, 255])

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


class Model:
    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors = [], []

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.views.append(v)
        self.bin += data
        return len(self.views) - 1

    def accessor(self, view, ctype, count, kind, **extra):
        a = {"componentType": ctype, "count": count, "type": kind, **extra}
        if view is not None:
            a["bufferView"] = view
        self.accessors.append(a)
        return len(self.accessors) - 1

    def floats(self, values, kind, per):
        return self.accessor(self.view(struct.pack("<%df" % len(values), *values)), 5126,
                             len(values) // per, kind)

    def doc(self, body, uri):
        d = {"asset": {"version": "2.0"}}
        if self.bin:
            buf = {"byteLength": len(self.bin)}
            if uri:
                buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
            d.update(buffers=[buf], bufferViews=self.views, accessors=self.accessors)
        d.update(body)
        return d

    def glb(self, body):
        j = json.dumps(self.doc(body, False), separators=(",", ":")).encode()
        j += b" " * ((4 - len(j) % 4) % 4)
        b = bytes(self.bin) + b"\0" * ((4 - len(self.bin) % 4) % 4)
        out = struct.pack("<I", len(j)) + b"JSON" + j
        if b:
            out += struct.pack("<I", len(b)) + b"BIN\0" + b
        return b"glTF" + struct.pack("<II", 2, 12 + len(out)) + out

    def gltf(self, body):
        return json.dumps(self.doc(body, True), separators=(",", ":")).encode()


def triangle(m, mode=4, extra_attr=None):
    p = m.floats([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], "VEC3", 3)
    attrs = {"POSITION": p}
    attrs.update(extra_attr or {})
    return {"scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": attrs, "mode": mode}]}]}


def seeds():
    m = Model()
    yield m, triangle(m)
    for mode in (5, 6, 1):
        m = Model()
        yield m, triangle(m, mode)
    m = Model()
    body = triangle(m)
    idx = m.accessor(m.view(struct.pack("<6H", 0, 1, 2, 2, 1, 3)), 5123, 6, "SCALAR")
    n = m.accessor(m.view(bytes([0, 0, 127, 0] * 4)), 5120, 4, "VEC3", normalized=True)
    c = m.accessor(m.view(bytes([255, 128, 0, 255] * 4)), 5121, 4, "VEC4", normalized=True)
    uv = m.floats([0, 0, 1, 0, 0, 1, 1, 1], "VEC2", 2)
    prim = body["meshes"][0]["primitives"][0]
    prim.update(indices=idx, material=0)
    prim["attributes"].update(NORMAL=n, COLOR_0=c, TEXCOORD_0=uv)
    img = m.view(png_2x2())
    body.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.5, 1], "metallicFactor": 0.3,
                                                     "roughnessFactor": 0.4,
                                                     "baseColorTexture": {"index": 0, "extensions": {
                                                         "KHR_texture_transform": {"offset": [0.5, 0], "rotation": 0.3,
                                                                                   "scale": [2, 2]}}}},
                            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5},
                                           "KHR_materials_ior": {"ior": 1.4}}}],
                textures=[{"source": 0, "sampler": 0}], samplers=[{"wrapS": 33071}],
                images=[{"bufferView": img, "mimeType": "image/png"}],
                extensionsUsed=["KHR_texture_transform", "KHR_materials_transmission", "KHR_materials_ior"])
    yield m, body
    m = Model()
    sparse_i = m.view(bytes([1]))
    sparse_v = m.view(struct.pack("<3f", 5, 6, 7))
    p = m.accessor(None, 5126, 3, "VEC3", sparse={"count": 1, "indices": {"bufferView": sparse_i, "componentType": 5121},
                                                 "values": {"bufferView": sparse_v}})
    inter = m.view(struct.pack("<18f", 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1), stride=24)
    q = m.accessor(inter, 5126, 3, "VEC3")
    nn = m.accessor(inter, 5126, 3, "VEC3", byteOffset=12)
    body = {"nodes": [{"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1], "children": [1, 2, 3, 4]},
                      {"mesh": 0, "translation": [0, 5, 0], "rotation": [0, 0, 0.7071, 0.7071], "scale": [2, 2, 2]},
                      {"mesh": 0, "scale": [-1, 1, 1]},
                      {"camera": 0, "translation": [0, 0, 5],
                       "extensions": {"KHR_lights_punctual": {"light": 0}}},
                      {"camera": 1, "extensions": {"KHR_lights_punctual": {"light": 1}}}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": p}},
                                       {"attributes": {"POSITION": q, "NORMAL": nn}}]}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
                        {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1, "znear": 0, "zfar": 5}}],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 100, "color": [1, 0.9, 0.8]},
                                                              {"type": "spot", "intensity": 50}]}},
            "extensionsUsed": ["KHR_lights_punctual"]}
    yield m, body


def write(folder, data):
    path = os.path.join(HERE, "corpus", folder)
    os.makedirs(path, exist_ok=True)
    with open(os.path.join(path, hashlib.sha1(data).hexdigest()), "wb") as f:
        f.write(data)


for model, body in seeds():
    write("gltf", model.gltf(body))
    write("glb", model.glb(body))
