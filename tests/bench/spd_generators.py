#!/usr/bin/env python3
"""SPD-style NFF scene generators for benchmarks at sizes larger than the
small reference files in tests/data/nff/.

Written from the published descriptions of Eric Haines' Standard Procedural
Databases (SPD) and from the structure of the real SPD output files kept in
tests/data/nff/ (balls-s2.nff, tetra-s4.nff, rings-s3.nff); no SPD
source code was used.  At the reference sizes the output matches those files
number for number (to the 6 significant digits NFF files carry); larger sizes
follow the same recursive / repetitive construction.

Scenes
  balls SIZE   "sphereflake": a sphere of radius 0.5 carrying 9 child spheres
               of 1/3 its radius (3 around its top, 6 around its equator),
               recursively SIZE levels deep, above a square ground polygon,
               3 lights.  (9^(SIZE+1) - 1) / 8 spheres: s2 = 91, s3 = 820,
               s4 = 7381, s5 = 66430.
  tetra SIZE   Sierpinski tetrahedron: a tetrahedron replaced recursively by
               the 4 half-size tetrahedra at its corners, SIZE-1 levels deep;
               each leaf is written as 4 triangles.  4^SIZE triangles:
               s4 = 256, s6 = 4096, s8 = 65536.
  rings SIZE   a pyramid of groups of 6 interlocked pentagonal rings (each
               ring 5 spheres joined by 5 open cylinders, one colour per ring)
               in front of a white back wall, 3 lights.  Layer L = 1..SIZE
               holds L^2 groups: sum_{L=1..SIZE} L^2 groups, 30 spheres + 30
               cylinders each (s3 = 14 groups, 420 + 420; s7 = 140 groups,
               4200 + 4200).

  lattice SIZE a cubic lattice of (SIZE+1)^3 shiny spheres (radius 1/(4 SIZE)) in the
               unit cube, each joined to its neighbours by matte open cylinders
               (radius 1/(16 SIZE), red along x, green along y, blue along z), six
               lights around the cube, the eye inside the lattice's top face looking
               down through it (hither 0).  3 SIZE^2 (SIZE+1) cylinders: s12 = 2197
               spheres + 6084 cylinders (SPD's default size).  As SPD's lattice
               database describes it (header comment and constants); no real lattice
               file was available to compare with.
  shells SIZE  a sea shell after Pickover (IEEE CG&A, November 1989), as SPD's shells
               database builds it: 180 * 2^SIZE + 1 spheres along the logarithmic
               spiral r = e^(0.15 a), a = 18 pi i / steps, centre (r sin a, r cos a,
               -2 r), radius r, one light, no ground.  Consecutive spheres
               overlap almost entirely: SPD calls it a realistic yet pathological
               database (many overlapping, many tiny primitives).  No real shells
               file was available; the numbers follow the generator's published
               description (its header comment and constants), the material's
               highlight exponent converted from its 10-degree half angle as the
               balls file shows (exponent = ln 0.5 / ln cos 10 deg).

Only one size of each real SPD file was available to compare with, so what
varies with size beyond the recursion is inferred: the balls and tetra
cameras, lights and ground do not depend on size (the objects keep their
extent); every sphereflake node, at any depth, orients its 9 children by
the smallest rotation taking +z to its own direction from its parent (which
is what balls-s2 shows for depths 1 and 2); for rings the eye and lights stay put while the back wall moves to
depth (SIZE + 1) * 2.61313 and grows to fill the 45-degree view with a 1 %
margin, which reproduces rings-s3 exactly.

NFF written: 'b' background, 'v' viewpoint block, 'l' lights, 'f' materials,
's' spheres, 'c' cylinders, 'p' polygons (see the SPD NFF.TXT description).

usage: spd_generators.py {balls,tetra,rings,lattice,shells} SIZE > scene.nff
"""
import argparse
import math
import sys

BACKGROUND = (0.078, 0.361, 0.753)  # SPD's standard sky blue


# ----------------------------------------------------------------- helpers

def fmt(x):
    """Format a number the way SPD's NFF writer does (C's %g)."""
    return "%g" % x


def vec(v):
    return " ".join(fmt(c) for c in v)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return scale(a, 1.0 / n)


def mat_vec(m, v):
    return tuple(dot(row, v) for row in m)


class NffWriter:
    """Collects NFF lines and writes them to a stream."""

    def __init__(self, out):
        self.out = out

    def line(self, text):
        self.out.write(text + "\n")

    def background(self, rgb):
        self.line("b " + vec(rgb))

    def viewpoint(self, frm, at, up, angle, hither, res=512):
        self.line("v")
        self.line("from " + vec(frm))
        self.line("at " + vec(at))
        self.line("up " + vec(up))
        self.line("angle " + fmt(angle))
        self.line("hither " + fmt(hither))
        self.line("resolution %d %d" % (res, res))

    def light(self, pos):
        self.line("l " + vec(pos))

    def material(self, rgb, kd, ks, shine, t, ior):
        self.line("f %s %s %s %s %s %s" % (vec(rgb), fmt(kd), fmt(ks), fmt(shine), fmt(t), fmt(ior)))

    def sphere(self, c, r):
        self.line("s %s %s" % (vec(c), fmt(r)))

    def cylinder(self, base, r0, apex, r1):
        self.line("c %s %s %s %s" % (vec(base), fmt(r0), vec(apex), fmt(r1)))

    def polygon(self, verts):
        self.line("p %d" % len(verts))
        for v in verts:
            self.line(vec(v))


# ------------------------------------------------------------------- balls

def rotation_z_to(d):
    """Rotation matrix turning +z into the unit vector d by the smallest
    angle (about the axis z x d).  For d = -z, a half turn about x."""
    a, b, c = d
    if c < -1.0 + 1e-12:
        return ((1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, -1.0))
    k = 1.0 / (1.0 + c)
    return ((1.0 - a * a * k, -a * b * k, a),
            (-a * b * k, 1.0 - b * b * k, b),
            (-a, -b, c))


def flake_directions():
    """The 9 child directions of a sphereflake node in its own frame (+z is
    'outwards'): 3 at elevation asin(sqrt(2/3)) = 54.7 deg around the top,
    azimuths 45 + 120 i deg, each followed by two of the 6 equator directions
    at azimuths 15 + 120 i and 75 + 120 i deg (the order SPD writes them)."""
    top_el = math.asin(math.sqrt(2.0 / 3.0))
    dirs = []
    for i in range(3):
        for az_deg, el in ((45.0 + 120.0 * i, top_el), (15.0 + 120.0 * i, 0.0), (75.0 + 120.0 * i, 0.0)):
            az = math.radians(az_deg)
            dirs.append((math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)))
    return dirs


def gen_balls(size, w):
    """Sphereflake of depth SIZE on a ground square (SPD 'balls')."""
    w.background(BACKGROUND)
    w.viewpoint((2.1, 1.3, 1.7), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 45, 0.01)
    for pos in ((4.0, 3.0, 2.0), (1.0, -4.0, 4.0), (-3.0, 1.0, 5.0)):
        w.light(pos)
    # ground: a 24 x 24 square just below the flake
    w.material((1.0, 0.75, 0.33), 0.8, 0.0, 100000, 0, 1)
    w.polygon([(12.0, 12.0, -0.5), (-12.0, 12.0, -0.5), (-12.0, -12.0, -0.5), (12.0, -12.0, -0.5)])
    # flake: shiny pale-yellow spheres
    w.material((1.0, 0.9, 0.7), 0.5, 0.5, 3.0827, 0, 1)
    local_dirs = flake_directions()
    count = 0

    def flake(center, radius, direction, depth):
        nonlocal count
        w.sphere(center, radius)
        count += 1
        if depth == 0:
            return
        rot = rotation_z_to(direction)
        child_r = radius / 3.0
        for ld in local_dirs:
            d = mat_vec(rot, ld)  # child direction in world space
            flake(add(center, scale(d, radius + child_r)), child_r, d, depth - 1)

    flake((0.0, 0.0, 0.0), 0.5, (0.0, 0.0, 1.0), size)
    return "%d spheres + 1 polygon" % count


# ------------------------------------------------------------------- tetra

def gen_tetra(size, w):
    """Sierpinski tetrahedron, 4^SIZE triangles (SPD 'tetra')."""
    w.background(BACKGROUND)
    w.viewpoint((1.02285, -3.17715, -2.17451), (-0.004103, -0.004103, 0.216539),
                (-0.816497, -0.816497, 0.816497), 45, 1)
    w.light((2.0, -18.0, -5.0))
    w.material((1.0, 0.2, 0.2), 1, 0, 100000, 0, 0)
    count = 0

    def tetra(v, depth):
        nonlocal count
        a, b, c, d = v
        if depth == 0:
            for tri in ((a, b, c), (d, c, b), (c, d, a), (b, a, d)):
                w.polygon(tri)
                count += 1
            return
        for corner in v:  # the half-size tetrahedron at each corner, in order
            tetra([scale(add(corner, q), 0.5) for q in v], depth - 1)

    tetra([(-1.0, -1.0, 1.0), (-1.0, 1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, 1.0)], max(0, size - 1))
    return "%d triangles" % count


# ------------------------------------------------------------------- rings

RING_COLOURS = ((1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1), (1, 1, 0))
RING_SPACING = 1.0 / math.sin(math.radians(22.5))  # 2.61313: layer spacing (y), as in SPD rings-s3
RING_THICKNESS = 0.07412  # radius of the corner spheres and edge cylinders
RING_RADIUS = 1.0 / (1.0 + RING_THICKNESS)  # 0.930995: centre to corner of each pentagon


def ring_frames():
    """(normal, first-corner direction) of the 6 rings of one group: one ring
    in the z = 0 plane, five tilted with normals at elevation atan(1/2)
    (icosahedron vertices) and azimuths -54 + 72 i deg; the first corner of
    each tilted ring lies horizontal, 90 deg round from its normal."""
    frames = [((0.0, 0.0, 1.0), (1.0, 0.0, 0.0))]
    el = math.atan(0.5)
    for i in range(5):
        az = math.radians(-54.0 + 72.0 * i)
        n = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
        u = (-math.sin(az), math.cos(az), 0.0)
        frames.append((n, u))
    return frames


def gen_rings(size, w):
    """Pyramid of groups of 6 interlocked pentagonal rings in front of a
    white wall (SPD 'rings'): layer L = 0..SIZE-1 holds (L+1)^2 groups on a
    grid of spacing 2 at depth y = (L+1) * RING_SPACING."""
    eye = (-1.0, -RING_SPACING, 0.5)
    angle = 45.0
    w.background(BACKGROUND)
    w.viewpoint(eye, add(eye, (0.0, 1.0, 0.0)), (0.0, 0.0, 1.0), angle, 1)
    for x, z in ((3.0, 3.0), (-4.0, 1.0), (2.0, -4.0)):
        w.light((x, eye[1], z))
    # back wall just filling the view (1 % margin)
    wall_y = (size + 1) * RING_SPACING
    half = 1.01 * math.tan(math.radians(angle) / 2.0) * (wall_y - eye[1])
    w.material((1.0, 1.0, 1.0), 1, 0, 100000, 0, 0)
    w.polygon([(eye[0] + half, wall_y, eye[2] + half), (eye[0] - half, wall_y, eye[2] + half),
               (eye[0] - half, wall_y, eye[2] - half), (eye[0] + half, wall_y, eye[2] - half)])
    frames = ring_frames()
    count = 0
    for layer in range(size):
        y = (layer + 1) * RING_SPACING
        coords = [2.0 * k - layer for k in range(layer + 1)]
        for z in coords:
            for x in coords:
                centre = (x, y, z)
                for colour, (n, u) in zip(RING_COLOURS, frames):
                    w.material(colour, 0.5, 0.2, 3.0827, 0, 0)
                    v = cross(n, u)
                    corners = []
                    for k in range(5):
                        t = math.radians(72.0 * k)
                        corners.append(add(centre, add(scale(u, RING_RADIUS * math.cos(t)),
                                                       scale(v, RING_RADIUS * math.sin(t)))))
                    for k in range(5):
                        w.cylinder(corners[k], RING_THICKNESS, corners[k - 1], RING_THICKNESS)
                        w.sphere(corners[k], RING_THICKNESS)
                        count += 1
    return "%d spheres + %d cylinders + 1 polygon" % (count, count)


# ----------------------------------------------------------------- lattice

def gen_lattice(size, w):
    """Spheres on a cubic grid joined by axis-parallel cylinders (SPD 'lattice')."""
    w.background(BACKGROUND)
    step = 1.0 / size
    middle = ((size >> 1) + 0.5) * step
    dip = 1.0 / (size << 1)
    w.viewpoint((middle, 1.0, 1.0 - dip), (middle, -1.0, -1.0 - dip), (0.2, 1.0, 0.0), 60, 0.0)
    for pos in ((2.0, 0.5, 0.5), (-1.0, 0.5, 0.5), (0.5, 2.0, 0.5), (0.5, -1.0, 0.5),
                (0.5, 0.5, 2.0), (0.5, 0.5, -1.0)):
        w.light(pos)
    ball = 0.25 * step
    rod = 0.0625 * step
    # the rods start inside the balls, just short of where their rims would show
    inset = ball * (1.0 - math.sqrt(0.0625 / 0.25)) * 0.99
    rod_colours = ((0.9, 0.1, 0.1), (0.1, 0.9, 0.1), (0.1, 0.1, 0.9))
    spheres = cylinders = 0
    for x in range(size + 1):
        for y in range(size + 1):
            for z in range(size + 1):
                p = (x * step, y * step, z * step)
                w.material((0.9, 0.9, 0.9), 0.5, 0.5, 3.0827, 0, 0)
                w.sphere(p, ball)
                spheres += 1
                for axis, index in enumerate((x, y, z)):
                    if index == size:
                        continue
                    w.material(rod_colours[axis], 0.99, 0, 100000, 0, 0)
                    start = list(p)
                    end = list(p)
                    start[axis] += inset
                    end[axis] += step - inset
                    w.cylinder(tuple(start), rod, tuple(end), rod)
                    cylinders += 1
    return "%d spheres + %d cylinders" % (spheres, cylinders)


# ------------------------------------------------------------------ shells

def gen_shells(size, w):
    """Pickover's shell as SPD's 'shells' lays it out: overlapping spheres on a spiral."""
    w.background(BACKGROUND)
    w.viewpoint((-6.0, -60.0, 35.0), (0.0, 8.0, -15.0), (0.0, 0.0, 1.0), 45, 0.5)
    w.light((-100.0, -100.0, 100.0))
    half_angle = math.radians(10.0)
    w.material((1.0, 0.8, 0.4), 0.8, 0.2, math.log(0.5) / math.log(math.cos(half_angle)), 0, 1)
    steps = 180 * 2 ** size
    count = 0
    for i in range(-(steps * 2 // 3), steps // 3 + 1):
        angle = 18.0 * math.pi * i / steps
        r = math.exp(0.15 * angle)
        w.sphere((r * math.sin(angle), r * math.cos(angle), -2.0 * r), r)
        count += 1
    return "%d spheres" % count


GENERATORS = {"balls": gen_balls, "tetra": gen_tetra, "rings": gen_rings, "lattice": gen_lattice,
              "shells": gen_shells}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.rsplit("\nusage:", 1)[0],
                                 epilog="Writes NFF to standard output (or -o FILE); a one-line count of the "
                                        "primitives goes to standard error.",
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", choices=sorted(GENERATORS), help="which database")
    ap.add_argument("size", type=int, help="SPD size factor (recursion depth / repetition count)")
    ap.add_argument("-o", "--output", help="write here instead of standard output")
    args = ap.parse_args(argv)
    if args.size < 1:
        ap.error("size must be at least 1")
    out = open(args.output, "w") if args.output else sys.stdout
    try:
        summary = GENERATORS[args.scene](args.size, NffWriter(out))
    finally:
        if args.output:
            out.close()
    print("%s-s%d: %s" % (args.scene, args.size, summary), file=sys.stderr)


if __name__ == "__main__":
    main()
