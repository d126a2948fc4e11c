#!/usr/bin/env python3
"""The path integrator against Mitsuba 3 on the Cornell box (docs/benchmarks.md, "Path integrator").

Reads a Betelgeuse scene file of rectangles, boxes and spheres with diffuse materials (roughness 1,
no coat) and rectangle lights, writes the same scene for Mitsuba 3 and renders it there with the
scalar_rgb `path` integrator; renders ours with `bench_path --render` (the CPU reference, the path
integrator, linear float); then prints the RMSE and the relative difference of the means per channel,
and writes ours, Mitsuba's and their relative difference side by side as a PNG.

Mitsuba comes from PyPI into a virtual environment of its own, build/mitsuba-venv (mitsuba==3.9.1 and
numpy), made on the first run; the script then runs itself again inside it.

What the two scenes share, and why each choice:
- Camera: Mitsuba's `perspective` sensor at the same position, look_at and up, fov_axis "y" (ours is
  the vertical angle, docs/shading.md 1; Mitsuba's default axis is x), the same square image, and a
  `box` reconstruction filter (ours is the box over the pixel, 1.1; Mitsuba's default is a Gaussian).
- Shapes: ours are the prototypes of docs/shading.md 2 under the file's affine transform; Mitsuba's
  `rectangle` is [-1, 1]^2 in z = 0 facing +z and its `cube` [-1, 1]^3, so a rectangle gets our
  transform times the turn that takes z to y, a box our transform as it is.
- Materials: roughness 1 (Schlick's Lambertian layer, a = 1, b = 0 in 6.3) becomes `diffuse` with the
  same reflectance C. They differ by design: Schlick's layer is S(u) / pi with
  S(u) = C + (1 - C)(1 - u)^5, u = V.H, brighter than C / pi at grazing half-angles; the script
  measures that gain (below) and renders Mitsuba a second time with it folded into the reflectance.
- Lights: a rectangle light of colour col and intensity I is, under the path integrator, an emitter of
  radiance Le = pi col I / A (13.1), one-sided towards edge_u x edge_v: Mitsuba's `area` emitter of
  radiance Le on a `rectangle` of the same corners. A visible light's own object reflects nothing in
  ours but Schlick's grazing term of C = 0; Mitsuba's gets a black `diffuse`.
- Depth: our max_depth counts bounces after the camera ray's hit, with light sampled at each of the
  max_depth + 1 hits; Mitsuba's counts path segments (1: emitters seen directly, 2: direct light), so
  Mitsuba's max_depth is ours + 2. Both end paths by Russian roulette without bias.

The Schlick gain: rho(v) = integral over the hemisphere of S(V.H) / pi (n.L) dL is the directional
albedo of the layer seen at n.V = v; averaged over v with the cosine (2 v dv, the bihemispherical
albedo) it is the reflectance a Lambertian surface needs to return the same light on average. Both
integrals by quadrature here. Mitsuba with those reflectances (the "albedo-matched" run) shows how much
of the difference that gain explains; what remains is its angular shape (ours is brighter at grazing
views and lights, dimmer-relative at normal ones). Last, Mitsuba renders the layer itself, a BSDF
written in Python (register_schlick), at a smaller size: the same BRDF on both sides, so what is left
is the integrators' difference.

Usage: python3 bench/mitsuba_compare.py [--scene FILE] [--size N] [--spp N] [--out PNG]
                                        [--bench build/release/bench/bench_path] [--work build/mitsuba]
                                        [--no-matched] [--mitsuba-only] [--schlick-size N]
                                        [--reuse-ours]
Defaults: examples/scenes/json/cornell_box.json, 512, 1024, docs/cornell_vs_mitsuba.png.
"""
import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(TOP, "build", "mitsuba-venv")
MITSUBA = "mitsuba==3.9.1"


def in_venv():
    """Runs the script inside build/mitsuba-venv, making it first if needed."""
    py = os.path.join(VENV, "bin", "python")
    if os.path.realpath(sys.prefix) == os.path.realpath(VENV):
        return
    if not os.path.exists(py):
        print(f"making {VENV} with {MITSUBA} and numpy (pip, once)", flush=True)
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
        subprocess.check_call([py, "-m", "pip", "install", "-q", MITSUBA, "numpy"])
    os.execv(py, [py, os.path.abspath(__file__)] + sys.argv[1:])


# ---- the scene file ----

def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def step_matrix(step, where):
    """One transform step of docs/scene_format.md as a 4 x 4 row-major matrix."""
    if len(step) != 1:
        raise ValueError(f"{where}: a step holds one key")
    (key, value), = step.items()
    if key == "matrix":
        rows = [list(map(float, r)) for r in value]
        return rows + [[0.0, 0.0, 0.0, 1.0]] if len(rows) == 3 else rows
    if key == "translate":
        m = identity()
        for i in range(3):
            m[i][3] = float(value[i])
        return m
    if key == "scale":
        s = [float(value)] * 3 if isinstance(value, (int, float)) else list(map(float, value))
        m = identity()
        for i in range(3):
            m[i][i] = s[i]
        return m
    if key == "rotate":
        ax = list(map(float, value["axis"]))
        n = math.sqrt(sum(a * a for a in ax))
        x, y, z = (a / n for a in ax)
        t = math.radians(float(value["degrees"]))
        c, s, k = math.cos(t), math.sin(t), 1 - math.cos(t)
        return [[c + x * x * k, x * y * k - z * s, x * z * k + y * s, 0.0],
                [y * x * k + z * s, c + y * y * k, y * z * k - x * s, 0.0],
                [z * x * k - y * s, z * y * k + x * s, c + z * z * k, 0.0],
                [0.0, 0.0, 0.0, 1.0]]
    raise ValueError(f"{where}: unknown step {key}")


def transform_of(obj, where):
    """The object's transform: steps applied in order, the first first (p' = M_n ... M_1 p)."""
    t = obj.get("transform")
    if t is None:
        return identity()
    steps = t if isinstance(t, list) else [t]
    m = identity()
    for i, step in enumerate(steps):
        m = matmul(step_matrix(step, f"{where}.transform[{i}]"), m)
    return m


def rgb(v):
    return [float(v)] * 3 if isinstance(v, (int, float)) else list(map(float, v))


def diffuse_reflectance(name, m):
    """C of a single Lambertian layer, or an error naming what the comparison cannot carry."""
    extra = set(m) - {"base", "ambient"}
    base = m.get("base", {})
    if extra or set(base) - {"reflectance", "roughness"} or float(base.get("roughness", 1)) != 1.0:
        raise ValueError(f"materials.{name}: only single Lambertian layers (roughness 1) are compared with "
                         f"Mitsuba's diffuse; this one has {sorted(extra) or base}")
    return rgb(base.get("reflectance", 0.8))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(sum(x * x for x in a))


# ---- Schlick's Lambertian layer ----

def schlick_albedo(c, v, n_theta=96, n_phi=96):
    """rho(v) = integral of S(V.H) / pi (n.L) dL over the hemisphere (docs/shading.md 6.2, 6.3 at r = 1),
    by the midpoint rule in (cos^2 theta_L, phi_L), where (n.L) dL = d(cos^2)/2 dphi is uniform."""
    sv = math.sqrt(max(0.0, 1.0 - v * v))
    V = (sv, 0.0, v)
    total = 0.0
    for i in range(n_theta):
        c2 = (i + 0.5) / n_theta
        cl = math.sqrt(c2)
        sl = math.sqrt(1.0 - c2)
        for j in range(n_phi):
            phi = 2.0 * math.pi * (j + 0.5) / n_phi
            L = (sl * math.cos(phi), sl * math.sin(phi), cl)
            H = [V[k] + L[k] for k in range(3)]
            h = norm(H)
            u = sum(V[k] * H[k] for k in range(3)) / h if h > 0 else 1.0
            total += c + (1.0 - c) * (1.0 - min(max(u, 0.0), 1.0)) ** 5
    # each cell: d(cos^2)/2 dphi = (1 / n_theta) / 2 * (2 pi / n_phi), times 1/pi of the BRDF
    return total * (0.5 / n_theta) * (2.0 * math.pi / n_phi) / math.pi


def schlick_mean_albedo(c, n_v=24):
    """The cosine-weighted mean of rho(v) over the viewing hemisphere: integral of rho(v) 2 v dv."""
    return sum(schlick_albedo(c, math.sqrt((i + 0.5) / n_v)) for i in range(n_v)) / n_v


# ---- Mitsuba ----

def mitsuba_scene(scene, size, spp, max_depth, reflectance_map=None):
    """The scene file as a Mitsuba dict; reflectance_map(C) replaces each diffuse reflectance."""
    import mitsuba as mi
    T = mi.ScalarTransform4f
    cam = scene.get("camera", {})
    d = {"type": "scene",
         "integrator": {"type": "path", "max_depth": max_depth + 2},
         "sensor": {"type": "perspective", "fov_axis": "y", "fov": float(cam.get("fov_y", 45)),
                    "to_world": T().look_at(origin=cam.get("position", [0, 0, 5]),
                                            target=cam.get("look_at", [0, 0, 0]), up=cam.get("up", [0, 1, 0])),
                    "sampler": {"type": "independent", "sample_count": spp},
                    "film": {"type": "hdrfilm", "width": size, "height": size, "pixel_format": "rgb",
                             "rfilter": {"type": "box"}}}}
    materials = {}
    for name, m in scene.get("materials", {}).items():
        c = diffuse_reflectance(name, m)
        if reflectance_map:
            c = [reflectance_map(x) for x in c]
        materials[name] = {"type": "diffuse", "reflectance": {"type": "rgb", "value": c}}
    default = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
    # Mitsuba's rectangle (z = 0, facing +z) onto ours (y = 0, facing +y): (x, y, z) -> (x, z, -y).
    turn = [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]]
    for i, obj in enumerate(scene.get("objects", [])):
        where = f"objects[{i}]"
        m = transform_of(obj, where)
        bsdf = materials[obj["material"]] if "material" in obj else default
        if "rectangle" in obj:
            shape = {"type": "rectangle", "to_world": T(matmul(m, turn))}
        elif "box" in obj:
            shape = {"type": "cube", "to_world": T(m)}
        elif "sphere" in obj:
            s = obj["sphere"]
            place = matmul(step_matrix({"translate": s.get("center", [0, 0, 0])}, where),
                           step_matrix({"scale": s.get("radius", 1)}, where))
            shape = {"type": "sphere", "to_world": T(matmul(m, place))}
        else:
            raise ValueError(f"{where}: only rectangles, boxes and spheres are exported")
        shape["bsdf"] = bsdf
        d[f"object_{i}"] = shape
    for i, light in enumerate(scene.get("lights", [])):
        if "rectangle" not in light:
            raise ValueError(f"lights[{i}]: only rectangle lights are exported")
        r = light["rectangle"]
        c0, u, v = (list(map(float, r[k])) for k in ("corner", "edge_u", "edge_v"))
        n = cross(u, v)
        area = norm(n)
        n = [x / area for x in n]
        le = [math.pi * x * float(light.get("intensity", 1)) / area for x in rgb(light.get("color", 1))]
        centre = [c0[k] + 0.5 * (u[k] + v[k]) for k in range(3)]
        to_world = [[0.5 * u[k], 0.5 * v[k], n[k], centre[k]] for k in range(3)] + [[0, 0, 0, 1]]
        d[f"light_{i}"] = {"type": "rectangle", "to_world": T(to_world),
                           "emitter": {"type": "area", "radiance": {"type": "rgb", "value": le}},
                           "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0, 0, 0]}}}
    return d


def register_schlick():
    """Schlick's Lambertian layer as a Mitsuba BSDF written in Python (scalar variants only):
    f = S(u) / pi, S(u) = C + (1 - C)(1 - u)^5, u = V.H (docs/shading.md 6.2, 6.3 at r = 1), drawn by the
    cosine as Mitsuba's diffuse is. A Python call per BSDF query makes it about 40 times slower than
    the built-in diffuse, so it runs at a smaller size (--schlick-size)."""
    import mitsuba as mi

    class SchlickLambert(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.c = [props["r"], props["g"], props["b"]]
            self.m_flags = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide
            self.m_components = [self.m_flags]

        def f(self, wi, wo):
            if mi.Frame3f.cos_theta(wi) <= 0 or mi.Frame3f.cos_theta(wo) <= 0:
                return mi.Color3f(0.0)
            h = [wi[k] + wo[k] for k in range(3)]
            n = math.sqrt(sum(x * x for x in h))
            u = min(max(sum(wi[k] * h[k] for k in range(3)) / n, 0.0), 1.0) if n > 0 else 1.0
            k5 = (1.0 - u) ** 5
            return mi.Color3f([(c + (1.0 - c) * k5) / math.pi for c in self.c])

        def sample(self, ctx, si, sample1, sample2, active=True):
            bs = mi.BSDFSample3f()
            bs.wo = mi.warp.square_to_cosine_hemisphere(sample2)
            bs.pdf = mi.warp.square_to_cosine_hemisphere_pdf(bs.wo)
            bs.eta = 1.0
            bs.sampled_type = mi.UInt32(+mi.BSDFFlags.DiffuseReflection)
            bs.sampled_component = 0
            if bs.pdf <= 0 or mi.Frame3f.cos_theta(si.wi) <= 0:
                return bs, mi.Color3f(0.0)
            return bs, self.f(si.wi, bs.wo) * mi.Frame3f.cos_theta(bs.wo) / bs.pdf

        def eval(self, ctx, si, wo, active=True):
            return self.f(si.wi, wo) * max(mi.Frame3f.cos_theta(wo), 0.0)

        def pdf(self, ctx, si, wo, active=True):
            if mi.Frame3f.cos_theta(si.wi) <= 0:
                return 0.0
            return mi.warp.square_to_cosine_hemisphere_pdf(wo)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

        def to_string(self):
            return "SchlickLambert[%s]" % self.c

    mi.register_bsdf("schlick_lambert", lambda props: SchlickLambert(props))


def render_mitsuba(work, scene, size, spp, max_depth, seed, reflectance_map=None, tag="plain"):
    """Mitsuba's image, kept in work/ under a name of everything it depends on, so that a second run
    (another output, ours rebuilt) reuses it. Returns the image and the seconds it took (0: reused)."""
    import mitsuba as mi
    import numpy as np
    d = mitsuba_scene(scene, size, spp, max_depth, reflectance_map)
    if tag == "schlick":
        for v in d.values():
            if isinstance(v, dict) and v.get("bsdf", {}).get("type") == "diffuse" and "emitter" not in v:
                c = v["bsdf"]["reflectance"]["value"]
                v["bsdf"] = {"type": "schlick_lambert", "r": c[0], "g": c[1], "b": c[2]}
    key = hashlib.sha1(json.dumps([scene, size, spp, max_depth, seed, tag, mi.__version__],
                                  sort_keys=True).encode()).hexdigest()[:12]
    path = os.path.join(work, f"mitsuba_{tag}_{size}_{spp}_{key}.npy")
    if os.path.exists(path):
        return np.load(path), 0.0
    s = mi.load_dict(d)
    t0 = time.time()
    image = np.array(mi.render(s, spp=spp, seed=seed), dtype=np.float64)[:, :, :3]
    np.save(path, image)
    return image, time.time() - t0


def read_pfm(path):
    import numpy as np
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").astype(np.float64)
    return data.reshape(h, w, 3)[::-1]


# ---- comparison ----

def away_from_emitters(ours, theirs, margin=2):
    """The pixels at least margin pixels away from any pixel above 1 in either image (the light, at
    radiance 17, and the pixels its edge crosses; the walls stay below 1). The margin matters: a pixel
    the light's edge crosses is kept or left out by its noisy value, and a test of each pixel's own
    value (both below a level) keeps the pixels where the noisier image (Mitsuba's independent samples
    against our stratified ones) came out low, which made ours read about 8 % brighter on the ceiling
    beside the light."""
    import numpy as np
    bright = (ours.max(axis=2) > 1.0) | (theirs.max(axis=2) > 1.0)
    near = bright.copy()
    h, w = bright.shape
    for dy in range(-margin, margin + 1):
        for dx in range(-margin, margin + 1):
            near[max(0, dy):h + min(0, dy), max(0, dx):w + min(0, dx)] |= \
                bright[max(0, -dy):h + min(0, -dy), max(0, -dx):w + min(0, -dx)]
    return ~near


def compare(ours, theirs, label):
    """Prints and returns per channel: RMSE, and the relative difference of the means over all pixels and
    over the pixels away from the emitters (away_from_emitters)."""
    import numpy as np
    lit = away_from_emitters(ours, theirs)
    rows = {}
    for k, ch in enumerate("RGB"):
        a, b = ours[:, :, k], theirs[:, :, k]
        rows[ch] = {"rmse": float(np.sqrt(np.mean((a - b) ** 2))),
                    "rel_all": float(a.mean() / b.mean() - 1.0),
                    "rel_lit": float(a[lit].mean() / b[lit].mean() - 1.0),
                    "mean_ours": float(a[lit].mean()), "mean_mitsuba": float(b[lit].mean())}
    d = (ours - theirs)[lit]
    se = d.std(axis=0) / math.sqrt(len(d))
    for k, ch in enumerate("RGB"):
        rows[ch]["se_rel"] = float(se[k] / rows[ch]["mean_mitsuba"])
    print(f"{label}: pixels away from the light {int(lit.sum())} of {lit.size}; the relative differences' noise "
          f"(standard error): " + " ".join(f"{ch} {100 * rows[ch]['se_rel']:.2f}%" for ch in "RGB"))
    print(f"  {'ch':2} {'RMSE':>9} {'mean ours':>10} {'mean Mitsuba':>12} {'rel. diff (lit)':>16} "
          f"{'rel. diff (all)':>16}")
    for ch, r in rows.items():
        print(f"  {ch:2} {r['rmse']:9.5f} {r['mean_ours']:10.5f} {r['mean_mitsuba']:12.5f} "
              f"{100 * r['rel_lit']:+15.2f}% {100 * r['rel_all']:+15.2f}%")
    return rows


def region_table(ours, theirs, boxes):
    """Relative difference of the means of each named image box (x0, y0, x1, y1), per channel, over its
    pixels away from the emitters (as compare's), with its standard error."""
    lit = away_from_emitters(ours, theirs)
    print("  regions (relative difference of the means, R G B, +- its standard error):")
    for name, (x0, y0, x1, y1) in boxes.items():
        keep = lit[y0:y1, x0:x1].reshape(-1)
        a, b = ours[y0:y1, x0:x1].reshape(-1, 3)[keep], theirs[y0:y1, x0:x1].reshape(-1, 3)[keep]
        rel = [100 * (a[:, k].mean() / b[:, k].mean() - 1.0) for k in range(3)]
        se = [100 * (a[:, k] - b[:, k]).std() / math.sqrt(len(a)) / b[:, k].mean() for k in range(3)]
        print(f"    {name:22} " + " ".join(f"{r:+7.2f}% +-{e:.2f}" for r, e in zip(rel, se)))


def srgb8(img):
    import numpy as np
    x = np.clip(img, 0.0, 1.0)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return np.round(255.0 * x).astype(np.uint8)


def write_side_by_side(path, ours, theirs, gap=8, block=8):
    """ours | Mitsuba | their relative difference, ours / Mitsuba - 1 of the means of block x block
    pixel blocks (the noise averaged out), averaged over the channels: red where ours is brighter, blue
    where dimmer, full at 10 %; black where an emitter is (both images equal there by construction)."""
    import mitsuba as mi
    import numpy as np
    h, w, _ = ours.shape
    hb, wb = h // block, w // block
    a = ours[:hb * block, :wb * block].reshape(hb, block, wb, block, 3).mean(axis=(1, 3))
    b = theirs[:hb * block, :wb * block].reshape(hb, block, wb, block, 3).mean(axis=(1, 3))
    ok = (a.max(axis=2) < 2.0) & (b.max(axis=2) < 2.0) & (b.min(axis=2) > 0.0)
    rel = np.where(ok, (a / np.where(b > 0, b, 1.0) - 1.0).mean(axis=2), 0.0) / 0.10
    d = np.zeros((h, w, 3))
    up = np.kron(rel, np.ones((block, block)))
    d[:hb * block, :wb * block, 0] = np.clip(up, 0, 1)
    d[:hb * block, :wb * block, 2] = np.clip(-up, 0, 1)
    canvas = np.full((h, 3 * w + 2 * gap, 3), 255, dtype=np.uint8)
    for i, img in enumerate((srgb8(ours), srgb8(theirs), np.round(255 * d).astype(np.uint8))):
        canvas[:, i * (w + gap):i * (w + gap) + w] = img
    mi.Bitmap(canvas, mi.Bitmap.PixelFormat.RGB).write(path)


def main():
    in_venv()
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", default=os.path.join(TOP, "examples/scenes/json/cornell_box.json"))
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--out", default=os.path.join(TOP, "docs/cornell_vs_mitsuba.png"))
    p.add_argument("--bench", default=os.path.join(TOP, "build/release/bench/bench_path"))
    p.add_argument("--work", default=os.path.join(TOP, "build/mitsuba"))
    p.add_argument("--no-matched", action="store_true", help="skip the albedo-matched Mitsuba render")
    p.add_argument("--mitsuba-only", action="store_true", help="render (and keep) Mitsuba's images only")
    p.add_argument("--reuse-ours", action="store_true",
                   help="take our images from an earlier run in --work when they are there")
    p.add_argument("--schlick-size", type=int, default=64,
                   help="size of the run with Schlick's layer as a Python BSDF in Mitsuba (0: none)")
    a = p.parse_args()
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    os.makedirs(a.work, exist_ok=True)
    scene = json.load(open(a.scene))
    max_depth = int(scene.get("settings", {}).get("max_depth", 5))
    print(f"scene {os.path.relpath(a.scene, TOP)}: {a.size}x{a.size}, {a.spp} samples a pixel, max_depth {max_depth} "
          f"(Mitsuba {max_depth + 2}); Mitsuba {mi.__version__} scalar_rgb path, box filter", flush=True)

    # Schlick's gain of each reflectance in the file (for the albedo-matched Mitsuba run).
    cs = sorted({x for name, m in scene.get("materials", {}).items() for x in diffuse_reflectance(name, m)})
    gain = {c: schlick_mean_albedo(c) for c in cs}

    theirs, secs = render_mitsuba(a.work, scene, a.size, a.spp, max_depth, seed=1)
    print(f"Mitsuba: {secs:.1f} s" if secs else "Mitsuba: reused from " + a.work, flush=True)
    matched = None
    if not a.no_matched:
        matched, secs = render_mitsuba(a.work, scene, a.size, a.spp, max_depth, seed=2,
                                       reflectance_map=lambda c: gain[c], tag="matched")
        print(f"Mitsuba, albedo-matched: {secs:.1f} s" if secs else "Mitsuba, albedo-matched: reused", flush=True)
    if a.schlick_size:
        register_schlick()
        schlick, secs = render_mitsuba(a.work, scene, a.schlick_size, a.spp, max_depth, seed=3, tag="schlick")
        print(f"Mitsuba with Schlick's layer at {a.schlick_size}x{a.schlick_size}: {secs:.1f} s" if secs else
              "Mitsuba with Schlick's layer: reused", flush=True)
    if a.mitsuba_only:
        return

    ours_pfm = os.path.join(a.work, f"ours_{a.size}_{a.spp}.pfm")
    t0 = time.time()
    if not (a.reuse_ours and os.path.exists(ours_pfm)):
        subprocess.check_call([a.bench, "--render", a.scene, str(a.size), str(a.spp), ours_pfm])
    ours = read_pfm(ours_pfm)
    print(f"ours: {time.time() - t0:.1f} s (CPU reference, bench_path --render)", flush=True)

    rows = compare(ours, theirs, "ours against Mitsuba (same reflectances)")
    s = a.size / 512.0
    boxes = {k: tuple(int(round(c * s)) for c in v) for k, v in {
        "back wall": (200, 110, 312, 190), "ceiling": (150, 40, 360, 85), "floor (front)": (140, 470, 360, 505),
        "red wall": (20, 150, 70, 380), "green wall": (442, 150, 492, 380),
        "tall block front": (180, 200, 240, 380), "short block front": (300, 330, 380, 420)}.items()}
    region_table(ours, theirs, boxes)

    print("Schlick's Lambertian layer: the cosine-weighted mean albedo rho against C "
          "(rho(v) at v = 1, 0.5, 0.1):")
    for c in cs:
        print(f"  C {c:6.3f}: rho {gain[c]:.4f} ({100 * (gain[c] / c - 1):+.1f} %); "
              f"rho(v) {schlick_albedo(c, 1.0):.4f} {schlick_albedo(c, 0.5):.4f} {schlick_albedo(c, 0.1):.4f}")
    if matched is not None:
        compare(ours, matched, "ours against Mitsuba with C replaced by Schlick's mean albedo")
        region_table(ours, matched, boxes)
    if a.schlick_size:
        small_pfm = os.path.join(a.work, f"ours_{a.schlick_size}_{a.spp}.pfm")
        if not (a.reuse_ours and os.path.exists(small_pfm)):
            subprocess.check_call([a.bench, "--render", a.scene, str(a.schlick_size), str(a.spp), small_pfm])
        small = read_pfm(small_pfm)
        compare(small, schlick, f"ours against Mitsuba with Schlick's layer (a Python BSDF), "
                                         f"{a.schlick_size}x{a.schlick_size}")
        s_small = a.schlick_size / 512.0
        region_table(small, schlick, {k: tuple(int(round(c * s_small / s)) for c in v) for k, v in boxes.items()})
    write_side_by_side(a.out, ours, theirs)
    print(f"wrote {os.path.relpath(a.out, TOP)} (ours | Mitsuba | ours / Mitsuba - 1 over 8 x 8 blocks, the "
          f"channels' mean: red brighter, blue dimmer, full at 10 %)")
    worst = max(abs(r["rel_lit"]) for r in rows.values())
    print(f"largest relative difference of a channel's mean (same reflectances): {100 * worst:.2f} % "
          f"(target 1 %: {'met' if worst <= 0.01 else 'missed'})")


if __name__ == "__main__":
    main()
