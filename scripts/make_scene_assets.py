#!/usr/bin/env python3
"""Generates the assets of Prism's example scenes (standard library only).

  scenes/assets/sky/{px,nx,py,ny,pz,nz}.png  a procedural sky cube map (OpenGL face order and
                                             orientation): gradient, sun, distant hills
  scenes/assets/trefoil.obj                  a trefoil-knot tube with per-vertex normals

The files are committed; run this only to change them:  python3 scripts/make_scene_assets.py
(or name one: `... sky`, `... trefoil`). The sky's 1024² faces take a few minutes.
"""
import math
import multiprocessing
import os
import struct
import sys
import zlib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "assets")


def write_png(path, width, height, rows):
    """Writes 8-bit RGB rows (lists of (r, g, b) bytes) as a PNG file."""
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def srgb(linear):
    linear = min(max(linear, 0.0), 1.0)
    encoded = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return int(round(255 * encoded))


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


SUN = normalize((0.5, 0.55, -0.65))


def sky_radiance(d):
    """Linear radiance seen along unit direction d (y is up)."""
    x, y, z = d
    azimuth = math.atan2(z, x)
    hills = 0.05 + 0.035 * math.sin(3 * azimuth) + 0.02 * math.sin(7 * azimuth + 1.3)
    if y < hills:
        # Distant hills and ground: darker green-brown, lighter towards the horizon.
        fade = math.exp(-max(0.0, hills - y) * 4.0)
        return tuple(c * (0.25 + 0.75 * fade) for c in (0.16, 0.20, 0.10))
    t = max(y, 0.0)
    horizon = (0.85, 0.90, 0.95)
    zenith = (0.20, 0.40, 0.85)
    base = tuple(h + (zz - h) * t ** 0.6 for h, zz in zip(horizon, zenith))
    cos_sun = sum(a * b for a, b in zip(d, SUN))
    glow = 0.6 * max(cos_sun, 0.0) ** 64
    disc = 8.0 if cos_sun > math.cos(math.radians(2.0)) else 0.0
    return tuple(c + glow + disc for c in base)


# Face directions for texel coordinates s, t in [-1, 1] (t grows downwards in the image),
# the inverse of the OpenGL cube-map selection.
FACES = {
    "px": lambda s, t: (1.0, -t, -s),
    "nx": lambda s, t: (-1.0, -t, s),
    "py": lambda s, t: (s, 1.0, t),
    "ny": lambda s, t: (s, -1.0, -t),
    "pz": lambda s, t: (s, -t, 1.0),
    "nz": lambda s, t: (-s, -t, -1.0),
}


# 1024² faces: a texel of the default view's horizon (the -Z face's middle) spans 3.2 pixels
# at 1920x1080 (320² faces: 10), small enough that bilinear magnification draws the hills'
# edges without steps; the renderer reads coarser mip levels where pixels are larger.
SKY_SIZE = 1024


def make_face(name, size, supersampling):
    """Each texel averages supersampling² directions so the hills' edges are antialiased."""
    direction = FACES[name]
    n = supersampling
    rows = []
    for j in range(size):
        row = []
        for i in range(size):
            total = [0.0, 0.0, 0.0]
            for sj in range(n):
                t = 2.0 * (j + (sj + 0.5) / n) / size - 1.0
                for si in range(n):
                    s = 2.0 * (i + (si + 0.5) / n) / size - 1.0
                    for c, value in enumerate(sky_radiance(normalize(direction(s, t)))):
                        total[c] += value
            row.append(tuple(srgb(min(c / (n * n), 1.0)) for c in total))
        rows.append(row)
    write_png(os.path.join(ROOT, "sky", name + ".png"), size, size, rows)


def make_sky(size=SKY_SIZE, supersampling=3):
    """The six faces, one process each (a 1024² face takes minutes in pure Python)."""
    os.makedirs(os.path.join(ROOT, "sky"), exist_ok=True)
    with multiprocessing.Pool() as pool:
        pool.starmap(make_face, [(name, size, supersampling) for name in FACES])


def trefoil(u):
    return (math.sin(u) + 2 * math.sin(2 * u), math.cos(u) - 2 * math.cos(2 * u), -math.sin(3 * u))


def make_trefoil(segments=240, sides=20, tube=0.45):
    """A tube around the trefoil knot. Normals are exact: vertex minus the tube's centre line."""
    sub = lambda a, b: tuple(x - y for x, y in zip(a, b))
    cross = lambda a, b: (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    dot = lambda a, b: sum(x * y for x, y in zip(a, b))
    centres = [trefoil(2 * math.pi * k / segments) for k in range(segments)]
    tangents = [normalize(sub(centres[(k + 1) % segments], centres[k - 1])) for k in range(segments)]
    # Parallel-transport a frame along the curve, then spread the closing twist evenly.
    normal = normalize(cross(tangents[0], (0.0, 0.0, 1.0)))
    frames = []
    for k in range(segments):
        t = tangents[k]
        normal = normalize(sub(normal, tuple(dot(normal, t) * c for c in t)))
        frames.append((normal, cross(t, normal)))
    t0 = tangents[0]
    end = normalize(sub(normal, tuple(dot(normal, t0) * c for c in t0)))
    twist = math.atan2(dot(cross(frames[0][0], end), t0), dot(frames[0][0], end))
    positions, normals = [], []
    for k in range(segments):
        n, b = frames[k]
        for j in range(sides):
            angle = 2 * math.pi * j / sides - twist * k / segments
            offset = tuple(math.cos(angle) * x + math.sin(angle) * y for x, y in zip(n, b))
            positions.append(tuple(c + tube * o for c, o in zip(centres[k], offset)))
            normals.append(offset)
    with open(os.path.join(ROOT, "trefoil.obj"), "w") as f:
        f.write("# Trefoil-knot tube with per-vertex normals; made by scripts/make_scene_assets.py\n")
        for p in positions:
            f.write("v %.6f %.6f %.6f\n" % p)
        for n in normals:
            f.write("vn %.6f %.6f %.6f\n" % n)
        for k in range(segments):
            for j in range(sides):
                a = k * sides + j
                b = k * sides + (j + 1) % sides
                c = ((k + 1) % segments) * sides + (j + 1) % sides
                d = ((k + 1) % segments) * sides + j
                f.write("f %d//%d %d//%d %d//%d\n" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1))
                f.write("f %d//%d %d//%d %d//%d\n" % (a + 1, a + 1, c + 1, c + 1, d + 1, d + 1))


if __name__ == "__main__":
    # "sky" or "trefoil" makes only that asset; nothing makes both.
    wanted = sys.argv[1:] or ["sky", "trefoil"]
    if "sky" in wanted:
        make_sky()
    if "trefoil" in wanted:
        make_trefoil()
