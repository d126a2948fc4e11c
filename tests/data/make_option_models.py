#!/usr/bin/env python3
"""Writes the models of the command's model options (tests/test_scenefile_options.c, make
check-command): two_cameras.gltf and ico_no_normals.ply. Run from the repository root:
    python3 tests/data/make_option_models.py
The files are kept in the repository; the build never runs this."""
import base64
import json
import math
import struct


def two_cameras():
    # The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), wound counter-clockwise seen from outside.
    positions = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    indices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
    blob = b"".join(struct.pack("<3f", *p) for p in positions) + struct.pack("<12H", *indices)
    s = math.sqrt(0.5)
    gltf = {
        "asset": {"version": "2.0", "generator": "tests/data/make_option_models.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0, "name": "tetra"},
            # Camera 1 (the first): in front, looking down -z.
            {"camera": 0, "name": "front", "translation": [0.3, 0.3, 4]},
            # Camera 2: to the right, turned +90 degrees about y, so looking down -x.
            {"camera": 1, "name": "side", "translation": [4, 0.3, 0.3], "rotation": [0, s, 0, s]},
        ],
        "cameras": [
            {"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}},
            {"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100}},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 24, "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    }
    with open("tests/data/two_cameras.gltf", "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def ico_sphere():
    # An icosahedron subdivided once, its vertices pushed onto the unit sphere: 42 vertices, 80 faces.
    t = (1 + math.sqrt(5)) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    middle = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            p = [(v[a][k] + v[b][k]) / 2 for k in range(3)]
            n = math.sqrt(sum(x * x for x in p))
            v.append(tuple(x / n for x in p))
            middle[key] = len(v) - 1
        return middle[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    with open("tests/data/ico_no_normals.ply", "w") as f:
        f.write("ply\nformat ascii 1.0\ncomment tests/data/make_option_models.py\n")
        f.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(v))
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(out))
        for p in v:
            f.write("%.7f %.7f %.7f\n" % p)
        for a, b, c in out:
            f.write("3 %d %d %d\n" % (a, b, c))


two_cameras()
ico_sphere()
