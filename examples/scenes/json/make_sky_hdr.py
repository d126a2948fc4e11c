#!/usr/bin/env python3
"""Writes sky.hdr beside this script: a 256 x 128 equirectangular Radiance HDR image (RGBE, flat
scanlines) of a blue sky over a brown ground with a small sun 35 degrees up, to the right of the
view along -z, for examples/scenes/json/environment.json. Run it to regenerate the file."""
import math
import os

W, H = 256, 128


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    e = math.frexp(m)[1]
    scale = math.ldexp(1.0, -e) * 256.0
    return bytes((int(r * scale), int(g * scale), int(b * scale), e + 128))


def radiance(theta, phi):
    """theta from +y (up), phi the azimuth from -z towards +x."""
    up = math.cos(theta)
    if up < 0.0:
        return (0.12, 0.09, 0.06)
    sky = (0.25 + 0.35 * (1.0 - up), 0.45 + 0.3 * (1.0 - up), 0.95)
    sun_theta, sun_phi = math.radians(55.0), math.radians(40.0)
    d = (math.sin(theta) * math.sin(phi), up, -math.sin(theta) * math.cos(phi))
    s = (math.sin(sun_theta) * math.sin(sun_phi), math.cos(sun_theta), -math.sin(sun_theta) * math.cos(sun_phi))
    if sum(a * b for a, b in zip(d, s)) > math.cos(math.radians(3.0)):
        return (400.0, 380.0, 340.0)
    return sky


def main():
    rows = []
    for y in range(H):  # top row first, as the file stores it
        theta = math.pi * (y + 0.5) / H
        row = b"".join(rgbe(*radiance(theta, 2.0 * math.pi * ((x + 0.5) / W - 0.5))) for x in range(W))
        rows.append(row)
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sky.hdr")
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W))
        for row in rows:
            f.write(row)


if __name__ == "__main__":
    main()
