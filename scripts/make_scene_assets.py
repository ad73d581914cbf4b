#!/usr/bin/env python3
"""Generates the assets of Prism's example scenes (standard library only).

  scenes/assets/sky/{px,nx,py,ny,pz,nz}.png  a procedural sky cube map (OpenGL face order and
                                             orientation): gradient, sun, distant hills
  scenes/assets/trefoil.obj                  a trefoil-knot tube with per-vertex normals
  scenes/assets/still-life/                  an OBJ with its MTL and two PNG textures: a wooden
                                             crate, a tiled table top, a glass and a metal ball
  scenes/globe.glb                           a glTF 2.0 binary: a textured globe on a stand with
                                             its own camera and light, rendered as it comes

The files are committed; run this only to change them:  python3 scripts/make_scene_assets.py
(or name some: `... sky`, `... trefoil`, `... still-life`, `... globe`). The sky's 1024² faces
take a few minutes.
"""
import json
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


def png_bytes(width, height, pixel):
    """An 8-bit RGB PNG of pixel(x, y) -> (r, g, b) bytes, rows from the top, as bytes."""
    path = os.path.join(ROOT, ".tmp.png")
    write_png(path, width, height, [[pixel(x, y) for x in range(width)] for y in range(height)])
    with open(path, "rb") as f:
        data = f.read()
    os.remove(path)
    return data


def hash_noise(x, y, seed):
    """A repeatable value in [0, 1) for integer coordinates: grain without a random module."""
    h = (x * 374761393 + y * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return (h ^ (h >> 16)) / 2.0**32


def crate_texture(size=256):
    """Five vertical planks with grain and dark gaps, a dark frame: one crate face."""
    def pixel(x, y):
        plank = x * 5 // size
        edge = min(x, y, size - 1 - x, size - 1 - y)
        gap = (x * 5) % size < 4
        grain = 0.85 + 0.15 * math.sin(y * 0.11 + plank * 1.7 + 3 * math.sin(x * 0.05 + plank))
        tone = (0.55 + 0.08 * ((plank * 7) % 3)) * grain * (0.93 + 0.07 * hash_noise(x, y, 1))
        if edge < 18:
            tone *= 0.55
        if gap:
            tone *= 0.35
        return (srgb(tone), srgb(tone * 0.62), srgb(tone * 0.33))
    return png_bytes(size, size, pixel)


def tile_texture(size=128):
    """Two-tone stone tiles with grout: the table top, repeated eight times across it."""
    def pixel(x, y):
        grout = x % 64 < 3 or y % 64 < 3
        light = ((x // 64) + (y // 64)) % 2 == 0
        tone = 0.04 if grout else (0.7 if light else 0.25)
        tone *= 0.9 + 0.1 * hash_noise(x // 2, y // 2, 2)
        return (srgb(tone), srgb(tone * 0.95), srgb(tone * 0.88))
    return png_bytes(size, size, pixel)


def uv_sphere(centre, radius, rings=24, segments=48):
    """Positions, normals, texture coordinates (u around, v from the south pole up) and
    triangles (index triples) of a sphere; the seam repeats its column so u runs 0..1."""
    positions, normals, uvs, triangles = [], [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings  # from the north pole
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            positions.append(tuple(c + radius * k for c, k in zip(centre, n)))
            normals.append(n)
            uvs.append((j / segments, 1.0 - i / rings))
    for i in range(rings):
        for j in range(segments):
            a = i * (segments + 1) + j
            b, c, d = a + 1, a + segments + 2, a + segments + 1
            if i > 0:
                triangles.append((a, d, b))
            if i < rings - 1:
                triangles.append((b, d, c))
    return positions, normals, uvs, triangles


def make_still_life():
    """A crate on a tiled table with a glass ball and a metal ball: one OBJ, one MTL (four
    materials, two textures, a glass by illum 7 and a mirror by illum 3), PNG textures."""
    folder = os.path.join(ROOT, "still-life")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "crate.png"), "wb") as f:
        f.write(crate_texture())
    with open(os.path.join(folder, "tiles.png"), "wb") as f:
        f.write(tile_texture())
    with open(os.path.join(folder, "still-life.mtl"), "w") as f:
        f.write("# Materials of still-life.obj; made by scripts/make_scene_assets.py\n"
                "newmtl crate\nKa 0 0 0\nKd 1 1 1\nKs 0.05 0.05 0.05\nNs 20\nillum 2\n"
                "map_Kd crate.png\n\n"
                "newmtl tiles\nKa 0 0 0\nKd 0.9 0.9 0.9\nKs 0.1 0.1 0.1\nNs 60\nillum 2\n"
                "map_Kd -s 8 8 1 tiles.png\n\n"
                "newmtl glass\nKa 0 0 0\nKd 0 0 0\nKs 1 1 1\nNs 200\nNi 1.5\nd 0\nTf 1 1 1\n"
                "illum 7\n\n"
                "newmtl metal\nKa 0 0 0\nKd 0.05 0.05 0.05\nKs 0.8 0.75 0.6\nNs 300\nillum 3\n")
    out = ["# A crate on a tiled table, a glass ball and a metal ball; made by "
           "scripts/make_scene_assets.py", "mtllib still-life.mtl"]
    counts = {"v": 0, "vt": 0, "vn": 0}

    def emit(material, positions, uvs, normals, faces):
        """faces: corner index triples into this part's lists (0-based)."""
        v0, t0, n0 = counts["v"], counts["vt"], counts["vn"]
        out.extend("v %.5f %.5f %.5f" % p for p in positions)
        out.extend("vt %.5f %.5f" % t for t in uvs)
        out.extend("vn %.5f %.5f %.5f" % n for n in normals)
        counts["v"] += len(positions)
        counts["vt"] += len(uvs)
        counts["vn"] += len(normals)
        out.append("usemtl " + material)
        for face in faces:
            corners = []
            for k in face:
                corners.append("%d/%d/%d" % (v0 + k + 1, t0 + k + 1, n0 + k + 1))
            out.append("f " + " ".join(corners))

    # The table top: 8 x 8 units at y = 0, its texture repeated by the MTL's -s 8 8.
    # Every corner names a normal: an OBJ mesh is smooth shaded only where all of them do.
    emit("tiles", [(-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4)],
         [(0, 1), (0, 0), (1, 0), (1, 1)], [(0, 1, 0)] * 4, [(0, 1, 2, 3)])
    # The crate: a 1.6-unit cube, each face the whole texture, turned 25 degrees.
    half, angle = 0.8, math.radians(25)
    def place(p):
        x, y, z = p
        return (math.cos(angle) * x + math.sin(angle) * z - 0.9, y + half,
                -math.sin(angle) * x + math.cos(angle) * z - 0.6)
    corners = [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
    directions = [  # (rotation of the front face to each face)
        lambda x, y, z: (x, y, z), lambda x, y, z: (-x, y, -z), lambda x, y, z: (z, y, -x),
        lambda x, y, z: (-z, y, x), lambda x, y, z: (x, z, -y), lambda x, y, z: (x, -z, y)]
    def turn_only(p):
        x, y, z = p
        return (math.cos(angle) * x + math.sin(angle) * z, y,
                -math.sin(angle) * x + math.cos(angle) * z)
    positions, uvs, normals = [], [], []
    for turn in directions:
        for c in corners:
            positions.append(place(tuple(half * k for k in turn(*c))))
            normals.append(turn_only(turn(0, 0, 1)))
        uvs.extend([(0, 0), (1, 0), (1, 1), (0, 1)])
    emit("crate", positions, uvs, normals,
         [(4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3) for k in range(6)])
    for material, centre, radius in (("glass", (1.3, 0.7, 0.6), 0.7),
                                     ("metal", (2.3, 0.45, -1.3), 0.45)):
        p, n, t, tris = uv_sphere(centre, radius)
        emit(material, p, t, n, tris)
    with open(os.path.join(folder, "still-life.obj"), "w") as f:
        f.write("\n".join(out) + "\n")


def globe_texture(width=512, height=256):
    """An equirectangular map of made-up continents (sums of sines) in ocean, with ice caps and
    a graticule every 30 degrees."""
    def pixel(x, y):
        lon = 2 * math.pi * (x + 0.5) / width
        lat = math.pi * (0.5 - (y + 0.5) / height)
        land = (math.sin(2 * lon + 0.5) * math.cos(3 * lat) + 0.6 * math.sin(5 * lon - 1.0 + lat)
                + 0.4 * math.cos(7 * lat + 2 * lon))
        if abs(lat) > math.radians(72):
            colour = (0.85, 0.88, 0.9)
        elif land > 0.55:
            green = 0.25 + 0.2 * hash_noise(x // 3, y // 3, 3)
            colour = (0.18 + 0.25 * (land - 0.55), green, 0.06)
        else:
            colour = (0.02, 0.08 + 0.04 * land, 0.28 + 0.05 * land)
        degrees_lon = math.degrees(lon) % 30
        degrees_lat = math.degrees(lat) % 30
        if min(degrees_lon, 30 - degrees_lon) < 0.35 or min(degrees_lat, 30 - degrees_lat) < 0.35:
            colour = tuple(0.5 * c + 0.25 for c in colour)
        return tuple(srgb(c) for c in colour)
    return png_bytes(width, height, pixel)


def make_globe():
    """A glTF 2.0 binary: the globe (texture embedded as a PNG buffer view), its brass stand (a
    metallic material), a node hierarchy with a tilt, a perspective camera and a point light."""
    p, n, t, tris = uv_sphere((0.0, 0.0, 0.0), 1.0, rings=48, segments=96)
    uv_top = [(u, 1.0 - v) for u, v in t]  # glTF's texture coordinates run from the top
    stand_p, stand_n, _, stand_t = uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=32)
    stand_p = [(0.5 * x, 0.08 * y - 1.25, 0.5 * z) for x, y, z in stand_p]  # a flat dish
    blob = bytearray()
    views, accessors = [], []

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        blob.extend(data)
        views.append(view)
        return len(views) - 1

    def add_accessor(values, kind, component=5126):
        flat = [c for v in values for c in (v if isinstance(v, tuple) else (v,))]
        fmt = "<%d%s" % (len(flat), "f" if component == 5126 else "I")
        view = add_view(struct.pack(fmt, *flat), 34963 if component == 5125 else 34962)
        accessor = {"bufferView": view, "componentType": component, "count": len(values),
                    "type": kind}
        if kind == "VEC3" and component == 5126:
            accessor["min"] = [min(v[k] for v in values) for k in range(3)]
            accessor["max"] = [max(v[k] for v in values) for k in range(3)]
        accessors.append(accessor)
        return len(accessors) - 1

    globe = {"attributes": {"POSITION": add_accessor(p, "VEC3"),
                            "NORMAL": add_accessor(n, "VEC3"),
                            "TEXCOORD_0": add_accessor(uv_top, "VEC2")},
             "indices": add_accessor([i for tri in tris for i in tri], "SCALAR", 5125),
             "material": 0}
    stand = {"attributes": {"POSITION": add_accessor(stand_p, "VEC3"),
                            "NORMAL": add_accessor(stand_n, "VEC3")},
             "indices": add_accessor([i for tri in stand_t for i in tri], "SCALAR", 5125),
             "material": 1}
    image_view = add_view(globe_texture())
    while len(blob) % 4:
        blob.append(0)
    tilt = math.radians(23.4) / 2
    document = {
        "asset": {"version": "2.0", "generator": "Prism scripts/make_scene_assets.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1.0, 0.95, 0.9], "intensity": 30000.0}]}},
        "scene": 0,
        "scenes": [{"name": "globe", "nodes": [0, 3, 4]}],
        "nodes": [
            {"name": "stand", "mesh": 1, "children": [1]},
            {"name": "axis", "rotation": [0.0, 0.0, -math.sin(tilt), math.cos(tilt)],
             "children": [2]},
            {"name": "globe", "mesh": 0, "rotation": [0.0, math.sin(0.6), 0.0, math.cos(0.6)]},
            {"name": "camera", "camera": 0, "translation": [0.0, 0.4, 4.2],
             "rotation": [-math.sin(0.05), 0.0, 0.0, math.cos(0.05)]},
            {"name": "lamp", "translation": [-3.0, 3.0, 3.0],
             "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": math.radians(40), "znear": 0.1,
                                     "aspectRatio": 16 / 9}}],
        "meshes": [{"name": "globe", "primitives": [globe]},
                   {"name": "stand", "primitives": [stand]}],
        "materials": [
            {"name": "map", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                     "metallicFactor": 0.0,
                                                     "roughnessFactor": 0.6}},
            {"name": "brass", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.25, 1.0],
                                                       "metallicFactor": 0.9,
                                                       "roughnessFactor": 0.3}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": image_view, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    with open(os.path.join(ROOT, "..", "globe.glb"), "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(blob)))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(blob), 0x004E4942) + bytes(blob))


if __name__ == "__main__":
    # Names make only those assets; none makes them all.
    wanted = sys.argv[1:] or ["sky", "trefoil", "still-life", "globe"]
    if "sky" in wanted:
        make_sky()
    if "trefoil" in wanted:
        make_trefoil()
    if "still-life" in wanted:
        make_still_life()
    if "globe" in wanted:
        make_globe()
