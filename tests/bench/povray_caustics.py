#!/usr/bin/env python3
"""Time against error of Prism's photon-mapped caustics and POV-Ray 3.7's photons.

Scene: scenes/caustic-glass-sphere.yaml (a glass ball, n = 1.5, above a white floor under one
point light of 150 W/sr).  The script writes POV-Ray's translation of it, checks that the two
renderers agree on direct light, renders (once, cached) Prism's converged reference, then times
both renderers over a range of photon budgets and measures each image's error against the
reference.

Units.  POV-Ray's point light with `fade_distance D fade_power 2` falls off as
2 / (1 + (d/D)^2) = 2 D^2 / (D^2 + d^2), and its diffuse term has no 1/pi; so the light of
I W/sr becomes `color rgb I / (2 pi D^2)` with D = 0.001 (relative error D^2/d^2 < 1e-7 here),
and the floor `pigment { rgb 0.75 } finish { diffuse 1 ambient 0 }`, `assumed_gamma 1.0`.  A
pixel then holds rho/pi * E in W/(m^2 sr), as in Prism.  The script verifies this on the plain
floor (no sphere): the per-pixel ratio POV-Ray / Prism is printed (median, min, max), and it
checks POV-Ray's photon units with an index-1 "glass" ball (light passes straight, the photons
under it must give the same floor radiance as the plain floor).  Glass: `pigment { rgbf 1 }`,
`interior { ior 1.5 }`, `reflection { 0, 1 fresnel on } conserve_energy` (reflected weight F,
refracted 1 - F, as Prism's Fresnel split), Phong highlight `phong 0.8 pi phong_size 200`
(Prism's specular 0.8 times the light's radiant intensity; POV-Ray's light colour carries the
1/pi of the diffuse calibration, so phong is 0.8 pi).  No ambient, no radiosity.  Depth: Prism
max_depth 10 bounces after the primary ray = POV-Ray max_trace_level 11; photons follow up to 16
specular bounces in both; adc_bailout 0.001 = Prism's min_contribution.  One sample per pixel
through the pixel centre in both (Prism --spp 1, POV-Ray -A).  With photons on, POV-Ray's
shadow rays are blocked by the refracting photon target (without photons they would pass
through the filter pigment); the index-1 check confirms light is neither lost nor doubled.

Budgets.  Prism classic: --photons N with k = gather(N) nearest photons.  POV-Ray: photons
{ count N gather 20, gather(N) radius 0.1 jitter 1 } (count asks for about N photons; the number it really
shot is read from its log and reported).  Both use the same rule gather(N) = clamp(sqrt(N)/4,
50, 1000): a fixed k does not converge for POV-Ray (docs: /work/shared/notes/peers.md), and the
same rule is given to Prism.  POV-Ray's gather radius is set to Prism's largest k-NN radius
(0.1, a tenth of the ball's radius), so both estimate with the k nearest photons within 0.1: its
automatic radius failed at some budgets (scattered single photons on a black shadow).  Prism progressive: --progressive --passes P (the scene's 500 k
photons per pass).  The reference is Prism progressive with many passes and a different seed
(photon streams are keyed by seed, so the benchmark runs are independent of it).

Error: RMSE over all pixels and channels of the linear radiance against the reference, and the
same over a caustic mask: the pixels where the reference exceeds Prism's direct-light-only image
(--caustics none) by more than --mask-threshold W/(m^2 sr); and over that mask without the focal
spot (reference above --focus-threshold): the point light's image through the ball is nearly
singular, a few pixels hold radiance in the hundreds, every estimator blurs them and they
dominate the first two measures (the reference itself is not converged there: the check against
a --ref-check-passes reference shows it).  Also printed: the caustic region's mean brightness
and the value at the reference's brightest pixel, each relative to the reference.  Time: wall seconds of the whole
process (median of --repeats runs) and CPU seconds (user + system of the child, median).  Runs
are interleaved (every round runs each budget of each renderer once, the order rotating) since
the machine is shared and noisy.  Both renderers use --threads threads.

Images are read back with OpenImageIO's oiiotool (converted to uncompressed float TIFF, parsed
here); POV-Ray writes half-float OpenEXR (+FE), Prism float OpenEXR.  The chart is drawn with
gnuplot (Debian gnuplot-nox) if it is installed; the CSV and table are written either way.

Python 3, standard library only, no numpy (plus the command-line tools povray, oiiotool from
openimageio-tools, and gnuplot from gnuplot-nox).

Example (what made docs/caustics-povray.png):
  tests/bench/povray_caustics.py --ref-dir /tmp/prism-caustic-ref --out /tmp/povray-caustics3 \\
      --size 1024 --repeats 3 --ref-passes 256 --photons 100000,300000,1000000,3000000 \\
      --passes 1,2,4,8,16,32 --chart docs/caustics-povray.png --csv docs/caustics-povray.csv
(about 15 minutes on a 2-core VM, 221 s of it the reference, which is cached in --ref-dir).
A quick check: --size 128 --repeats 1 --ref-passes 8 --ref-check-passes 4 --photons 100000
--passes 1,3.
"""
import argparse
import csv
import math
import os
import resource
import shutil
import statistics
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCENE = os.path.join(REPO, "scenes", "caustic-glass-sphere.yaml")

# The scene, as in scenes/caustic-glass-sphere.yaml (checked against the file at start-up).
LIGHT_POS = (0.0, 8.0, 0.0)
LIGHT_I = 150.0
FLOOR_ALBEDO = 0.75
SPHERE_C = (0.0, 2.0, 0.0)
SPHERE_R = 1.0
IOR = 1.5
SPECULAR, SHININESS = 0.8, 200
CAM_POS, CAM_AT, FOV = (0.0, 4.5, 7.5), (0.0, 1.2, 0.0), 40.0
MAX_DEPTH = 10
FADE_D = 0.001
# POV-Ray's gather radius: Prism's default largest k-NN radius (a tenth of the largest caster's
# bounding radius).  POV-Ray's automatic radius is unreliable here: with count 300000 it came out
# so small that the caustic rendered as scattered single photons on a black shadow.
POV_RADIUS = 0.1 * SPHERE_R


def die(msg):
    sys.exit("povray_caustics: error: " + msg)


def gather_k(n):
    return int(min(1000, max(50, round(math.sqrt(n) / 4))))


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

def prism_yaml(path, sphere=True, ior=IOR, fresnel=True, specular=SPECULAR):
    objs = "  - plane: {point: [0, 0, 0], normal: [0, 1, 0], material: floor}\n"
    if sphere:
        objs = ("  - sphere: {center: [%g, %g, %g], radius: %g, material: glass}\n"
                % (SPHERE_C + (SPHERE_R,))) + objs
    with open(path, "w") as f:
        f.write("""camera:
  position: [%g, %g, %g]
  look_at: [%g, %g, %g]
  fov: %g
render:
  samples: 1
  max_depth: %d
caustics:
  method: photon_map
  photons: 500000
  gather: 100
materials:
  - name: floor
    diffuse: %g
  - name: glass
    diffuse: 0
    specular: %g
    shininess: %g
    transmittance: 1
    ior: %g
    fresnel: %s
lights:
  - position: [%g, %g, %g]
    intensity: %g
    attenuation: [0, 0, 1]
objects:
%s""" % (CAM_POS + CAM_AT + (FOV, MAX_DEPTH, FLOOR_ALBEDO, specular, SHININESS, ior,
          "true" if fresnel else "false") + LIGHT_POS + (LIGHT_I, objs)))


def pov_scene(path, sphere=True, ior=IOR, fresnel=True, phong=SPECULAR * math.pi,
              count=None, k=100):
    """POV-Ray 3.7 translation.  POV-Ray is left-handed: Prism's (x, y, z) is (x, y, -z)."""
    colour = LIGHT_I / (2.0 * math.pi * FADE_D ** 2)
    photons = ""
    if count:
        photons = ("photons { count %d gather 20, %d radius %r jitter 1.0 max_trace_level 16 "
                   "adc_bailout 0.001 }" % (count, k, POV_RADIUS))
    p = lambda v: "<%r, %r, %r>" % (v[0], v[1], -v[2])  # noqa: E731
    s = """#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level %d adc_bailout 0.001 %s }
camera { perspective location %s look_at %s right x up y angle %r }
light_source { %s color rgb %r fade_distance %r fade_power 2
  photons { refraction on reflection on } }
plane { y, 0 pigment { rgb %r } finish { diffuse 1 ambient 0 specular 0 phong 0 } }
""" % (MAX_DEPTH + 1, photons, p(CAM_POS), p(CAM_AT), FOV, p(LIGHT_POS), colour, FADE_D,
       FLOOR_ALBEDO)
    if sphere:
        s += """sphere { %s, %r
  pigment { rgbf <1, 1, 1, 1> }
  finish { diffuse 0 ambient 0 specular 0 phong %r phong_size %r %s conserve_energy }
  interior { ior %r }
  photons { target refraction on reflection on collect off }
}
""" % (p(SPHERE_C), SPHERE_R, phong, SHININESS,
       "reflection { 0, 1 fresnel on }" if fresnel else "", ior)
    with open(path, "w") as f:
        f.write(s)


def check_scene_file():
    """Stop if the seed scene no longer says what the translation assumes."""
    with open(SCENE) as f:
        text = f.read()
    for needle in ["position: [0, 4.5, 7.5]", "look_at: [0, 1.2, 0]", "fov: 40",
                   "max_depth: 10", "diffuse: 0.75", "specular: 0.8", "shininess: 200",
                   "transmittance: 1", "ior: 1.5", "position: [0, 8, 0]", "intensity: 150",
                   "attenuation: [0, 0, 1]", "center: [0, 2, 0], radius: 1",
                   "photons: 500000"]:
        if needle not in text:
            die("%s changed (no %r): update the translation in this script" % (SCENE, needle))


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

def calibrate(a, work):
    """Direct light on the plain floor, and photon units through an index-1 ball."""
    size = 256
    res = {}
    prism_yaml(os.path.join(work, "plane.yaml"), sphere=False)
    pov_scene(os.path.join(work, "plane.pov"), sphere=False)
    run_timed(prism_cmd(a, os.path.join(work, "plane.yaml"), os.path.join(work, "plane-prism.exr"),
                        size, []), os.path.join(work, "plane-prism.log"), a.timeout)
    run_timed(pov_cmd(a, os.path.join(work, "plane.pov"), os.path.join(work, "plane-pov.exr"), size),
              os.path.join(work, "plane-pov.log"), a.timeout)
    _, _, pr = read_image(os.path.join(work, "plane-prism.exr"))
    _, _, pv = read_image(os.path.join(work, "plane-pov.exr"))
    ratios = sorted(y / x for x, y in zip(pr, pv) if x > 1e-3)
    res["plane_ratio_median"] = ratios[len(ratios) // 2]
    res["plane_ratio_min"], res["plane_ratio_max"] = ratios[0], ratios[-1]
    # analytic check of Prism at the image centre row bottom: not needed, Prism's own tests do it
    # Index-1 ball, no Fresnel, no highlight: the floor must look like the plain floor.
    prism_yaml(os.path.join(work, "ior1.yaml"), ior=1.0, fresnel=False, specular=0.0)
    pov_scene(os.path.join(work, "ior1.pov"), ior=1.0, fresnel=False, phong=0.0,
              count=1000000, k=gather_k(1000000))
    pov_scene(os.path.join(work, "ior1-nophotons.pov"), ior=1.0, fresnel=False, phong=0.0)
    run_timed(prism_cmd(a, os.path.join(work, "ior1.yaml"), os.path.join(work, "ior1-prism.exr"),
                        size, ["--photons", "1000000", "--gather", str(gather_k(1000000))]),
              os.path.join(work, "ior1-prism.log"), a.timeout)
    run_timed(pov_cmd(a, os.path.join(work, "ior1.pov"), os.path.join(work, "ior1-pov.exr"), size),
              os.path.join(work, "ior1-pov.log"), a.timeout)
    # the shadow region: floor pixels that the ball hides from the light (Prism, no caustics)
    run_timed(prism_cmd(a, os.path.join(work, "ior1.yaml"), os.path.join(work, "ior1-shadow.exr"),
                        size, ["--caustics", "none"]), os.path.join(work, "ior1-shadow.log"),
              a.timeout)
    _, _, sh = read_image(os.path.join(work, "ior1-shadow.exr"))
    _, _, p1 = read_image(os.path.join(work, "ior1-prism.exr"))
    _, _, v1 = read_image(os.path.join(work, "ior1-pov.exr"))
    # shadowed floor seen directly or through the (invisible) ball: direct light gone
    shadow = [i for i in range(size * size) if sh[3 * i] < 0.2 * pr[3 * i] and pr[3 * i] > 0.05]
    res["shadow_pixels"] = len(shadow)
    plain = region_mean(pr, shadow)
    res["ior1_prism_ratio"] = region_mean(p1, shadow) / plain
    res["ior1_pov_ratio"] = region_mean(v1, shadow) / plain
    return res


# ------------------------------------------------------------------ main

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--prism", default=os.path.join(REPO, "build-bench", "prism"))
    ap.add_argument("--povray", default="/usr/bin/povray")
    ap.add_argument("--ref-dir", required=True, help="folder caching the reference renders")
    ap.add_argument("--out", default="/tmp/povray-caustics", help="work folder (images, logs)")
    ap.add_argument("--size", type=int, default=1024, help="image width = height")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--ref-passes", type=int, default=256)
    ap.add_argument("--ref-seed", type=int, default=987654321)
    ap.add_argument("--photons", default="100000,300000,1000000,3000000",
                    help="budgets N for Prism classic and POV-Ray (comma list)")
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

    check_scene_file()
    for tool in (a.prism, a.povray, shutil.which("oiiotool")):
        if not tool or not os.path.exists(tool):
            die("missing %s" % tool)
    os.makedirs(a.out, exist_ok=True)
    os.makedirs(a.ref_dir, exist_ok=True)
    work = os.path.abspath(a.out)
    prism_copy = os.path.join(work, "prism-under-test")
    shutil.copy2(a.prism, prism_copy)
    a.prism = prism_copy
    budgets_n = [int(x) for x in a.photons.split(",")]
    budgets_p = [int(x) for x in a.passes.split(",")]

    if not a.skip_calibration:
        cal = calibrate(a, work)
        print("calibration (256x256):")
        print("  plain floor, POV-Ray / Prism per pixel: median %.5f, min %.5f, max %.5f"
              % (cal["plane_ratio_median"], cal["plane_ratio_min"], cal["plane_ratio_max"]))
        print("  index-1 ball, floor in its shadow lit by photons only, / plain floor "
              "(%d px): Prism %.4f, POV-Ray %.4f"
              % (cal["shadow_pixels"], cal["ior1_prism_ratio"], cal["ior1_pov_ratio"]))
        sys.stdout.flush()

    yaml = os.path.join(work, "scene.yaml")
    prism_yaml(yaml)

    # Reference (cached) and direct-only image for the mask.
    ref = os.path.join(a.ref_dir, "ref-%d-p%d-s%d.exr" % (a.size, a.ref_passes, a.ref_seed))
    if not os.path.exists(ref):
        print("rendering the reference: %d progressive passes of 500 k photons ..." % a.ref_passes)
        sys.stdout.flush()
        w, c = run_timed(prism_cmd(a, yaml, ref + ".part.exr", a.size,
                                   ["--progressive", "--passes", str(a.ref_passes),
                                    "--seed", str(a.ref_seed)]), ref + ".log", a.timeout)
        os.replace(ref + ".part.exr", ref)
        print("  reference took %.1f s wall, %.1f s CPU" % (w, c))
    direct = os.path.join(a.ref_dir, "direct-%d.exr" % a.size)
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

    def errors(v):
        return {"rmse": rmse(v, rv), "caustic_rmse": rmse(v, rv, mask),
                "halo_rmse": rmse(v, rv, halo),
                "caustic_brightness": region_mean(v, mask) / ref_caustic_mean,
                "peak_ratio": v[3 * peak] / rv[3 * peak]}

    if a.ref_check_passes:
        chk = os.path.join(a.ref_dir, "ref-%d-p%d-s%d.exr"
                           % (a.size, a.ref_check_passes, a.ref_seed + 1))
        if not os.path.exists(chk):
            run_timed(prism_cmd(a, yaml, chk + ".part.exr", a.size,
                                ["--progressive", "--passes", str(a.ref_check_passes),
                                 "--seed", str(a.ref_seed + 1)]), chk + ".log", a.timeout)
            os.replace(chk + ".part.exr", chk)
        e = errors(read_image(chk)[2])
        print("reference check: %d passes (seed %d) against the reference: RMSE %.4f, caustic "
              "%.4f, without focus %.4f, brightness %.4f, peak %.3f"
              % (a.ref_check_passes, a.ref_seed + 1, e["rmse"], e["caustic_rmse"],
                 e["halo_rmse"], e["caustic_brightness"], e["peak_ratio"]))
    sys.stdout.flush()

    # The runs: (method, budget, command maker)
    jobs = []
    for n in budgets_n:
        jobs.append(("prism-classic", n, lambda out, n=n: prism_cmd(
            a, yaml, out, a.size, ["--photons", str(n), "--gather", str(gather_k(n))])))
        pov = os.path.join(work, "scene-%d.pov" % n)
        pov_scene(pov, count=n, k=gather_k(n))
        jobs.append(("povray", n, lambda out, pov=pov: pov_cmd(a, pov, out, a.size)))
    for p in budgets_p:
        jobs.append(("prism-progressive", p, lambda out, p=p: prism_cmd(
            a, yaml, out, a.size, ["--progressive", "--passes", str(p)])))

    times = {(m, b): [] for m, b, _ in jobs}
    cpus = {(m, b): [] for m, b, _ in jobs}
    for r in range(a.repeats):
        order = jobs[r % len(jobs):] + jobs[:r % len(jobs)]
        if r % 2:
            order.reverse()
        for m, b, make in order:
            out = os.path.join(work, "%s-%d.exr" % (m, b))
            log = os.path.join(work, "%s-%d.log" % (m, b))
            wall, cpu = run_timed(make(out), log, a.timeout)
            times[(m, b)].append(wall)
            cpus[(m, b)].append(cpu)
            print("  round %d  %-18s %9d  %7.2f s wall  %7.2f s CPU" % (r + 1, m, b, wall, cpu))
            sys.stdout.flush()

    rows = []
    for m, b, _ in jobs:
        out = os.path.join(work, "%s-%d.exr" % (m, b))
        _, _, v = read_image(out)
        shot = pov_photons_shot(os.path.join(work, "%s-%d.log" % (m, b))) if m == "povray" else ""
        rows.append({
            "method": m, "budget": b,
            "gather_k": gather_k(b) if m != "prism-progressive" else "",
            "povray_photons_shot": shot,
            "wall_s": statistics.median(times[(m, b)]),
            "wall_min": min(times[(m, b)]), "wall_max": max(times[(m, b)]),
            "cpu_s": statistics.median(cpus[(m, b)]),
        })
        rows[-1].update(errors(v))

    hdr = ("%-18s %9s %5s %9s %8s %15s %8s %8s %10s %9s %8s %6s"
           % ("method", "budget", "k", "pov shot", "wall s", "(min..max)", "CPU s", "RMSE",
              "caust.RMSE", "halo RMSE", "bright.", "peak"))
    print(hdr)
    for row in rows:
        print("%-18s %9d %5s %9s %8.2f %15s %8.2f %8.4f %10.4f %9.4f %8.4f %6.3f" % (
            row["method"], row["budget"], row["gather_k"], row["povray_photons_shot"],
            row["wall_s"], "%.2f..%.2f" % (row["wall_min"], row["wall_max"]), row["cpu_s"],
            row["rmse"], row["caustic_rmse"], row["halo_rmse"], row["caustic_brightness"],
            row["peak_ratio"]))

    # Prism's time to reach POV-Ray's best caustic error, log-log interpolated.
    def time_for(method, target, key):
        pts = sorted((r["wall_s"], r[key]) for r in rows if r["method"] == method)
        for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
            if (e0 - target) * (e1 - target) <= 0 and e0 != e1:
                f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
                return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
        return None
    for key in ("caustic_rmse", "rmse", "halo_rmse"):
        best = min((r for r in rows if r["method"] == "povray"), key=lambda r: r[key])
        for m in ("prism-classic", "prism-progressive"):
            t = time_for(m, best[key], key)
            print("%s: POV-Ray's best %.4f takes it %.2f s; %s takes %s"
                  % (key, best[key], best["wall_s"], m,
                     "%.2f s (ratio %.2f)" % (t, t / best["wall_s"]) if t else
                     "(not bracketed by its budgets)"))

    if a.csv:
        with open(a.csv, "w", newline="") as f:
            wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            wr.writeheader()
            for row in rows:
                wr.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in row.items()})
        print("wrote", a.csv)

    # PNGs of the reference and of each method's largest budget.
    write_png(ref, os.path.join(work, "reference.png"))
    for m in ("prism-classic", "prism-progressive", "povray"):
        b = max(r["budget"] for r in rows if r["method"] == m)
        write_png(os.path.join(work, "%s-%d.exr" % (m, b)), os.path.join(work, "best-%s.png" % m))
    print("PNGs in", work)

    if a.chart:
        if not shutil.which("gnuplot"):
            print("gnuplot not found (apt-get install -y gnuplot-nox): no chart")
            return
        dat = os.path.join(work, "chart.dat")
        with open(dat, "w") as f:
            for m in ("prism-classic", "prism-progressive", "povray"):
                f.write("# %s\n" % m)
                for row in sorted((r for r in rows if r["method"] == m), key=lambda r: r["wall_s"]):
                    f.write("%g %g %g %g %d %g\n" % (row["wall_s"], row["rmse"], row["caustic_rmse"],
                                                    row["cpu_s"], row["budget"], row["halo_rmse"]))
                f.write("\n\n")
        titles = ["Prism classic (--photons N)", "Prism progressive (--passes P)",
                  "POV-Ray 3.7 (photons count N)"]
        plots = []
        for col, name in ((2, "whole-image RMSE"), (3, "caustic-region RMSE"),
                          (6, "caustic-region RMSE without the focus")):
            series = ", ".join(
                "'%s' index %d using 1:%d with linespoints lw 2 pt %d title '%s'"
                % (dat, i, col, (7, 5, 9)[i], titles[i]) for i in range(3))
            plots.append("set title '%s'\nset ylabel '%s, W/(m^2 sr)'\nplot %s\n" % (name, name, series))
        script = """set terminal pngcairo size 1800,560 font 'Sans,11'
set output '%s'
set multiplot layout 1,3 title 'Glass-sphere caustic, %dx%d, %d threads: error against Prism reference (%d passes) vs wall time (median of %d)'
set logscale xy
set grid
set key top right
set xlabel 'wall time, s'
%s
unset multiplot
""" % (os.path.abspath(a.chart), a.size, a.size, a.threads, a.ref_passes, a.repeats, "".join(plots))
        gp = os.path.join(work, "chart.gp")
        with open(gp, "w") as f:
            f.write(script)
        subprocess.run(["gnuplot", gp], check=True)
        print("wrote", a.chart)


if __name__ == "__main__":
    main()
