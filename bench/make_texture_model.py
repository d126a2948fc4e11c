#!/usr/bin/env python3
"""Writes a model shaped like DamagedHelmet for the texture-memory measurement of docs/benchmarks.md
("Texture memory"): one glTF mesh of about 15,000 triangles (a UV sphere) whose material has the
five 8-bit PNG textures that model has, each 2048 x 2048: base colour, metallic-roughness, normal,
emissive and occlusion. The renderer reads four of them (the normal map it warns about and skips).

The texels are smooth patterns with a little hashed noise, so the PNGs compress like photographs
rather than like flat colour, but any content costs the renderer the same memory.

Usage: python3 bench/make_texture_model.py [folder] [side]   (default /tmp/texture_model, 2048)
"""
import json
import math
import os
import struct
import sys
import zlib


def png(path, side, pixel):
    """An 8-bit RGBA PNG of side x side texels, pixel(x, y) -> 4 bytes."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    rows = bytearray()
    for y in range(side):
        rows.append(0)
        for x in range(side):
            rows += pixel(x, y)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(rows), 1)) + chunk(b"IEND", b""))


def noise(x, y):
    return ((x * 73856093) ^ (y * 19349663)) & 15


def sphere(rings, segments):
    pos, uv, idx = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2.0 * math.pi * j / segments
            pos += [math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)]
            uv += [j / segments, i / rings]
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, uv, idx


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "/tmp/texture_model"
    side = int(sys.argv[2]) if len(sys.argv) > 2 else 2048
    os.makedirs(out, exist_ok=True)
    maps = {
        "base.png": lambda x, y: bytes((x * 255 // side, y * 255 // side, 128 + noise(x, y), 255)),
        "metal_rough.png": lambda x, y: bytes((0, (x ^ y) & 255, 255 - ((x + y) & 255), 255)),
        "normal.png": lambda x, y: bytes((128 + noise(x, y), 128, 255, 255)),
        "emissive.png": lambda x, y: bytes((255 if (x // 64 + y // 64) % 7 == 0 else noise(x, y), 0, 0, 255)),
        "occlusion.png": lambda x, y: bytes((200 + noise(x, y) * 3, 0, 0, 255)),
    }
    for name, f in maps.items():
        png(os.path.join(out, name), side, f)

    pos, uv, idx = sphere(88, 88)  # 15,312 triangles
    buf = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(uv), *uv) + \
        struct.pack("<%dI" % len(idx), *idx)
    with open(os.path.join(out, "model.bin"), "wb") as f:
        f.write(buf)
    n = len(pos) // 3
    doc = {
        "asset": {"version": "2.0", "generator": "bench/make_texture_model.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "buffers": [{"uri": "model.bin", "byteLength": len(buf)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
                        {"buffer": 0, "byteOffset": 12 * n, "byteLength": 8 * n},
                        {"buffer": 0, "byteOffset": 20 * n, "byteLength": 4 * len(idx)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
                       "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]},
                      {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}],
        "images": [{"uri": name} for name in maps],
        "textures": [{"source": i} for i in range(len(maps))],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                "metallicRoughnessTexture": {"index": 1}},
                       "normalTexture": {"index": 2}, "emissiveTexture": {"index": 3},
                       "emissiveFactor": [1.0, 1.0, 1.0], "occlusionTexture": {"index": 4}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                    "material": 0}]}],
    }
    with open(os.path.join(out, "model.gltf"), "w") as f:
        json.dump(doc, f, indent=1)


main()
