#!/usr/bin/env python3
"""Time against error of Prism's photon-mapped caustics and POV-Ray 3.7's photons.

Scene: --scene, a glass ball over a diffuse plane under one point light (default
scenes/caustic-glass-sphere.yaml: n = 1.5, a white floor, 150 W/sr; also
tests/bench/scenes/glass-ball-top.yaml and glass-ball-oblique.yaml).  The script reads the scene
(a small reader for the YAML these scenes use; it refuses, naming the key, anything it cannot
translate: see load_scene), writes Prism's copy of it at --size and POV-Ray's translation, checks
that the two renderers see the same picture and agree on direct light, then times both renderers
over a range of photon budgets and measures each image's error against a reference.

Two references, two sets of error measures:

  * default: Prism's own converged render (progressive, --ref-passes passes, another seed; cached
    in --ref-dir), and the absolute RMSEs described under "Error" below.  What the first
    comparison (docs/caustics.md) used; a reference made by one of the two contestants.
  * --exact-reference TOOL (build/tests/prism_sphere_caustic_reference): the exact caustic,
    computed independently of both renderers (light rays traced through the ball analytically,
    binned on the plane, pixel-averaged through the camera; --exact-rays, --exact-samples,
    --exact-bins; built once, cached in --ref-dir; ~2 min at 1024^2 on 2 threads; its own error
    bounded by a second one from --exact-check-rays rays).  Every image, POV-Ray's and Prism's,
    is scored by the tool: its caustic is the image minus one direct-light image, Prism's render
    of the same scene with the ball's caustic role off (the ball blocks shadow rays and casts
    nothing; tests/bench/caustic_convergence.py, whose helpers this script imports).  Measures,
    over the caustic region (reference above 1 % of the plane's direct radiance scale albedo I /
    (pi h^2)): relative RMSE ||x - r|| / ||r|| of the channel mean, the same over the regular
    part (without the focus, folds and edges), the flux ratio sum x / sum r, and the 9x9 pixels
    around the focus summed, relative to the reference.  The same direct image serves POV-Ray
    because POV-Ray's direct light is Prism's: the calibration below checks it pixel by pixel,
    and the script prints the relative RMSE that the difference between the two direct images
    alone gives at --size (POV-Ray's render with the ball blocking light but no caustic,
    "POV-Ray direct", see pov_scene), the floor under POV-Ray's scores.  POV-Ray's own
    photon-less render is not a direct image: its shadow rays pass through the glass's filter
    pigment, so the floor under the ball is lit as if the ball were not there.

Units.  POV-Ray's point light with `fade_distance D fade_power 2` falls off as
2 / (1 + (d/D)^2) = 2 D^2 / (D^2 + d^2), and its diffuse term has no 1/pi; so the light of
I W/sr becomes `color rgb I / (2 pi D^2)` with D = 0.001 (relative error D^2/d^2 < 1e-7 here),
and the floor `pigment { rgb albedo } finish { diffuse 1 ambient 0 }`, `assumed_gamma 1.0`.  A
pixel then holds rho/pi * E in W/(m^2 sr), as in Prism.  POV-Ray is left-handed: Prism's
(x, y, z) is (x, y, -z), the camera's up is POV-Ray's `sky`.  Glass: `pigment { rgbf 1 }`,
`interior { ior n }`, `reflection { 0, 1 fresnel on } conserve_energy` (reflected weight F,
refracted 1 - F, as Prism's Fresnel split), Phong highlight `phong pi*specular phong_size
shininess` (POV-Ray's light colour carries the 1/pi of the diffuse calibration) on the outside
only, through an interior_texture without it: Prism's glass blocks the shadow rays of its own
inner surfaces, POV-Ray's lets them through its filter pigment (it blocks shadow rays at a photon
target only for surfaces that collect photons), which drew highlights inside the ball (the top
view's highlight 1.5 times Prism's; `collect on` on the glass would block them, but POV-Ray then
stores photons on the glass too and, for the same count, shot a third as many).  No ambient, no
radiosity.  Depth: Prism max_depth bounces after the primary ray = POV-Ray max_trace_level
max_depth + 1; photons follow up to the scene's max_bounces (16) specular bounces in both;
adc_bailout = Prism's min_contribution.  One sample per pixel through the pixel centre in both
(Prism --spp 1, POV-Ray -A).  With photons on, POV-Ray's shadow rays from the floor are blocked
by the refracting photon target (without photons they would pass through the filter pigment).

Calibration (256x256, before the runs; a failed check stops the script): the plain floor (no
sphere), per-pixel ratio POV-Ray / Prism (median, min, max); an opaque ball instead of the glass
one, the share of pixels where the two differ by more than 1 % (same camera, same geometry, same
shadow: a mirrored view fails); the same for the glass ball's direct light (Fresnel split,
highlight, shadow; "POV-Ray direct" above); and POV-Ray's photon units with an index-1 "glass"
ball (light passes straight, the photons under it must give the same floor radiance as the plain
floor: light is neither lost nor doubled).

Budgets.  Prism classic: --photons N (or its own list, --prism-photons) with k = gather(N)
nearest photons (--prism-gather scene: the scene's k, what a user of the scene gets; Prism's
per-photon radii cost time in proportion to N k, so the rule's k makes large N slow).  POV-Ray:
photons { count N gather 20, gather(N) radius R jitter 1 } (count asks for about N photons; the
number it really shot is read from its log and reported).
Both use the same rule gather(N) = clamp(sqrt(N)/4, 50, 1000): a fixed k does not converge for
POV-Ray (docs: /work/shared/notes/peers.md), and the same rule is given to Prism.  POV-Ray's
gather radius R is Prism's largest k-NN radius (the scene's max_radius, or a tenth of the ball's
radius), so both estimate with the k nearest photons within R: its automatic radius failed at
some budgets (scattered single photons on a black shadow).  Prism progressive: --progressive
--passes P (the scene's photons per pass).

Error (default mode): RMSE over all pixels and channels of the linear radiance against the
reference, and the same over a caustic mask: the pixels where the reference exceeds Prism's
direct-light-only image (--caustics none) by more than --mask-threshold W/(m^2 sr); and over that
mask without the focal spot (reference above --focus-threshold): the point light's image through
the ball is nearly singular, a few pixels hold radiance in the hundreds, every estimator blurs
them and they dominate the first two measures (the reference itself is not converged there: the
check against a --ref-check-passes reference shows it).  Also printed: the caustic region's mean
brightness and the value at the reference's brightest pixel, each relative to the reference.

Time: wall seconds of the whole process (median of --repeats runs) and CPU seconds (user +
system of the child, median).  Runs are interleaved (every round runs each budget of each
renderer once, the order rotating) since the machine is shared and noisy.  Both renderers use
--threads threads.  Then, for each error measure, the time Prism needs to reach POV-Ray's best
(log-log interpolated between its budgets).

Images are read back with OpenImageIO's oiiotool (converted to uncompressed float TIFF, parsed
here); POV-Ray writes half-float OpenEXR (+FE), Prism float OpenEXR.  The chart is drawn with
gnuplot (Debian gnuplot-nox) if it is installed; the CSV and table are written either way.

Python 3, standard library only, no numpy (plus the command-line tools povray, oiiotool from
openimageio-tools, and gnuplot from gnuplot-nox).

Example (what made docs/caustics-povray.png, Prism's long run as the reference):
  tests/bench/povray_caustics.py --ref-dir /tmp/prism-caustic-ref --out /tmp/povray-caustics3 \\
      --size 1024 --repeats 3 --ref-passes 256 --photons 100000,300000,1000000,3000000 \\
      --passes 1,2,4,8,16,32 --chart docs/caustics-povray.png --csv docs/caustics-povray.csv
(about 15 minutes on a 2-core VM, 221 s of it the reference, which is cached in --ref-dir).
Against the exact reference (an estimated 13 minutes a scene on the 2-core VM, 4 of them the
two cached references; POV-Ray renders the whole view's caustic, so its runs take about twice
the default scene's):
  tests/bench/povray_caustics.py --prism build/prism \\
      --exact-reference build/tests/prism_sphere_caustic_reference --exact-check-rays 50000000 \\
      --scene tests/bench/scenes/glass-ball-oblique.yaml --ref-dir /tmp/exact-ref \\
      --out /tmp/povray-exact-oblique --size 1024 --threads 2 --repeats 3 \\
      --photons 30000,100000,300000,1000000,3000000 \\
      --prism-gather scene --prism-photons 100000,200000,500000,1000000 --passes 1,2,4,8,16,32
A quick check: --size 128 --repeats 1 --ref-passes 8 --ref-check-passes 4 --photons 100000
--passes 1,3 (with --exact-reference: --exact-rays 20000000 --photons 100000 --passes 1,3).
"""
import argparse
import csv
import hashlib
import math
import os
import resource
import shutil
import statistics
import struct
import subprocess
import sys
import time
from types import SimpleNamespace

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import caustic_convergence as exact  # noqa: E402  (the exact reference's helpers, shared)

SCENE = os.path.join(REPO, "scenes", "caustic-glass-sphere.yaml")
FADE_D = 0.001


def die(msg):
    sys.exit("povray_caustics: error: " + msg)


def gather_k(n):
    return int(min(1000, max(50, round(math.sqrt(n) / 4))))


# ------------------------------------------------------------------ scene reader

# Only what the glass-ball scenes use: block mappings and sequences, one-line (or bracket-continued)
# flow lists and maps of scalars, `#` comments.  Prism's own loader (yaml-cpp) stays the judge of
# the file; this reader only has to see the same values in it.

def _strip_comment(line):
    quote = None
    for i, c in enumerate(line):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1] in " \t"):
            return line[:i]
    return line


def _yaml_lines(path):
    """[line number, indent, text] per meaningful line; a flow collection spread over several
    lines is joined into its first."""
    lines, open_brackets = [], 0
    with open(path) as f:
        for no, raw in enumerate(f, 1):
            text = _strip_comment(raw.rstrip("\n")).rstrip()
            if not text.strip():
                continue
            if "\t" in text[:len(text) - len(text.lstrip())]:
                die("%s:%d: tab in indentation" % (path, no))
            if open_brackets > 0:
                lines[-1][2] += " " + text.strip()
            else:
                lines.append([no, len(text) - len(text.lstrip()), text.strip()])
            open_brackets += text.count("[") + text.count("{") - text.count("]") - text.count("}")
    return lines


def _scalar(word, where):
    if len(word) >= 2 and word[0] == word[-1] and word[0] in "'\"":
        return word[1:-1]
    if word in ("true", "True", "TRUE"):
        return True
    if word in ("false", "False", "FALSE"):
        return False
    for kind in (int, float):
        try:
            return kind(word)
        except ValueError:
            pass
    if not word:
        die("%s: empty value" % where)
    return word


def _flow(text, where):
    """Value of a flow text: a scalar, [a, b, ...] or {k: v, ...}, nested."""
    pos = 0

    def value():
        nonlocal pos
        while text[pos] == " ":
            pos += 1
        if text[pos] in "[{":
            close = "]" if text[pos] == "[" else "}"
            items = [] if close == "]" else {}
            pos += 1
            while True:
                while text[pos] == " ":
                    pos += 1
                if text[pos] == close:
                    pos += 1
                    return items
                if close == "]":
                    items.append(value())
                else:
                    colon = text.index(":", pos)
                    key = text[pos:colon].strip()
                    pos = colon + 1
                    items[key] = value()
                while text[pos] == " ":
                    pos += 1
                if text[pos] == ",":
                    pos += 1
                elif text[pos] != close:
                    die("%s: expected ',' or '%s' in %r" % (where, close, text))
        end = pos
        while end < len(text) and text[end] not in ",]}":
            end += 1
        word, pos = text[pos:end].strip(), end
        return _scalar(word, where)

    try:
        v = value()
    except (IndexError, ValueError):
        die("%s: cannot read %r" % (where, text))
    if text[pos:].strip():
        die("%s: unexpected %r" % (where, text[pos:]))
    return v


def _block(lines, i, indent, path):
    """(value, next line) of the block mapping or sequence at `indent` starting at line i."""
    if lines[i][2] == "-" or lines[i][2].startswith("- "):
        seq = []
        while i < len(lines) and lines[i][1] == indent and (
                lines[i][2] == "-" or lines[i][2].startswith("- ")):
            no, _, text = lines[i]
            rest = text[1:].lstrip()
            if not rest:  # "-" alone: the item is the block below
                value, i = _block(lines, i + 1, lines[i + 1][1], path)
            elif ":" in rest and not rest.startswith(("[", "{", "'", '"')):
                # "- key: ...": a mapping whose first key sits on the dash's line
                lines[i] = [no, indent + len(text) - len(rest), rest]
                value, i = _block(lines, i, lines[i][1], path)
            else:
                value, i = _flow(rest, "%s:%d" % (path, no)), i + 1
            seq.append(value)
        return seq, i
    mapping = {}
    while i < len(lines) and lines[i][1] == indent and not lines[i][2].startswith("- "):
        no, _, text = lines[i]
        where = "%s:%d" % (path, no)
        key, colon, rest = text.partition(":")
        if not colon or not key.strip():
            die("%s: expected 'key: value', found %r" % (where, text))
        key = key.strip()
        if key in mapping:
            die("%s: '%s' given twice" % (where, key))
        i += 1
        if rest.strip():
            mapping[key] = _flow(rest.strip(), where)
        elif i < len(lines) and (lines[i][1] > indent or (
                lines[i][1] == indent and lines[i][2].startswith("- "))):
            mapping[key], i = _block(lines, i, lines[i][1], path)
        else:
            mapping[key] = None
    if i < len(lines) and lines[i][1] > indent:
        die("%s:%d: unexpected indentation" % (path, lines[i][0]))
    return mapping, i


def read_yaml(path):
    lines = _yaml_lines(path)
    if not lines:
        die("%s is empty" % path)
    doc, i = _block(lines, 0, lines[0][1], path)
    if i < len(lines) or not isinstance(doc, dict):
        no = lines[min(i, len(lines) - 1)][0]
        die("%s:%d: cannot read the document's structure" % (path, no))
    return doc


def load_scene(path):
    """The glass-ball scene as the translation needs it.  Takes exactly one sphere of clear glass
    (diffuse 0, transmittance 1, no mirror reflectance) over one plane of Lambertian colour, one
    point light with inverse-square falloff, a perspective camera, no ambient or background; any
    other key or value is refused by name (POV-Ray would not be rendering the same scene)."""
    doc = read_yaml(path)

    def fail(msg):
        die("%s: %s (this script translates a glass ball over a plane under one point light only)"
            % (path, msg))

    def section(name, allowed, m):
        if m is None:
            return {}
        if not isinstance(m, dict):
            fail("'%s' must be a mapping" % name)
        for k in m:
            if k not in allowed:
                fail("'%s' in '%s' is not translated (known: %s)" % (k, name, ", ".join(allowed)))
        return m

    def num(m, key, default, name):
        v = m.get(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            fail("%s.%s must be a number, found %r" % (name, key, v))
        return float(v)

    def vec(m, key, default, name):
        v = m.get(key, default)
        if not (isinstance(v, list) and len(v) == 3 and all(
                isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)):
            fail("%s.%s must be [x, y, z], found %r" % (name, key, v))
        return tuple(float(x) for x in v)

    def colour(m, key, default, name):  # one number means grey
        v = m.get(key, default)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            v = [v] * 3
        return vec({key: v}, key, None, name)

    def grey(m, key, default, name):
        c = colour(m, key, default, name)
        if c[0] != c[1] or c[1] != c[2]:
            fail("%s.%s must be grey (one number), found %r" % (name, key, c))
        return c[0]

    section("the scene", ["camera", "render", "caustics", "materials", "lights", "objects",
                   "background", "ambient"], doc)
    for key in ("background", "ambient"):
        if key in doc and grey(doc, key, 0, "scene") != 0:
            fail("'%s' must be 0" % key)
    cam = section("camera", ["projection", "position", "look_at", "up", "fov", "near"],
                  doc.get("camera"))
    if cam.get("projection", "perspective") != "perspective":
        fail("camera.projection must be perspective")
    if num(cam, "near", 0, "camera") != 0:
        fail("camera.near must be 0")
    ren = section("render", ["width", "height", "samples", "max_depth", "min_contribution", "seed",
                             "exposure", "triangle_test"], doc.get("render"))
    # (render size and samples: the script's own, --size and one sample through the pixel centre)
    cau = section("caustics", ["method", "photons", "gather", "max_radius", "filter", "max_bounces",
                               "alpha"], doc.get("caustics"))
    materials = {"default": {}}
    for m in doc.get("materials") or []:
        m = section("materials", ["name", "ambient", "diffuse", "specular", "shininess",
                                  "reflectance", "transmittance", "ior", "fresnel"], m)
        materials[m.get("name")] = m
    lights = doc.get("lights") or []
    if len(lights) != 1:
        fail("needs exactly one light, found %d" % len(lights))
    light = section("lights", ["position", "intensity", "attenuation"], lights[0])
    if vec(light, "attenuation", [0, 0, 1], "light") != (0.0, 0.0, 1.0):
        fail("the light's attenuation must be [0, 0, 1] (POV-Ray's fade_power 2 is translated)")
    spheres, planes = [], []
    for o in doc.get("objects") or []:
        if not isinstance(o, dict) or len(o) != 1 or list(o)[0] not in ("sphere", "plane"):
            fail("objects must be one sphere and one plane, found %r" % o)
        kind, body = list(o.items())[0]
        body = section(kind, (["center", "radius"] if kind == "sphere" else ["point", "normal"])
                       + ["material", "caustic"], body)
        if str(body.get("caustic", "auto")).lower() != "auto":
            fail("%s.caustic must be auto" % kind)
        if body.get("material", "default") not in materials:
            fail("unknown material %r" % body.get("material"))
        (spheres if kind == "sphere" else planes).append(body)
    if len(spheres) != 1 or len(planes) != 1:
        fail("needs exactly one sphere and one plane")
    sphere, plane = spheres[0], planes[0]
    glass = materials[sphere.get("material", "default")]
    floor = materials[plane.get("material", "default")]
    for name, m, zero in (
            ("glass", glass, ("ambient", "diffuse", "reflectance")),
            ("floor", floor, ("ambient", "specular", "reflectance", "transmittance"))):
        for key in zero:
            if colour(m, key, 0.8 if key == "diffuse" else 0, name) != (0.0, 0.0, 0.0):
                fail("the %s material's %s must be 0" % (name, key))
    if colour(glass, "transmittance", 0, "glass") != (1.0, 1.0, 1.0):
        fail("the glass material's transmittance must be 1")
    fresnel = glass.get("fresnel", True)
    if not isinstance(fresnel, bool):
        fail("glass.fresnel must be true or false")
    normal = vec(plane, "normal", None, "plane")
    n_len = math.sqrt(sum(x * x for x in normal))
    if n_len == 0:
        fail("the plane's normal is zero")
    sc = SimpleNamespace(
        path=path,
        cam_pos=vec(cam, "position", [0, 0, 5], "camera"),
        cam_at=vec(cam, "look_at", [0, 0, 0], "camera"),
        cam_up=vec(cam, "up", [0, 1, 0], "camera"),
        fov=num(cam, "fov", 45, "camera"),
        max_depth=int(num(ren, "max_depth", 5, "render")),
        min_contribution=num(ren, "min_contribution", 0.001, "render"),
        seed=int(num(ren, "seed", 0, "render")),
        photons=int(num(cau, "photons", 200000, "caustics")),
        gather=int(num(cau, "gather", 100, "caustics")),
        max_radius=num(cau, "max_radius", 0, "caustics"),
        filter=str(cau.get("filter", "cone")),
        max_bounces=int(num(cau, "max_bounces", 16, "caustics")),
        alpha=num(cau, "alpha", 0.7, "caustics"),
        floor_albedo=colour(floor, "diffuse", 0.8, "floor"),
        sphere_c=vec(sphere, "center", None, "sphere"),
        sphere_r=num(sphere, "radius", None, "sphere"),
        ior=num(glass, "ior", 1.5, "glass"),
        fresnel=fresnel,
        specular=grey(glass, "specular", 0, "glass"),
        shininess=num(glass, "shininess", 32, "glass"),
        light_pos=vec(light, "position", None, "light"),
        light_i=colour(light, "intensity", 1, "light"),
        plane_point=vec(plane, "point", None, "plane"),
        plane_normal=tuple(x / n_len for x in normal),
    )
    # Prism's automatic largest k-NN radius: a tenth of the (only) caster's bounding radius.
    sc.radius = sc.max_radius or 0.1 * sc.sphere_r
    return sc


# ------------------------------------------------------------------ images

def read_tiff_float(path):
    """(width, height, channels, flat tuple of floats) of an uncompressed float TIFF."""
    with open(path, "rb") as f:
        d = f.read()
    e = {b"II": "<", b"MM": ">"}[d[:2]]
    off = struct.unpack(e + "I", d[4:8])[0]
    n = struct.unpack(e + "H", d[off:off + 2])[0]
    sizes = {1: 1, 3: 2, 4: 4, 11: 4, 12: 8, 16: 8}
    codes = {1: "B", 3: "H", 4: "I", 11: "f", 12: "d", 16: "Q"}
    tags = {}
    for i in range(n):
        p = off + 2 + 12 * i
        tag, typ, cnt = struct.unpack(e + "HHI", d[p:p + 8])
        if typ not in codes:
            continue
        sz = sizes[typ] * cnt
        vo = p + 8 if sz <= 4 else struct.unpack(e + "I", d[p + 8:p + 12])[0]
        tags[tag] = struct.unpack(e + str(cnt) + codes[typ], d[vo:vo + sz])
    w, h, spp = tags[256][0], tags[257][0], tags[277][0]
    if tags[258][0] != 32 or tags.get(339, (1,))[0] != 3 or tags.get(259, (1,))[0] != 1:
        die("%s is not an uncompressed 32-bit float TIFF" % path)
    if 322 in tags:
        die("%s is tiled" % path)
    data = b"".join(d[o:o + c] for o, c in zip(tags[273], tags[279]))
    return w, h, spp, struct.unpack(e + str(w * h * spp) + "f", data[:w * h * spp * 4])


def read_image(path):
    """Linear RGB of an EXR/HDR file as (w, h, flat list r,g,b,r,g,b,...), top row first."""
    tmp = path + ".float.tif"
    subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "float", "--compression", "none",
                    "-o", tmp], check=True)
    w, h, spp, v = read_tiff_float(tmp)
    os.remove(tmp)
    if spp != 3:
        die("%s: expected 3 channels" % path)
    return w, h, v


def write_png(exr, png):
    subprocess.run(["oiiotool", exr, "--ch", "R,G,B", "--colorconvert", "linear", "sRGB",
                    "-d", "uint8", "-o", png], check=True)


def rmse(a, b, mask=None):
    if mask is None:
        s = sum((x - y) ** 2 for x, y in zip(a, b))
        return math.sqrt(s / len(a))
    s, n = 0.0, 0
    for i in mask:
        for c in range(3):
            s += (a[3 * i + c] - b[3 * i + c]) ** 2
        n += 3
    return math.sqrt(s / n)


def region_mean(v, mask):
    return sum(v[3 * i] + v[3 * i + 1] + v[3 * i + 2] for i in mask) / (3 * len(mask))


# ------------------------------------------------------------------ scenes

def _v(v):
    return "[%r, %r, %r]" % tuple(v)


def prism_yaml(sc, path, size, sphere=True, ior=None, fresnel=None, specular=None, opaque=False):
    """Prism's copy of the scene at size x size (the reference tool takes the size from the
    file), optionally without the sphere, with another glass, or with an opaque white ball."""
    ball = ("  - name: ball\n    diffuse: %s\n" % _v(sc.floor_albedo) if opaque else
            "  - name: glass\n    diffuse: 0\n    specular: %r\n    shininess: %r\n"
            "    transmittance: 1\n    ior: %r\n    fresnel: %s\n"
            % (sc.specular if specular is None else specular, sc.shininess,
               sc.ior if ior is None else ior,
               "true" if (sc.fresnel if fresnel is None else fresnel) else "false"))
    objs = "  - plane: {point: %s, normal: %s, material: floor}\n" % (
        _v(sc.plane_point), _v(sc.plane_normal))
    if sphere:  # one flow line: caustic_convergence.write_direct_scene edits it
        objs = ("  - sphere: {center: %s, radius: %r, material: %s}\n"
                % (_v(sc.sphere_c), sc.sphere_r, "ball" if opaque else "glass")) + objs
    with open(path, "w") as f:
        f.write("""# written by tests/bench/povray_caustics.py from %s
camera:
  position: %s
  look_at: %s
  up: %s
  fov: %r
render:
  width: %d
  height: %d
  samples: 1
  max_depth: %d
  min_contribution: %r
  seed: %d
caustics:
  method: photon_map
  photons: %d
  gather: %d
  max_radius: %r
  filter: %s
  max_bounces: %d
  alpha: %r
materials:
  - name: floor
    diffuse: %s
%slights:
  - position: %s
    intensity: %s
    attenuation: [0, 0, 1]
objects:
%s""" % (os.path.relpath(sc.path, REPO), _v(sc.cam_pos), _v(sc.cam_at), _v(sc.cam_up), sc.fov,
         size, size, sc.max_depth, sc.min_contribution, sc.seed, sc.photons, sc.gather,
         sc.max_radius, sc.filter, sc.max_bounces, sc.alpha, _v(sc.floor_albedo), ball,
         _v(sc.light_pos), _v(sc.light_i), objs))


def pov_scene(sc, path, sphere=True, ior=None, fresnel=None, specular=None, count=None, k=100,
              opaque=False, direct_only=False):
    """POV-Ray 3.7 translation.  POV-Ray is left-handed: Prism's (x, y, z) is (x, y, -z).
    count: photons on (about count photons, k nearest).  opaque: a white ball instead of the
    glass.  direct_only: the glass ball blocking the light as in Prism, no caustic."""
    colour = tuple(i / (2.0 * math.pi * FADE_D ** 2) for i in sc.light_i)
    p = lambda v: "<%r, %r, %r>" % (v[0], v[1], -v[2])  # noqa: E731  (a point or direction)
    c = lambda v: "<%r, %r, %r>" % tuple(v)  # noqa: E731  (a colour)
    fresnel = sc.fresnel if fresnel is None else fresnel
    phong = math.pi * (sc.specular if specular is None else specular)
    glass_finish = lambda ph: (  # noqa: E731
        "diffuse 0 ambient 0 specular 0 phong %r phong_size %r %s conserve_energy"
        % (ph, sc.shininess, "reflection { 0, 1 fresnel on }" if fresnel else ""))
    # POV-Ray treats a photon target as opaque to shadow rays only from surfaces that collect
    # photons, and only when its photon map holds some (measured: a floor with `collect off`,
    # or an empty map, and the ball's shadow is gone).  direct_only therefore keeps photons on,
    # but sends them (the ball's share divided by 10^6: none) to a second glass ball far behind
    # the camera, whose caustic lands out of view.
    target, extra = "target", ""
    if direct_only:
        count, target = 20000, "target 1000000"
        dot = lambda u, v: sum(x * y for x, y in zip(u, v))  # noqa: E731
        n = sc.plane_normal
        view = [a - b for a, b in zip(sc.cam_at, sc.cam_pos)]
        back = [b * dot(view, n) - a for a, b in zip(view, n)]  # -view, along the plane
        if dot(back, back) < 1e-12 * dot(view, view):  # looking straight at the plane
            back = [n[1], -n[0], 0.0] if abs(n[2]) < 0.9 else [0.0, n[2], -n[1]]
        far = 100.0 * (math.dist(sc.cam_pos, sc.light_pos) + sc.sphere_r) / math.sqrt(
            dot(back, back))
        height = dot([a - b for a, b in zip(sc.light_pos, sc.plane_point)], n)
        centre = [lp + far * b + (2 * sc.sphere_r - height) * y  # 2 r above the plane
                  for lp, b, y in zip(sc.light_pos, back, n)]
        extra = ("sphere { %s, %r pigment { rgbf 1 } interior { ior %r } no_reflection\n"
                 "  photons { target refraction on reflection off collect off } }\n"
                 % (p(centre), sc.sphere_r, sc.ior))
    photons = ""
    if count:
        photons = ("photons { count %d gather 20, %d radius %r jitter 1.0 max_trace_level %d "
                   "adc_bailout %r }" % (count, k, sc.radius, sc.max_bounces, sc.min_contribution))
    # Square images: POV-Ray's `angle` (horizontal) is Prism's vertical fov.  `look_at` last: it
    # turns the camera (right, up, direction) towards the point, keeping `sky` up.
    s = """#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level %d adc_bailout %r %s }
camera { perspective location %s right x up y angle %r sky %s look_at %s }
light_source { %s color rgb %s fade_distance %r fade_power 2
  photons { refraction on reflection on } }
plane { %s, %r pigment { rgb %s } finish { diffuse 1 ambient 0 specular 0 phong 0 } }
""" % (sc.max_depth + 1, sc.min_contribution, photons, p(sc.cam_pos), sc.fov, p(sc.cam_up),
       p(sc.cam_at), p(sc.light_pos), c(colour), FADE_D, p(sc.plane_normal),
       sum(a * b for a, b in zip(sc.plane_point, sc.plane_normal)), c(sc.floor_albedo))
    if sphere and opaque:
        s += ("sphere { %s, %r pigment { rgb %s } finish { diffuse 1 ambient 0 specular 0 "
              "phong 0 } }\n" % (p(sc.sphere_c), sc.sphere_r, c(sc.floor_albedo)))
    elif sphere:
        # interior_texture: no highlight on the inside.  The glass collects no photons (with
        # `collect on` POV-Ray stores photons on the glass too and, for the same count, shot a
        # third as many), so shadow rays from its inner surfaces pass through its filter pigment
        # and would add highlights inside the ball that Prism, whose glass blocks every shadow
        # ray, does not draw (measured: the top view's highlight 1.5 times Prism's).
        s += """sphere { %s, %r
  pigment { rgbf <1, 1, 1, 1> }
  finish { %s }
  interior_texture { pigment { rgbf <1, 1, 1, 1> } finish { %s } }
  interior { ior %r }
  photons { %s refraction on reflection on collect off }
}
""" % (p(sc.sphere_c), sc.sphere_r, glass_finish(phong), glass_finish(0),
       sc.ior if ior is None else ior, target)
    with open(path, "w") as f:
        f.write(s + extra)


# ------------------------------------------------------------------ running

def run_timed(cmd, log_path, timeout):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    with open(log_path, "w") as log:
        try:
            rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if rc != 0:
        die("%s failed (%s); log: %s" % (" ".join(cmd), rc, log_path))
    return wall, cpu


def prism_cmd(a, yaml, out, size, extra):
    return [a.prism, "render", yaml, "-t", str(a.threads), "-W", str(size), "-H", str(size),
            "--spp", "1", "-q", "-o", out, "--overwrite"] + extra


def pov_cmd(a, pov, out, size):
    return [a.povray, "-D", "-A", "-V", "+WT%d" % a.threads, "+W%d" % size, "+H%d" % size,
            "+FE", "+O" + out, "+I" + pov]


def pov_photons_shot(log_path):
    with open(log_path, errors="replace") as f:
        for line in f:
            if "Number of photons shot" in line:
                return int(line.split(":")[1])
    return 0


# ------------------------------------------------------------------ calibration

def render_pair(a, sc, work, name, size, prism_flags=(), prism_kw=None, pov_kw=None):
    """Renders variant `name` of the scene with both renderers; (Prism's, POV-Ray's) pixels."""
    base = os.path.join(work, name)
    prism_yaml(sc, base + ".yaml", size, **(prism_kw or {}))
    pov_scene(sc, base + ".pov", **(pov_kw or {}))
    run_timed(prism_cmd(a, base + ".yaml", base + "-prism.exr", size, list(prism_flags)),
              base + "-prism.log", a.timeout)
    run_timed(pov_cmd(a, base + ".pov", base + "-pov.exr", size), base + "-pov.log", a.timeout)
    return read_image(base + "-prism.exr")[2], read_image(base + "-pov.exr")[2]


def differ_share(a, b):
    """The share of pixels that differ by more than 1 % (and 1e-3 W/(m^2 sr) a channel)."""
    n = len(a) // 3
    return sum(1 for i in range(n)
               if abs(sum(a[3 * i:3 * i + 3]) - sum(b[3 * i:3 * i + 3]))
               > 0.01 * max(sum(a[3 * i:3 * i + 3]), sum(b[3 * i:3 * i + 3])) + 3e-3) / n


def calibrate(a, sc, work):
    """Direct light on the plain floor, the picture with an opaque ball, the glass ball's direct
    light, and photon units through an index-1 ball.  Returns (results, [(check, passed)])."""
    size = 256
    res = {}
    pr, pv = render_pair(a, sc, work, "plane", size, prism_kw={"sphere": False},
                         pov_kw={"sphere": False})
    ratios = sorted(y / x for x, y in zip(pr, pv) if x > 1e-3)
    res["plane_ratio_median"] = ratios[len(ratios) // 2]
    res["plane_ratio_min"], res["plane_ratio_max"] = ratios[0], ratios[-1]
    # An opaque ball of the floor's colour: same camera, same ball, same shadow, pixel by pixel
    # (both trace one ray through each pixel's centre).  A mirrored or shifted view fails here
    # even where the plain floor cannot show it.
    po, vo = render_pair(a, sc, work, "opaque", size, prism_flags=["--caustics", "none"],
                         prism_kw={"opaque": True}, pov_kw={"opaque": True})
    res["opaque_differ"] = differ_share(po, vo)
    # The glass ball, direct light only (Prism: caustics off): the same Fresnel split, highlight
    # and shadow, seen directly and through the ball.
    pg, vg = render_pair(a, sc, work, "glass-direct", size, prism_flags=["--caustics", "none"],
                         pov_kw={"direct_only": True})
    res["glass_differ"] = differ_share(pg, vg)
    # Index-1 ball, no Fresnel, no highlight: the floor must look like the plain floor.
    n = 1000000
    p1, v1 = render_pair(a, sc, work, "ior1", size,
                         prism_flags=["--photons", str(n), "--gather", str(gather_k(n))],
                         prism_kw={"ior": 1.0, "fresnel": False, "specular": 0.0},
                         pov_kw={"ior": 1.0, "fresnel": False, "specular": 0.0, "count": n,
                                 "k": gather_k(n)})
    # the shadow region: floor pixels that the ball hides from the light (Prism, no caustics)
    run_timed(prism_cmd(a, os.path.join(work, "ior1.yaml"), os.path.join(work, "ior1-shadow.exr"),
                        size, ["--caustics", "none"]), os.path.join(work, "ior1-shadow.log"),
              a.timeout)
    _, _, sh = read_image(os.path.join(work, "ior1-shadow.exr"))
    # shadowed floor seen directly or through the (invisible) ball: direct light gone
    shadow = [i for i in range(size * size) if sh[3 * i] < 0.2 * pr[3 * i] and pr[3 * i] > 0.05]
    res["shadow_pixels"] = len(shadow)
    if not shadow:
        die("calibration: the ball casts no shadow in view; the index-1 check needs one")
    plain = region_mean(pr, shadow)
    res["ior1_prism_ratio"] = region_mean(p1, shadow) / plain
    res["ior1_pov_ratio"] = region_mean(v1, shadow) / plain
    checks = [
        # half-float EXR rounds to 2^-11 relative: POV-Ray's pixels within 0.05 % of Prism's
        ("plain floor ratio within 0.2 %",
         abs(res["plane_ratio_min"] - 1) < 0.002 and abs(res["plane_ratio_max"] - 1) < 0.002),
        # the silhouette and the shadow's edge may flip a pixel or two where a ray grazes the ball
        ("opaque ball: under 0.2 % of pixels differ", res["opaque_differ"] < 0.002),
        ("glass ball, direct light: under 0.2 % of pixels differ", res["glass_differ"] < 0.002),
        # k-NN blur at the shadow's edge makes both about 1 % low (docs/caustics.md)
        ("index-1 ball: photons give the plain floor within 3 %",
         abs(res["ior1_prism_ratio"] - 1) < 0.03 and abs(res["ior1_pov_ratio"] - 1) < 0.03),
    ]
    return res, checks


# ------------------------------------------------------------------ references

def prism_reference(a, yaml, key):
    """The default mode's scorer: Prism's long progressive run as the reference (cached)."""
    ref = os.path.join(a.ref_dir, "ref-%s-p%d-s%d.exr" % (key, a.ref_passes, a.ref_seed))
    if not os.path.exists(ref):
        print("rendering the reference: %d progressive passes ..." % a.ref_passes)
        sys.stdout.flush()
        w, c = run_timed(prism_cmd(a, yaml, ref + ".part.exr", a.size,
                                   ["--progressive", "--passes", str(a.ref_passes),
                                    "--seed", str(a.ref_seed)]), ref + ".log", a.timeout)
        os.replace(ref + ".part.exr", ref)
        print("  reference took %.1f s wall, %.1f s CPU" % (w, c))
    direct = os.path.join(a.ref_dir, "direct-%s.exr" % key)
    if not os.path.exists(direct):
        run_timed(prism_cmd(a, yaml, direct, a.size, ["--caustics", "none"]),
                  direct + ".log", a.timeout)
    _, _, rv = read_image(ref)
    _, _, dv = read_image(direct)
    npx = a.size * a.size
    mask = [i for i in range(npx)
            if sum(rv[3 * i:3 * i + 3]) - sum(dv[3 * i:3 * i + 3]) > 3 * a.mask_threshold]
    if not mask:
        die("empty caustic mask")
    ref_caustic_mean = region_mean(rv, mask)
    halo = [i for i in mask if max(rv[3 * i:3 * i + 3]) < a.focus_threshold]
    peak = max(range(npx), key=lambda i: rv[3 * i] + rv[3 * i + 1] + rv[3 * i + 2])
    print("caustic mask: %d pixels (%.2f %%), reference mean there %.4f W/(m^2 sr); "
          "without the focus (reference < %g): %d pixels; reference peak %.1f at (%d, %d)"
          % (len(mask), 100.0 * len(mask) / npx, ref_caustic_mean, a.focus_threshold,
             len(halo), rv[3 * peak], peak % a.size, peak // a.size))

    def errors(image, png=None):  # (png: the exact mode's; the images are written by main)
        v = read_image(image)[2]
        return {"rmse": rmse(v, rv), "caustic_rmse": rmse(v, rv, mask),
                "halo_rmse": rmse(v, rv, halo),
                "caustic_brightness": region_mean(v, mask) / ref_caustic_mean,
                "peak_ratio": v[3 * peak] / rv[3 * peak]}

    if a.ref_check_passes:
        chk = os.path.join(a.ref_dir, "ref-%s-p%d-s%d.exr"
                           % (key, a.ref_check_passes, a.ref_seed + 1))
        if not os.path.exists(chk):
            run_timed(prism_cmd(a, yaml, chk + ".part.exr", a.size,
                                ["--progressive", "--passes", str(a.ref_check_passes),
                                 "--seed", str(a.ref_seed + 1)]), chk + ".log", a.timeout)
            os.replace(chk + ".part.exr", chk)
        e = errors(chk)
        print("reference check: %d passes (seed %d) against the reference: RMSE %.4f, caustic "
              "%.4f, without focus %.4f, brightness %.4f, peak %.3f"
              % (a.ref_check_passes, a.ref_seed + 1, e["rmse"], e["caustic_rmse"],
                 e["halo_rmse"], e["caustic_brightness"], e["peak_ratio"]))
    write_png(ref, os.path.join(a.out, "reference.png"))
    return SimpleNamespace(
        score=errors, name="Prism reference (%d passes)" % a.ref_passes,
        columns=[("rmse", "RMSE", "%8.4f"), ("caustic_rmse", "caust.RMSE", "%10.4f"),
                 ("halo_rmse", "halo RMSE", "%9.4f"), ("caustic_brightness", "bright.", "%8.4f"),
                 ("peak_ratio", "peak", "%6.3f")],
        errors=[("rmse", "whole-image RMSE, W/(m^2 sr)"),
                ("caustic_rmse", "caustic-region RMSE, W/(m^2 sr)"),
                ("halo_rmse", "caustic-region RMSE without the focus, W/(m^2 sr)")])


def exact_reference(a, sc, yaml, key):
    """The --exact-reference mode's scorer: the exact caustic (cached), every image's caustic
    taken against Prism's direct light with the ball blocking it and casting nothing."""
    ref = os.path.join(a.ref_dir, "exact-%s-r%s-s%s-b%s.exr"
                       % (key, a.exact_rays, a.exact_samples, a.exact_bins))
    if not os.path.exists(ref):
        print("building the exact reference (%s light rays) ..." % a.exact_rays)
        sys.stdout.flush()
    t = exact.build_reference(a.exact_reference, yaml, ref, a.exact_rays, a.exact_samples,
                              a.exact_bins, a.threads)
    if t is not None:
        print("  exact reference took %.1f s wall" % t)
    direct_yaml = os.path.join(a.out, "direct-scene.yaml")
    exact.write_direct_scene(yaml, direct_yaml)
    direct = os.path.join(a.out, "direct.exr")
    run_timed(prism_cmd(a, direct_yaml, direct, a.size, []), direct + ".log", a.timeout)

    def score(image, png=None):
        return exact.score(a.exact_reference, ref, image, direct, yaml, png)

    # POV-Ray's direct light under the same shadow, against Prism's: added to the exact caustic
    # and scored, the difference alone gives this relative RMSE, a floor under POV-Ray's scores
    # (it includes the half-float rounding of POV-Ray's EXR).
    pov = os.path.join(a.out, "pov-direct")
    pov_scene(sc, pov + ".pov", direct_only=True)
    run_timed(pov_cmd(a, pov + ".pov", pov + ".exr", a.size), pov + ".log", a.timeout)
    exact.run([a.exact_reference, "--reference", ref, "--direct", pov + ".exr",
               "--compose", pov + "-plus-ref.exr"])
    s = score(pov + "-plus-ref.exr")
    print("exact reference: caustic region %d px (regular part %d); peak %.4g W/(m^2 sr)"
          % (s["region_px"], s["regular_px"], s["peak_ref"]))
    print("POV-Ray's direct light - Prism's, as a caustic error: rel. RMSE %.5f, regular part "
          "%.5f, flux ratio %.5f (the floor under POV-Ray's scores)"
          % (s["rel_rmse"], s["rel_rmse_regular"], s["flux_ratio"]))
    if a.exact_check_rays:
        # A reference from fewer light rays (another ray grid), scored against the main one: an
        # upper bound on the main reference's own error, which every score includes.
        chk = os.path.join(a.ref_dir, "exact-%s-r%s-s%s-b%s.exr"
                           % (key, a.exact_check_rays, a.exact_samples, a.exact_bins))
        exact.build_reference(a.exact_reference, yaml, chk, a.exact_check_rays, a.exact_samples,
                              a.exact_bins, a.threads)
        full = os.path.join(a.out, "reference-check.exr")
        exact.run([a.exact_reference, "--reference", chk, "--direct", direct, "--compose", full])
        s = score(full)
        print("reference check: %s light rays against %s: rel. RMSE %.5f, regular part %.5f, "
              "flux ratio %.5f (the main reference's own error is below this: about half, if "
              "its noise falls as 1/sqrt(rays))" % (a.exact_check_rays, a.exact_rays,
                                                   s["rel_rmse"], s["rel_rmse_regular"],
                                                   s["flux_ratio"]))
    return SimpleNamespace(
        score=score, name="exact reference",
        columns=[("rel_rmse", "rel.RMSE", "%8.4f"), ("rel_rmse_regular", "regular", "%8.4f"),
                 ("flux_ratio", "flux", "%7.4f"), ("focus9_ratio", "focus9", "%7.3f"),
                 ("peak_ratio", "peak", "%6.3f")],
        errors=[("rel_rmse", "caustic region: relative RMSE"),
                ("rel_rmse_regular", "regular part: relative RMSE")])


# ------------------------------------------------------------------ main

def scene_key(sc, yaml):
    """Cache key: the scene's name and a hash of Prism's copy (size included), so a changed scene
    never reuses a stale reference."""
    with open(yaml, "rb") as f:
        text = f.read().split(b"\n", 1)[1]  # not the comment naming the source
    name = os.path.splitext(os.path.basename(sc.path))[0]
    return "%s-%s" % (name, hashlib.sha1(text).hexdigest()[:10])


def main():
    # --help: the docstring up to "Units." (what is measured, against which reference)
    ap = argparse.ArgumentParser(description=__doc__[:__doc__.index("\nUnits.")],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="The docstring (this file's head) has every detail.")
    ap.add_argument("--prism", default=os.path.join(REPO, "build-bench", "prism"))
    ap.add_argument("--povray", default="/usr/bin/povray")
    ap.add_argument("--scene", default=SCENE,
                    help="glass ball over a plane, one point light (default %(default)s)")
    ap.add_argument("--ref-dir", required=True, help="folder caching the reference renders")
    ap.add_argument("--out", default="/tmp/povray-caustics", help="work folder (images, logs)")
    ap.add_argument("--size", type=int, default=1024, help="image width = height")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--exact-reference", metavar="TOOL", default=None,
                    help="score against the exact caustic built by TOOL "
                         "(build/tests/prism_sphere_caustic_reference): relative RMSE over the "
                         "caustic region and its regular part, flux ratio; not Prism's long run")
    ap.add_argument("--exact-rays", type=int, default=exact.REF_RAYS,
                    help="light rays of the exact reference")
    ap.add_argument("--exact-check-rays", type=int, default=0,
                    help="also build (cached) a reference from this many light rays and report "
                         "its error against the main one: the reference's own error floor "
                         "(0: not)")
    ap.add_argument("--exact-samples", type=int, default=exact.REF_SAMPLES,
                    help="eye samples per pixel side of the exact reference")
    ap.add_argument("--exact-bins", type=int, default=exact.REF_BINS,
                    help="plane bins per pixel side of the exact reference")
    ap.add_argument("--ref-passes", type=int, default=256, help="Prism reference (default mode)")
    ap.add_argument("--ref-seed", type=int, default=987654321)
    ap.add_argument("--photons", default="100000,300000,1000000,3000000",
                    help="budgets N for Prism classic and POV-Ray (comma list)")
    ap.add_argument("--prism-photons", default=None,
                    help="budgets N for Prism classic, if not --photons's (comma list)")
    ap.add_argument("--prism-gather", choices=("rule", "scene"), default="rule",
                    help="Prism classic's k: POV-Ray's rule clamp(sqrt(N)/4, 50, 1000), or the "
                         "scene's gather")
    ap.add_argument("--passes", default="1,2,4,8,16,32", help="Prism progressive budgets (passes)")
    ap.add_argument("--mask-threshold", type=float, default=0.05)
    ap.add_argument("--focus-threshold", type=float, default=10.0,
                    help="third error measure: the caustic mask without pixels where the "
                         "reference exceeds this (the focal spot), W/(m^2 sr)")
    ap.add_argument("--ref-check-passes", type=int, default=64,
                    help="also render (cached) a smaller reference with another seed and report "
                         "its error against the main one: the reference's own error floor")
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--csv", default=None)
    ap.add_argument("--chart", default=None, help="PNG chart (needs gnuplot)")
    ap.add_argument("--skip-calibration", action="store_true")
    a = ap.parse_args()

    sc = load_scene(a.scene)
    tools = [a.prism, a.povray, shutil.which("oiiotool")] + (
        [a.exact_reference] if a.exact_reference else [])
    for tool in tools:
        if not tool or not os.path.exists(tool):
            die("missing %s" % tool)
    os.makedirs(a.out, exist_ok=True)
    os.makedirs(a.ref_dir, exist_ok=True)
    a.out = work = os.path.abspath(a.out)
    prism_copy = os.path.join(work, "prism-under-test")
    shutil.copy2(a.prism, prism_copy)
    a.prism = prism_copy
    budgets_n = [int(x) for x in a.photons.split(",") if x]
    budgets_prism = [int(x) for x in (a.prism_photons or a.photons).split(",") if x]
    budgets_p = [int(x) for x in a.passes.split(",") if x]
    print("scene %s: camera %s -> %s, ball r %g at %s, n %g; light %s; photons %d per pass, k %d"
          % (os.path.relpath(a.scene), sc.cam_pos, sc.cam_at, sc.sphere_r, sc.sphere_c, sc.ior,
             sc.light_pos, sc.photons, sc.gather))

    if not a.skip_calibration:
        cal, checks = calibrate(a, sc, work)
        print("calibration (256x256):")
        print("  plain floor, POV-Ray / Prism per pixel: median %.5f, min %.5f, max %.5f"
              % (cal["plane_ratio_median"], cal["plane_ratio_min"], cal["plane_ratio_max"]))
        print("  pixels differing by more than 1 %%: opaque ball %.3f %%, glass ball's direct "
              "light %.3f %%" % (100 * cal["opaque_differ"], 100 * cal["glass_differ"]))
        print("  index-1 ball, floor in its shadow lit by photons only, / plain floor "
              "(%d px): Prism %.4f, POV-Ray %.4f"
              % (cal["shadow_pixels"], cal["ior1_prism_ratio"], cal["ior1_pov_ratio"]))
        for what, ok in checks:
            print("  %-55s %s" % (what, "ok" if ok else "FAILED"))
        if not all(ok for _, ok in checks):
            die("calibration failed: POV-Ray's translation does not render the same scene "
                "(images in %s)" % work)
        sys.stdout.flush()

    yaml = os.path.join(work, "scene.yaml")
    prism_yaml(sc, yaml, a.size)
    key = scene_key(sc, yaml)
    scorer = (exact_reference(a, sc, yaml, key) if a.exact_reference
              else prism_reference(a, yaml, key))
    sys.stdout.flush()

    # The runs: (method, budget, k, command maker)
    jobs = []
    for n in budgets_prism:
        k = gather_k(n) if a.prism_gather == "rule" else sc.gather
        jobs.append(("prism-classic", n, k, lambda out, n=n, k=k: prism_cmd(
            a, yaml, out, a.size, ["--photons", str(n), "--gather", str(k)])))
    for n in budgets_n:
        pov = os.path.join(work, "scene-%d.pov" % n)
        pov_scene(sc, pov, count=n, k=gather_k(n))
        jobs.append(("povray", n, gather_k(n), lambda out, pov=pov: pov_cmd(a, pov, out, a.size)))
    for p in budgets_p:
        jobs.append(("prism-progressive", p, "", lambda out, p=p: prism_cmd(
            a, yaml, out, a.size, ["--progressive", "--passes", str(p)])))

    times = {(m, b): [] for m, b, _, _ in jobs}
    cpus = {(m, b): [] for m, b, _, _ in jobs}
    for r in range(a.repeats):
        order = jobs[r % len(jobs):] + jobs[:r % len(jobs)]
        if r % 2:
            order.reverse()
        for m, b, _, make in order:
            out = os.path.join(work, "%s-%d.exr" % (m, b))
            log = os.path.join(work, "%s-%d.log" % (m, b))
            wall, cpu = run_timed(make(out), log, a.timeout)
            times[(m, b)].append(wall)
            cpus[(m, b)].append(cpu)
            print("  round %d  %-18s %9d  %7.2f s wall  %7.2f s CPU" % (r + 1, m, b, wall, cpu))
            sys.stdout.flush()

    rows = []
    methods = ("prism-classic", "prism-progressive", "povray")
    largest = {m: max((b for mm, b, _, _ in jobs if mm == m), default=None) for m in methods}
    for m, b, k, _ in jobs:
        out = os.path.join(work, "%s-%d.exr" % (m, b))
        shot = pov_photons_shot(os.path.join(work, "%s-%d.log" % (m, b))) if m == "povray" else ""
        rows.append({
            "method": m, "budget": b, "gather_k": k, "povray_photons_shot": shot,
            "wall_s": statistics.median(times[(m, b)]),
            "wall_min": min(times[(m, b)]), "wall_max": max(times[(m, b)]),
            "cpu_s": statistics.median(cpus[(m, b)]),
        })
        # each method's largest budget is also kept as PNGs to look at
        if b == largest[m]:
            write_png(out, os.path.join(work, "best-%s.png" % m))
        scores = scorer.score(out, os.path.join(work, "best-%s-caustic" % m)
                              if b == largest[m] else None)
        rows[-1].update({key: scores[key] for key, _, _ in scorer.columns})

    print("errors against the %s" % scorer.name)
    hdr = "%-18s %9s %5s %9s %8s %15s %8s" % ("method", "budget", "k", "pov shot", "wall s",
                                             "(min..max)", "CPU s")
    print(hdr + "".join(" %*s" % (len(fmt % 0), head) for _, head, fmt in scorer.columns))
    for row in rows:
        print("%-18s %9d %5s %9s %8.2f %15s %8.2f" % (
            row["method"], row["budget"], row["gather_k"], row["povray_photons_shot"],
            row["wall_s"], "%.2f..%.2f" % (row["wall_min"], row["wall_max"]), row["cpu_s"])
            + "".join(" " + fmt % row[key] for key, _, fmt in scorer.columns))

    # Prism's time to reach POV-Ray's best error, log-log interpolated.
    def time_for(method, target, key):
        pts = sorted((r["wall_s"], r[key]) for r in rows if r["method"] == method)
        for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
            if (e0 - target) * (e1 - target) <= 0 and e0 != e1:
                f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
                t = math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
                return "%.2f s" % t, t
        if not pts:
            return "(no runs)", None
        if pts[0][1] <= target:  # better already at its cheapest budget: an upper bound
            return "at most %.2f s (its cheapest run: %.4f)" % pts[0], pts[0][0]
        t, e = min(pts, key=lambda p: p[1])
        return "more than its budgets give (its best: %.4f at %.2f s)" % (e, t), None
    if budgets_n:
        for key, _ in scorer.errors:
            best = min((r for r in rows if r["method"] == "povray"), key=lambda r: r[key])
            for m in ("prism-classic", "prism-progressive"):
                text, t = time_for(m, best[key], key)
                print("%s: POV-Ray's best %.4f takes it %.2f s; %s takes %s%s"
                      % (key, best[key], best["wall_s"], m, text,
                         " (ratio %.2f)" % (t / best["wall_s"]) if t else ""))

    if a.csv:
        with open(a.csv, "w", newline="") as f:
            wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            wr.writeheader()
            for row in rows:
                wr.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in row.items()})
        print("wrote", a.csv)
    print("PNGs in", work)

    if a.chart:
        if not shutil.which("gnuplot"):
            print("gnuplot not found (apt-get install -y gnuplot-nox): no chart")
            return
        dat = os.path.join(work, "chart.dat")
        with open(dat, "w") as f:
            for m in methods:
                f.write("# %s: wall_s %s\n" % (m, " ".join(k for k, _ in scorer.errors)))
                for row in sorted((r for r in rows if r["method"] == m), key=lambda r: r["wall_s"]):
                    f.write("%g %s\n" % (row["wall_s"], " ".join("%g" % row[k]
                                                                 for k, _ in scorer.errors)))
                f.write("\n\n")
        titles = ["Prism classic (--photons N)", "Prism progressive (--passes P)",
                  "POV-Ray 3.7 (photons count N)"]
        plots = []
        for col, (_, name) in enumerate(scorer.errors, 2):
            series = ", ".join(
                "'%s' index %d using 1:%d with linespoints lw 2 pt %d title '%s'"
                % (dat, i, col, (7, 5, 9)[i], titles[i]) for i in range(3))
            plots.append("set title '%s'\nset ylabel '%s'\nplot %s\n" % (name, name, series))
        script = """set terminal pngcairo size %d,560 font 'Sans,11'
set output '%s'
set multiplot layout 1,%d title '%s, %dx%d, %d threads: error against the %s vs wall time (median of %d)'
set logscale xy
set grid
set key top right
set xlabel 'wall time, s'
%s
unset multiplot
""" % (600 * len(plots), os.path.abspath(a.chart), len(plots),
       os.path.splitext(os.path.basename(sc.path))[0], a.size, a.size, a.threads, scorer.name,
       a.repeats, "".join(plots))
        gp = os.path.join(work, "chart.gp")
        with open(gp, "w") as f:
            f.write(script)
        subprocess.run(["gnuplot", gp], check=True)
        print("wrote", a.chart)


if __name__ == "__main__":
    main()
