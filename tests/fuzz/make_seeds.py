#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets, tests/fuzz/corpus/{json,ply,obj,stl}/.

Run once by hand from the source tree's root (python3 tests/fuzz/make_seeds.py) when the seeds are to
change; the build never runs it, and the files it writes are kept in the repository. It copies the
shipped scenes and test models, and writes the hand-made adversarial seeds (adv_*): each one a known
way for a loader to go wrong, small enough that the fuzzer mutates it cheaply. The copies start the
fuzzer on inputs that load; the adversarial ones start it at the edges. Files the fuzzer or a person
added (any other name) are left alone.
"""
import os
import shutil
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
CORPUS = os.path.join(ROOT, "tests", "fuzz", "corpus")


def put(kind, name, data):
    path = os.path.join(CORPUS, kind, name)
    if isinstance(data, str):
        data = data.encode()
    with open(path, "wb") as f:
        f.write(data)


def copy(kind, source):
    shutil.copyfile(os.path.join(ROOT, source), os.path.join(CORPUS, kind, os.path.basename(source)))


TETRA = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def json_seeds():
    scenes = os.path.join("examples", "scenes", "json")
    for name in sorted(os.listdir(os.path.join(ROOT, scenes))):
        if name.endswith(".json"):
            copy("json", os.path.join(scenes, name))
    # cJSON stops at 1000 levels; the loader must report that, not recurse.
    put("json", "adv_nesting_100000.json", '{"objects": ' + "[" * 100000 + "]" * 100000 + "}")
    # Texture names that hold a zero byte: after cJSON they are C strings cut at the zero, so two
    # different JSON keys become the same name "a".
    put("json", "adv_texture_name_nul.json",
        '{"textures": {"a\\u0000b": {"file": "earth.png"}, "a\\u0000c": {"file": "stripes.png"}},\n'
        ' "materials": {"m": {"base": {"reflectance": {"texture": "a"}}}},\n'
        ' "objects": [{"sphere": {}, "material": "m"}]}\n')
    put("json", "adv_texture_file_nul.json",
        '{"textures": {"t": {"file": "earth.png\\u0000.txt"}},\n'
        ' "materials": {"m": {"ambient": {"texture": "t"}}},\n'
        ' "objects": [{"box": {}, "material": "m"}]}\n')
    # A scene cut in the middle of a string.
    with open(os.path.join(ROOT, scenes, "textured_aniso.json"), "rb") as f:
        put("json", "adv_truncated.json", f.read()[:700])
    # Numbers at and past the ranges: an integer beyond int, a literal that overflows to infinity,
    # the largest image the format allows.
    put("json", "adv_numbers.json",
        '{"image": {"width": 16384, "height": 16384, "samples": 1024},\n'
        ' "settings": {"max_depth": 64, "ambient": 1e308},\n'
        ' "objects": [{"sphere": {"center": [1e308, -1e308, 0], "radius": 4294967297}}]}\n')
    put("json", "adv_number_overflow.json", '{"camera": {"fov_y": 1e999, "position": [0, 0, -0]}}\n')
    put("json", "adv_duplicate_keys.json", '{"camera": {}, "camera": {"fov_y": 10}}\n')
    # Transforms the scene must refuse: singular, non-affine, a rotation about a zero axis.
    put("json", "adv_transforms.json",
        '{"objects": [\n'
        ' {"box": {}, "transform": {"matrix": [[0,0,0,0],[0,0,0,0],[0,0,0,0]]}},\n'
        ' {"box": {}, "transform": {"matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[1,0,0,1]]}},\n'
        ' {"cylinder": {}, "transform": [{"rotate": {"axis": [0,0,0], "degrees": 90}}, {"scale": 1e-200}]}]}\n')
    # Area lights and a lens at the edges: the largest sphere radius the scene takes, a rectangle
    # whose far corner leaves the double range, edges all but parallel, and both shape keys on one
    # light; a lens far wider than the scene and focused next to the camera.
    put("json", "adv_area_lights.json",
        '{"lights": [\n'
        ' {"sphere": {"center": [0, 1e300, 0], "radius": 1e100}, "spot_cutoff_degrees": 90, "direction": [0, -1, 0]},\n'
        ' {"type": "rectangle", "rectangle": {"corner": [1e308, 0, 0], "edge_u": [1e308, 0, 0], "edge_v": [0, 0, 1]}},\n'
        ' {"rectangle": {"edge_u": [1, 0, 0], "edge_v": [1, 1e-13, 0]}},\n'
        ' {"sphere": {}, "rectangle": {}, "position": [0, 0, 0]}]}\n')
    put("json", "adv_lens.json",
        '{"camera": {"aperture_radius": 1e300, "focus_distance": 1e-300, "position": [0, 0, 1e-300]},\n'
        ' "objects": [{"sphere": {}}], "lights": [{"sphere": {"radius": 0}}]}\n')
    # Every model format from a scene, so that the JSON target also reaches the model reader.
    put("json", "adv_models.json",
        '{"objects": [\n'
        ' {"mesh": {"file": "../../../tests/data/tetra.ply", "normals": "flat"}},\n'
        ' {"mesh": {"file": "../../../tests/data/tetra.stl"}, "transform": {"translate": [2, 0, 0]}},\n'
        ' {"mesh": {"file": "../../../tests/data/two_boxes.obj", "normals": "smooth"}},\n'
        ' {"mesh": {"file": "missing.ply"}}]}\n')


def ply_header(fmt, nv, nf, extra=""):
    return ("ply\nformat %s 1.0\n%selement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (fmt, extra, nv, nf))


def ply_seeds():
    copy("ply", os.path.join("tests", "data", "tetra.ply"))
    copy("ply", os.path.join("tests", "data", "bunny.ply"))
    tri = "0 0 0\n1 0 0\n0 1 0\n"
    # An index past the vertices: assimp does not check it in its PLY reader.
    put("ply", "adv_index_out_of_range.ply", ply_header("ascii", 3, 1) + tri + "3 0 1 7\n")
    put("ply", "adv_index_negative.ply", ply_header("ascii", 3, 1) + tri + "3 0 1 -1\n")
    # Counts that the file cannot hold: a reader that reserves by the header's count asks for gigabytes.
    put("ply", "adv_vertex_count_int_max.ply",
        ply_header("ascii", 2147483647, 1, "comment 2^31 - 1 vertices in a 300-byte file\n") + tri + "3 0 1 2\n")
    put("ply", "adv_vertex_count_1000000.ply", ply_header("ascii", 1000000, 1) + tri + "3 0 1 2\n")
    put("ply", "adv_face_count_int_max.ply", ply_header("ascii", 3, 2147483647) + tri + "3 0 1 2\n")
    # A face list whose count byte promises 255 indices.
    put("ply", "adv_face_list_255.ply", ply_header("ascii", 3, 1) + tri + "255 0 1 2\n")
    # The tetrahedron in both binary byte orders.
    for order, fmt, name in (("<", "binary_little_endian", "adv_binary_le.ply"),
                             (">", "binary_big_endian", "adv_binary_be.ply")):
        body = b"".join(struct.pack(order + "3f", *v) for v in TETRA)
        body += b"".join(struct.pack(order + "B3i", 3, *f) for f in TETRA_FACES)
        put("ply", name, ply_header(fmt, 4, 4).encode() + body)
    # Binary data cut short, and a header cut short.
    body = b"".join(struct.pack("<3f", *v) for v in TETRA) + struct.pack("<B3i", 3, 0, 2, 1)
    put("ply", "adv_binary_truncated.ply", ply_header("binary_little_endian", 4, 4).encode() + body[:-3])
    put("ply", "adv_header_truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty fl")


def obj_seeds():
    copy("obj", os.path.join("tests", "data", "two_boxes.obj"))
    v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    # OBJ indices count from 1; negative ones count back from the last vertex.
    put("obj", "adv_index_zero.obj", v + "f 0 1 2\n")
    put("obj", "adv_index_negative.obj", v + "f -3 -2 -1\nf -1 -2 -7\n")
    put("obj", "adv_index_out_of_range.obj", v + "f 1 2 9\nf 1 2 4294967297\n")
    put("obj", "adv_uv_normal_out_of_range.obj", v + "vt 0 0\nvn 0 0 1\nf 1/1/1 2/5/1 3/1/9\n")
    put("obj", "adv_truncated.obj", v + "v 1 2\nf 1/")
    # A material library that is not there, and a material never defined.
    put("obj", "adv_mtllib_missing.obj", "mtllib missing.mtl\nusemtl nothing\n" + v + "f 1 2 3\n")
    # Points and lines only: nothing a ray tracer can hit.
    put("obj", "adv_points_lines.obj", v + "p 1 2\nl 1 2 3\n")


def stl_binary(count, triangles, header=b"binary tetra by make_seeds.py"):
    data = header.ljust(80, b" ")[:80] + struct.pack("<I", count)
    for a, b, c in triangles:
        data += struct.pack("<12fH", 0, 0, 0, *TETRA[a], *TETRA[b], *TETRA[c], 0)
    return data


def stl_seeds():
    copy("stl", os.path.join("tests", "data", "tetra.stl"))
    put("stl", "adv_binary.stl", stl_binary(4, TETRA_FACES))
    # The triangle count in the header against the bytes that follow: more, fewer, the most.
    put("stl", "adv_binary_count_1000000.stl", stl_binary(1000000, TETRA_FACES))
    put("stl", "adv_binary_count_short.stl", stl_binary(1, TETRA_FACES))
    put("stl", "adv_binary_count_uint_max.stl", stl_binary(0xFFFFFFFF, TETRA_FACES[:1]))
    put("stl", "adv_binary_empty.stl", stl_binary(0, []))
    # A binary file whose header starts with "solid", as some exporters write: the ASCII check must
    # not take it for text.
    put("stl", "adv_binary_solid_header.stl", stl_binary(4, TETRA_FACES, b"solid tetra"))
    with open(os.path.join(ROOT, "tests", "data", "tetra.stl"), "rb") as f:
        put("stl", "adv_ascii_truncated.stl", f.read()[:150])
    put("stl", "adv_ascii_facet_two_vertices.stl",
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid x\n")


if __name__ == "__main__":
    for kind in ("json", "ply", "obj", "stl"):
        os.makedirs(os.path.join(CORPUS, kind), exist_ok=True)
    json_seeds()
    ply_seeds()
    obj_seeds()
    stl_seeds()
