#!/usr/bin/env python3
# Copied from the project's shared tools so the benchmark is self-contained.
"""nff2tachyon.py - convert an Eric Haines NFF (SPD) scene to Tachyon's .dat
scene language, following the SPD rendering rules as closely as Tachyon allows.

Why: tachyon's built-in NFF reader (demosrc/nffparse.c in Tachyon 0.99b6)
  * ignores the 'angle' field (always ZOOM 1.0, i.e. a 53.13 deg field of view),
  * makes every NFF light a *visible* sphere of radius 1.0 (breaks SPD 'gears',
    whose 5th light sits 0.035 units from the eye: the whole image turns white),
  * ignores Shine (no Phong highlights) and the index of refraction,
  * fan-triangulates every polygon (wrong for the concave 144-gons of 'gears'),
  * fixes the ray depth at 6 (SPD asks for 5).
This converter keeps the SPD field of view, uses point lights of radius 0 with
the SPD-suggested intensity sqrt(n)/(2n) (ambient = that times Kd), adds Blinn/Phong highlights with the
NFF Shine exponent, ear-clips concave polygons, and sets RAYDEPTH 5.
What Tachyon cannot do is left as Tachyon does it: cones become cylinders
(FCYLINDER with the base radius; Tachyon has no cone), transmission is
straight-through (Tachyon has no refraction; ior is dropped).

usage: nff2tachyon.py in.nff > out.dat   (python3, standard library only)
"""
import math
import sys


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def norm(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0 else a


def newell(vs):
    n = [0.0, 0.0, 0.0]
    for i in range(len(vs)):
        a, b = vs[i], vs[(i + 1) % len(vs)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return tuple(n)


def triangulate(vs):
    """Return index triples. Fan for convex polygons, ear clipping otherwise."""
    n = len(vs)
    if n == 3:
        return [(0, 1, 2)]
    nrm = newell(vs)
    ax = max(range(3), key=lambda i: abs(nrm[i]))
    u, v = [(1, 2), (2, 0), (0, 1)][ax]
    sgn = 1.0 if nrm[ax] >= 0 else -1.0
    p = [(q[u], q[v]) for q in vs]

    def cr(o, a, b):
        return sgn * ((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))

    if all(cr(p[i], p[(i + 1) % n], p[(i + 2) % n]) >= -1e-12 for i in range(n)):
        return [(0, i, i + 1) for i in range(1, n - 1)]
    idx = list(range(n))
    tris = []
    guard = 0
    while len(idx) > 3 and guard < 10 * n * n:
        guard += 1
        m = len(idx)
        for k in range(m):
            i0, i1, i2 = idx[(k - 1) % m], idx[k], idx[(k + 1) % m]
            a, b, c = p[i0], p[i1], p[i2]
            if cr(a, b, c) <= 1e-14:
                continue  # reflex or degenerate corner
            inside = False
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                q = p[j]
                if cr(a, b, q) >= 0 and cr(b, c, q) >= 0 and cr(c, a, q) >= 0:
                    inside = True
                    break
            if not inside:
                tris.append((i0, i1, i2))
                idx.pop(k)
                break
        else:  # no ear found (numerical trouble): fall back to a fan
            tris.extend((idx[0], idx[t], idx[t + 1]) for t in range(1, len(idx) - 1))
            return tris
    tris.append(tuple(idx))
    return tris


def fmt(x):
    return "%.6g" % x


def vec(v):
    return " ".join(fmt(c) for c in v)


def main():
    # NFF comments: '#' to end of line
    tok = " ".join(line.split("#", 1)[0] for line in open(sys.argv[1])).split()
    pos = 0
    out = []
    lights = []
    objs = []
    cam = None
    bg = (0.0, 0.0, 0.0)
    ntex = 0
    cur = None

    def nums(k):
        nonlocal pos
        r = [float(t) for t in tok[pos:pos + k]]
        pos += k
        return r

    while pos < len(tok):
        t = tok[pos]
        pos += 1
        if t == "v":
            d = {}
            for key, k in (("from", 3), ("at", 3), ("up", 3), ("angle", 1), ("hither", 1), ("resolution", 2)):
                assert tok[pos] == key, (key, tok[pos])
                pos += 1
                d[key] = nums(k)
            cam = d
        elif t == "b":
            bg = tuple(nums(3))
        elif t == "l":
            c = nums(3)
            col = (1.0, 1.0, 1.0)
            if pos + 2 < len(tok):
                try:
                    col = tuple(float(x) for x in tok[pos:pos + 3])
                    pos += 3
                except ValueError:
                    pass
            lights.append((c, col))
        elif t == "f":
            r, g, b, kd, ks, shine, tr, ior = nums(8)
            ntex += 1
            cur = "t%d" % ntex
            objs.append(("tex", cur, (r, g, b), kd, ks, shine, tr))
        elif t == "s":
            x, y, z, rad = nums(4)
            objs.append(("s", cur, (x, y, z), rad))
        elif t == "c":
            b = nums(4)
            a = nums(4)
            objs.append(("c", cur, b, a))
        elif t == "p":
            n = int(tok[pos]); pos += 1
            vs = [tuple(nums(3)) for _ in range(n)]
            objs.append(("p", cur, vs))
        elif t == "pp":
            n = int(tok[pos]); pos += 1
            vs, ns = [], []
            for _ in range(n):
                q = nums(6)
                vs.append(tuple(q[:3]))
                ns.append(tuple(q[3:]))
            objs.append(("pp", cur, vs, ns))
        else:
            raise SystemExit("unknown NFF token %r at %d" % (t, pos))

    nl = max(1, len(lights))
    inten = math.sqrt(nl) / (nl * 2.0)  # SPD's suggested light/ambient level
    frm, at, up = cam["from"], cam["at"], cam["up"]
    view = norm(sub(at, frm))
    zoom = 0.5 / math.tan(math.radians(cam["angle"][0]) / 2.0)
    w = out.append
    w("BEGIN_SCENE")
    w("  RESOLUTION %d %d" % (int(cam["resolution"][0]), int(cam["resolution"][1])))
    w("CAMERA")
    w("  ZOOM %s" % fmt(zoom))
    w("  ASPECTRATIO 1.0")
    w("  ANTIALIASING 0")
    w("  RAYDEPTH 5")
    w("  CENTER %s" % vec(frm))
    w("  VIEWDIR %s" % vec(view))
    w("  UPDIR %s" % vec(norm(up)))
    w("END_CAMERA")
    w("BACKGROUND %s" % vec(bg))
    for c, col in lights:
        w("LIGHT CENTER %s RAD 0 COLOR %s" % (vec(c), vec(tuple(inten * x for x in col))))
    for o in objs:
        kind = o[0]
        if kind == "tex":
            _, name, col, kd, ks, shine, tr = o
            opac = 0.0 if tr > 0.99 else 1.0 - tr
            w("TEXDEF %s AMBIENT %s DIFFUSE %s SPECULAR %s OPACITY %s PHONG PLASTIC %s PHONG_SIZE %s COLOR %s TEXFUNC 0"
              % (name, fmt(inten * kd), fmt(kd), fmt(ks), fmt(opac), fmt(ks), fmt(max(1.0, shine)), vec(col)))
        elif kind == "s":
            w("SPHERE CENTER %s RAD %s %s" % (vec(o[2]), fmt(o[3]), o[1]))
        elif kind == "c":
            b, a = o[2], o[3]
            w("FCYLINDER BASE %s APEX %s RAD %s %s" % (vec(b[:3]), vec(a[:3]), fmt(abs(b[3])), o[1]))
        elif kind == "p":
            vs = o[2]
            for i, j, k in triangulate(vs):
                w("TRI V0 %s V1 %s V2 %s %s" % (vec(vs[i]), vec(vs[j]), vec(vs[k]), o[1]))
        elif kind == "pp":
            vs, ns = o[2], o[3]
            for i, j, k in triangulate(vs):
                w("STRI V0 %s V1 %s V2 %s N0 %s N1 %s N2 %s %s"
                  % (vec(vs[i]), vec(vs[j]), vec(vs[k]), vec(ns[i]), vec(ns[j]), vec(ns[k]), o[1]))
    w("END_SCENE")
    sys.stdout.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
