#!/usr/bin/env python3
"""Renders the model test files of tests/data with the `betelgeuse` command and lays the images out
as one PNG: the contact sheet of docs/scene_format.md ("Materials of model files"), one cell per
mapping rule, in the order of CELLS below. With --before OLD, each cell gets the image of another
build of the command above it (a before and after sheet).

Only the Python 3 standard library: the PNGs the command writes (8-bit RGBA, filtered rows) are
decoded and the sheet is encoded here.

Usage, from the repository root:
  python3 docs/contact_sheet.py [--betelgeuse build/release/betelgeuse] [--before OLD_BINARY]
                                [--renderer cpu|gpu] [--size 128x96] -o docs/contact_sheet.png
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib

# (model in tests/data, what the cell shows): the rules of docs/scene_format.md, one each.
CELLS = [
    ("img_png.glb", "a base colour PNG embedded in a .glb"),
    ("img_jpeg.glb", "a base colour JPEG embedded in a .glb"),
    ("img_jpeg.obj", "an OBJ whose map_Kd is a JPEG file"),
    ("img_metal_rough.gltf", "metallicRoughness: G 0 (a mirror, dark) | 1 (rough)"),
    ("img_occlusion.gltf", "occlusion R 1 | 0.25 scales the ambient term"),
    ("img_blend.gltf", "alphaMode BLEND: alpha 0 | 1 over a red quad"),
    ("img_opaque.gltf", "alphaMode OPAQUE ignores baseColorFactor alpha 0.2"),
    ("emissive_red.gltf", "emissiveFactor without a texture: a plain glow"),
    ("mask_over_floor.gltf", "alphaMode MASK: a hole, in the shadow too"),
    ("one_sided_back.gltf", "doubleSided false, seen from behind: not there"),
    ("two_sided_back.gltf", "doubleSided true, seen from behind: lit"),
    ("bunny.ply", "a PLY without materials: grey diffuse"),
    ("tetra.stl", "an STL without materials: grey diffuse"),
]
COLUMNS = 5
GAP = 4


def read_png(path):
    """An 8-bit RGBA PNG (what the command writes) as (width, height, rows of bytes)."""
    data = open(path, "rb").read()
    at, idat, w, h = 8, b"", 0, 0
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        at += 12 + n
        if kind == b"IHDR":
            w, h, depth, color = struct.unpack(">IIBB", body[:10])
            if depth != 8 or color != 6:
                raise ValueError("%s: not 8-bit RGBA" % path)
        elif kind == b"IDAT":
            idat += body
    raw, stride, rows, prev, k = zlib.decompress(idat), 4 * w, [], bytearray(4 * w), 0
    for _ in range(h):
        kind, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        for x in range(stride):
            a = line[x - 4] if x >= 4 else 0
            b = prev[x]
            c = prev[x - 4] if x >= 4 else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows


def write_png(path, w, h, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    raw = b"".join(b"\0" + bytes(r) for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def render(binary, model, size, renderer, out):
    cmd = [binary, "render", os.path.join("tests", "data", model), "-o", out, "--size", size, "--renderer",
           renderer, "--quiet"]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write("%s: %s" % (" ".join(cmd), result.stderr))
        return None
    return read_png(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--betelgeuse", default="build/release/betelgeuse")
    ap.add_argument("--before", help="another build of the command, shown above each cell")
    ap.add_argument("--renderer", default="cpu", choices=["cpu", "gpu"])
    ap.add_argument("--size", default="128x96")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    cw, ch = (int(v) for v in args.size.split("x"))
    builds = ([args.before] if args.before else []) + [args.betelgeuse]
    cell_h = len(builds) * ch + (len(builds) - 1) * GAP
    rows_n = (len(CELLS) + COLUMNS - 1) // COLUMNS
    sw, sh = COLUMNS * cw + (COLUMNS + 1) * GAP, rows_n * cell_h + (rows_n + 1) * GAP * 2
    sheet = [bytearray([255, 255, 255, 255] * sw) for _ in range(sh)]
    with tempfile.TemporaryDirectory() as tmp:
        for i, (model, _) in enumerate(CELLS):
            x0 = GAP + (i % COLUMNS) * (cw + GAP)
            y0 = 2 * GAP + (i // COLUMNS) * (cell_h + 2 * GAP)
            for j, binary in enumerate(builds):
                img = render(binary, model, args.size, args.renderer, os.path.join(tmp, "%d_%d.png" % (i, j)))
                y = y0 + j * (ch + GAP)
                for r in range(ch):
                    line = img[2][r] if img else bytearray([255, 0, 255, 255] * cw)  # magenta: it failed
                    sheet[y + r][4 * x0:4 * (x0 + cw)] = line
    write_png(args.output, sw, sh, sheet)
    for i, (model, what) in enumerate(CELLS):
        print("%2d  %-22s %s" % (i + 1, model, what))


if __name__ == "__main__":
    main()
