#!/usr/bin/env python3
"""Writes the glTF models of tests/data for cut-outs and sides (tests/data/README.md, "Cut-out and
side models"), for tests/test_scenefile_sides.c, with the glTF writer of make_image_models.py.

Each file has a camera on the +z or -z axis looking at the origin (60 degrees, square) and a
KHR_lights_punctual point light (intensity 30), so that a test knows where every surface, shadow and
hole falls in the image:
- mask_over_floor.gltf: a green quad [-1, 1]^2 at z = 0, alphaMode MASK (cut-off 0.5) with a 4 x 4
  base colour texture whose middle 2 x 2 texels have alpha 0, over a red floor quad [-3, 3]^2 at
  z = -1; camera at z = 6, light at (4, 0, 4), so that the quad's shadow on the floor, x in
  [-2.25, 0.25], falls partly beside the quad as the camera sees it, with the hole's lit patch at x
  in [-1.625, -0.375].
- one_sided_back.gltf, two_sided_back.gltf: a green quad [-1, 1]^2 at z = 0 facing +z, doubleSided
  false and true, seen and lit from behind (camera at z = -6, light at z = -5).
- normal_mapped.gltf: a quad whose material "bumpy" has a normalTexture (a flat 2 x 2 normal map).

Usage: python3 tests/data/make_side_models.py [folder]   (default: the folder of this script)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_image_models import Gltf, png  # noqa: E402  (the one glTF writer of tests/data)

GREEN, CLEAR = (40, 200, 40, 255), (40, 200, 40, 0)


def camera_and_light(g, z, light):
    """A camera at (0, 0, z) looking at the origin and a point light at light."""
    behind = z < 0
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.0471975511965976, "aspectRatio": 1.0,
                                                                "znear": 0.1}}]
    cam = {"camera": 0, "translation": [0, 0, z]}
    if behind:
        cam["rotation"] = [0, 1, 0, 0]  # half a turn about y: looking down +z
    g.doc["nodes"].append(cam)
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1],
                                                               "intensity": 30}]}}
    g.doc["nodes"].append({"translation": light, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    g.doc["scenes"][0]["nodes"] += [len(g.doc["nodes"]) - 2, len(g.doc["nodes"]) - 1]


def opaque(g, name, rgb, double_sided=False):
    return g.material({"name": name, "doubleSided": double_sided,
                       "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1], "metallicFactor": 0}})


def main(out):
    at = lambda name: os.path.join(out, name)
    g = Gltf(False)
    hole = [[CLEAR if 1 <= x <= 2 and 1 <= y <= 2 else GREEN for x in range(4)] for y in range(4)]
    t = g.image(png(hole), "image/png")
    g.quad(1, 0, g.material({"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.5, "pbrMetallicRoughness": {
        "baseColorTexture": {"index": t}, "metallicFactor": 0}}))
    g.quad(3, -1, opaque(g, "floor", (0.8, 0.1, 0.1)))
    camera_and_light(g, 6, [4, 0, 4])
    g.write(at("mask_over_floor.gltf"))
    for name, two in (("one_sided_back.gltf", False), ("two_sided_back.gltf", True)):
        g = Gltf(False)
        g.quad(1, 0, opaque(g, "sheet", (0.1, 0.8, 0.1), two))
        camera_and_light(g, -6, [0, 0, -5])
        g.write(at(name))
    # A normal map, which the renderers cannot take: left out with a warning naming the material.
    g = Gltf(False)
    t = g.image(png([[(128, 128, 255, 255)] * 2] * 2), "image/png")
    g.quad(1, 0, g.material({"name": "bumpy", "normalTexture": {"index": t},
                             "pbrMetallicRoughness": {"metallicFactor": 0}}))
    g.write(at("normal_mapped.gltf"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
