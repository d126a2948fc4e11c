#!/usr/bin/env python3
"""Writes the image test models of tests/data (tests/data/README.md, "Image models"), for
tests/test_scenefile_images.c: small glTF, GLB and OBJ files whose textures are PNG, JPEG and
unsupported images, next to the model or embedded in it.

Every model is one or two quads facing +z: a front quad [-1, 1]^2 at z = 0 and, where a test needs
something behind it, a back quad [-2, 2]^2 at z = -0.5. Every image is split into a left and a right
half (texture u below or above 1/2), so that what a test reads does not depend on which way a reader
turns v. JPEGs are made through libturbojpeg (ctypes), 4:4:4 at quality 95, with the halves on 8x8
block boundaries so that each block is one flat colour and decodes within a few steps of it.

Usage: python3 tests/data/make_image_models.py [folder]   (default: the folder of this script)
"""
import base64
import ctypes
import ctypes.util
import json
import os
import struct
import sys
import zlib

SIDE = 16  # every image is SIDE x SIDE texels


def halves(left, right):
    """RGBA rows (lists of 4-tuples) with the left half one colour and the right half another."""
    row = [left] * (SIDE // 2) + [right] * (SIDE // 2)
    return [row] * SIDE


def png(rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    h, w = len(rows), len(rows[0])
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def jpeg(rows):
    lib = ctypes.CDLL(ctypes.util.find_library("turbojpeg") or "libturbojpeg.so.0")
    lib.tjInitCompress.restype = ctypes.c_void_p
    lib.tjCompress2.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                ctypes.c_int, ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_ulong),
                                ctypes.c_int, ctypes.c_int, ctypes.c_int]
    lib.tjFree.argtypes = [ctypes.c_void_p]
    lib.tjDestroy.argtypes = [ctypes.c_void_p]
    h, w = len(rows), len(rows[0])
    rgb = bytes(c for row in rows for px in row for c in px[:3])
    handle = lib.tjInitCompress()
    out, size = ctypes.c_void_p(), ctypes.c_ulong(0)
    TJPF_RGB, TJSAMP_444 = 0, 0
    if lib.tjCompress2(handle, rgb, w, w * 3, h, TJPF_RGB, ctypes.byref(out), ctypes.byref(size), TJSAMP_444, 95, 0):
        sys.exit("tjCompress2 failed")
    data = ctypes.string_at(out, size.value)
    lib.tjFree(out)
    lib.tjDestroy(handle)
    return data


# A fake WebP: the RIFF/WEBP header and nothing a decoder could use (the loader must not try).
FAKE_WEBP = b"RIFF\x1a\0\0\0WEBPVP8 \x0e\0\0\0" + bytes(14)


class Gltf:
    """One glTF 2.0 asset under construction: one buffer, quads as meshes, images as data URIs
    (.gltf) or buffer views (.glb)."""

    def __init__(self, glb):
        self.glb = glb
        self.buf = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "tests/data/make_image_models.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": []}

    def view(self, data, target=None):
        while len(self.buf) % 4:
            self.buf.append(0)
        v = {"buffer": 0, "byteOffset": len(self.buf), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.buf += data
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, fmt, values, kind, ctype, count, extra=None):
        a = {"bufferView": self.view(struct.pack("<%d%s" % (len(values), fmt), *values),
                                     34963 if ctype == 5123 else 34962),
             "componentType": ctype, "count": count, "type": kind}
        a.update(extra or {})
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def quad(self, half, z, material):
        p = [-half, -half, z, half, -half, z, half, half, z, -half, half, z]
        pos = self.accessor("f", p, "VEC3", 5126, 4, {"min": [-half, -half, z], "max": [half, half, z]})
        nor = self.accessor("f", [0, 0, 1] * 4, "VEC3", 5126, 4)
        uv = self.accessor("f", [0, 1, 1, 1, 1, 0, 0, 0], "VEC2", 5126, 4)
        idx = self.accessor("H", [0, 1, 2, 0, 2, 3], "SCALAR", 5123, 6)
        self.doc["meshes"].append({"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor, "TEXCOORD_0": uv},
                                                   "indices": idx, "material": material}]})
        self.doc["nodes"].append({"mesh": len(self.doc["meshes"]) - 1})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def image(self, data, mime):
        """An image and a texture showing it; returns the texture's index."""
        if self.glb:
            img = {"bufferView": self.view(data), "mimeType": mime}
        else:
            img = {"uri": "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())}
        self.doc.setdefault("images", []).append(img)
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        return len(self.doc["textures"]) - 1

    def material(self, m):
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def write(self, path):
        while len(self.buf) % 4:
            self.buf.append(0)
        if self.glb:
            self.doc["buffers"] = [{"byteLength": len(self.buf)}]
            js = json.dumps(self.doc, separators=(",", ":")).encode()
            js += b" " * (-len(js) % 4)
            body = (struct.pack("<I4s", len(js), b"JSON") + js +
                    struct.pack("<I4s", len(self.buf), b"BIN\0") + bytes(self.buf))
            data = struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body
            with open(path, "wb") as f:
                f.write(data)
        else:
            self.doc["buffers"] = [{"byteLength": len(self.buf), "uri": "data:application/octet-stream;base64," +
                                    base64.b64encode(bytes(self.buf)).decode()}]
            with open(path, "w") as f:
                json.dump(self.doc, f, indent=1)
                f.write("\n")


RED, BLUE, GREEN, YELLOW = (255, 0, 0, 255), (0, 0, 255, 255), (0, 160, 0, 255), (255, 255, 0, 255)


def base_textured(glb, data, mime, name):
    g = Gltf(glb)
    t = g.image(data, mime)
    g.quad(1, 0, g.material({"name": name, "pbrMetallicRoughness": {"baseColorTexture": {"index": t},
                                                                     "metallicFactor": 0}}))
    return g


def main(out):
    os.makedirs(out, exist_ok=True)
    at = lambda name: os.path.join(out, name)
    # Embedded PNG and JPEG base colours in GLB files: red | blue, green | yellow.
    base_textured(True, png(halves(RED, BLUE)), "image/png", "png_halves").write(at("img_png.glb"))
    base_textured(True, jpeg(halves(GREEN, YELLOW)), "image/jpeg", "jpeg_halves").write(at("img_jpeg.glb"))
    # An OBJ whose map_Kd is a JPEG next to it: red | blue.
    with open(at("img_jpeg.jpg"), "wb") as f:
        f.write(jpeg(halves(RED, BLUE)))
    with open(at("img_jpeg.mtl"), "w") as f:
        f.write("# tests/data/make_image_models.py\nnewmtl jpeg_file\nKd 1 1 1\nmap_Kd img_jpeg.jpg\n")
    with open(at("img_jpeg.obj"), "w") as f:
        f.write("# tests/data/make_image_models.py: a quad textured by img_jpeg.jpg\nmtllib img_jpeg.mtl\n"
                "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                "usemtl jpeg_file\nf 1/1/1 2/2/1 3/3/1 4/4/1\n")
    # One image (a data URI) under two materials, and as one of them's emission too: one texture.
    g = Gltf(False)
    t = g.image(png(halves(RED, BLUE)), "image/png")
    g.quad(1, 0, g.material({"name": "first", "pbrMetallicRoughness": {"baseColorTexture": {"index": t}}}))
    g.quad(2, -0.5, g.material({"name": "second", "pbrMetallicRoughness": {"baseColorTexture": {"index": t}},
                                "emissiveFactor": [0.1, 0.1, 0.1], "emissiveTexture": {"index": t}}))
    g.write(at("img_shared.gltf"))
    # A WebP base colour (no decoder here): left out with a warning, the quad keeps its factor.
    g = Gltf(False)
    t = g.image(FAKE_WEBP, "image/webp")
    g.quad(1, 0, g.material({"name": "webp_material", "pbrMetallicRoughness": {
        "baseColorFactor": [0, 1, 0, 1], "baseColorTexture": {"index": t}}}))
    g.write(at("img_webp.gltf"))
    # The image file emissive_webp_texture.gltf names, a WebP too.
    with open(at("glow_not_read.webp"), "wb") as f:
        f.write(FAKE_WEBP)
    # A JPEG whose header is followed by nothing a decoder can use: an error naming it.
    base_textured(True, b"\xff\xd8\xff\xe0" + bytes(range(60)), "image/jpeg", "corrupt").write(at("img_corrupt.glb"))
    # metallicRoughness: B (metal) 255 everywhere, G (roughness) 0 on the left (a mirror) and 255 on
    # the right (a rough metal, Lambertian at roughness 1).
    g = Gltf(False)
    t = g.image(png(halves((0, 0, 255, 255), (0, 255, 255, 255))), "image/png")
    g.quad(1, 0, g.material({"name": "metal_rough", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 1, "roughnessFactor": 1,
        "metallicRoughnessTexture": {"index": t}}}))
    g.write(at("img_metal_rough.gltf"))
    # Occlusion: R 255 on the left, 64 on the right, over a white base colour.
    g = Gltf(False)
    t = g.image(png(halves((255, 0, 0, 255), (64, 0, 0, 255))), "image/png")
    g.quad(1, 0, g.material({"name": "occluded", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]},
                             "occlusionTexture": {"index": t}}))
    g.write(at("img_occlusion.gltf"))
    # Two materials over the same base colour (red | blue) and occlusion (255 | 64) images, front
    # and back quads: the second material's bake reads both images after the first's released them.
    g = Gltf(False)
    b = g.image(png(halves(RED, BLUE)), "image/png")
    t = g.image(png(halves((255, 0, 0, 255), (64, 0, 0, 255))), "image/png")
    for name, half, z in (("front", 1, 0), ("back", 2, -0.5)):
        g.quad(half, z, g.material({"name": name, "pbrMetallicRoughness": {"baseColorTexture": {"index": b}},
                                    "occlusionTexture": {"index": t}}))
    g.write(at("img_occlusion_shared.gltf"))
    # BLEND: a blue quad whose texture alpha is 0 on the left and 255 on the right, over a red back
    # quad; and an OPAQUE quad whose base colour alpha is 0.2, which must stay opaque.
    g = Gltf(False)
    t = g.image(png(halves((0, 0, 255, 0), (0, 0, 255, 255))), "image/png")
    g.quad(1, 0, g.material({"name": "blend", "alphaMode": "BLEND",
                             "pbrMetallicRoughness": {"baseColorTexture": {"index": t}}}))
    g.quad(2, -0.5, g.material({"name": "back", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}}))
    g.write(at("img_blend.gltf"))
    g = Gltf(False)
    g.quad(1, 0, g.material({"name": "opaque", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 0.2]}}))
    g.quad(2, -0.5, g.material({"name": "back", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}}))
    g.write(at("img_opaque.gltf"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
