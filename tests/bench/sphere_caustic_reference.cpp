// An exact (semi-analytic) reference for the caustic of a glass ball on a plane under a point
// light, and the scores of a Prism render against it. Independent of Prism's tracer, photon
// map and integrator: only the scene file is read with Prism's parser and images with its I/O.
//
// Light side. A dense stratified grid of directions (cos θ and φ about the light–centre axis,
// equal solid angle per cell, one jittered ray per cell from a fixed seed) covers the ball's
// cone; every ray is followed through the ball analytically — both Fresnel branches at every
// interface (unpolarised Fresnel, Hecht §4.6), the material's reflectance and transmittance as
// the scene format defines them — up to the scene's max_bounces, and the flux of every branch
// that reaches the plane from its lit side is binned on a fine grid on the plane:
// E_bin = Σ Φ / bin area, with Φ = I · Ω_cell · (falloff relative to inverse square at the first
// hit) · the branch's weight. Direct light is not counted (it is not a caustic).
//
// Eye side. Where a pixel sees the plane directly, every light branch that lands there visible
// from the camera is projected into its pixel: E = Σ Φ / (the area of the pixel's footprint on the
// plane, from its corner rays) — the exact pixel average, which bins cannot give at a focus
// narrower than a bin (looked up by S × S eye samples they alias: the focal pixel of
// glass-ball-oblique.yaml read 1991, 3312 and 2607 with 2, 4 and 8 bins a pixel; projected, 2402
// with any). The pixel's samples that meet the ball split into both Fresnel branches (up to the
// scene's max_depth), as a ray tracer does, and add the mean of albedo/π · E_bin where they land;
// the bins are finest at the focus, 1/B of the smallest footprint seen there (through the ball a
// pixel may see a tenth of the plane it sees directly: with the bins of the directly seen plane
// the focal pixels of glass-ball-top.yaml read 48929 and 52021 where symmetry wants one value).
// The result is the pixel-averaged caustic radiance, which a render converges to with many
// samples per pixel.
//
// Scores (--score IMAGE --direct DIRECT): IMAGE − DIRECT is the render's caustic (DIRECT is the
// same render with --caustics none). Over the caustic region — pixels where the reference
// exceeds --region (default 0.01) of the plane's direct radiance scale albedo/π · I/h² (h: the
// light's height above the plane) — the relative RMSE ‖x − r‖₂/‖r‖₂ of the channel mean, the
// same over the regular part (the region without the pixels within 2 of a pixel whose
// reference differs from a 4-neighbour's by more than 25 %: the focus, folds and edges), and the
// flux ratio Σx/Σr over the region; and the RMSE and flux ratio over the part of the region the
// camera sees directly, not through the ball (there pixel sums are proportional to flux).
// Then the same flux ratio over radial rings about the focus axis, each about --ring-pixels
// (default 3) pixels wide (scoreRings): the innermost ring (the focus), the outer fold's ring,
// the worst ring holding 0.5 % of the region's light, each with its standard error from 8
// sectors; --rings FILE writes every ring as CSV.
//
// usage: prism_sphere_caustic_reference SCENE --out REF.exr [--rays N] [--samples S]
//                                        [--bins-per-pixel B] [--threads T]
//        prism_sphere_caustic_reference --reference REF.exr --score IMAGE.exr --direct D.exr
//                                        [--scene SCENE] [--region F] [--png PREFIX]
//                                        [--rings RINGS.csv] [--ring-pixels P]
// --png writes PREFIX.png: the reference (left) and the render's caustic (right), exposure 0.3.
//        prism_sphere_caustic_reference --reference REF.exr --direct D.exr --compose FULL.exr
// writes D + REF: a whole reference image for `prism sweep --reference FULL.exr`.
// The scene must hold one sphere (the caster), one plane (the receiver), one point light.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "image/ImageIo.h"
#include "parse/SceneLoader.h"

namespace {

using D3 = std::array<double, 3>;
D3 operator+(D3 a, D3 b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
D3 operator-(D3 a, D3 b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
D3 operator*(double s, D3 a) {
  return {s * a[0], s * a[1], s * a[2]};
}
double dot(D3 a, D3 b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
D3 cross(D3 a, D3 b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
D3 normalize(D3 a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}
D3 d3(const prism::Vec3& v) {
  return {v.x, v.y, v.z};
}
double mean(const prism::Color& c) {
  return (c.x + c.y + c.z) / 3.0;
}

// Written again in double rather than calling common/shading/Optics.h (float): the reference
// must not share the renderer's arithmetic, or a mistake there would pass unseen.
double fresnel(double cosI, double eta) {  // eta = n1/n2, cosI > 0
  const double s2 = eta * eta * (1.0 - cosI * cosI);
  if (s2 >= 1.0) return 1.0;
  const double cosT = std::sqrt(1.0 - s2);
  const double rs = (eta * cosI - cosT) / (eta * cosI + cosT);
  const double rp = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

struct World {
  D3 centre;
  double radius;
  double reflectance, transmittance, ior;  // channel means
  bool fresnel;
  D3 planePoint, planeNormal;
  double albedo;  // channel mean; colours are restored per channel at the end
  D3 light;
  double intensity;
  prism::Attenuation falloff;
  int maxBounces, maxDepth;
  prism::CameraDesc camera;
  int width, height;
};

World readWorld(const prism::SceneDescription& s) {
  if (s.spheres.size() != 1 || s.planes.size() != 1 || s.lights.size() != 1 || !s.cones.empty() ||
      !s.meshes.empty())
    throw std::runtime_error("the scene must hold one sphere, one plane and one point light");
  World w;
  const auto& sphere = s.spheres[0];
  const auto& glass = s.materials[sphere.material];
  w.centre = d3(sphere.center);
  w.radius = sphere.radius;
  w.reflectance = mean(glass.reflectance);
  w.transmittance = mean(glass.transmittance);
  w.ior = glass.ior;
  w.fresnel = glass.fresnel;
  w.planePoint = d3(s.planes[0].point);
  w.planeNormal = normalize(d3(s.planes[0].normal));
  w.albedo = mean(s.materials[s.planes[0].material].diffuse);
  w.light = d3(s.lights[0].position);
  w.intensity = mean(s.lights[0].intensity);
  w.falloff = s.lights[0].attenuation;
  w.maxBounces = s.caustics.maxBounces;
  w.maxDepth = s.render.maxDepth;
  w.camera = s.camera;
  w.width = s.render.width;
  w.height = s.render.height;
  if (dot(w.light - w.planePoint, w.planeNormal) < 0.0) w.planeNormal = -1.0 * w.planeNormal;
  return w;
}

double hitSphere(const World& w, D3 o, D3 d, double tMin) {
  const D3 oc = o - w.centre;
  const double b = dot(oc, d), c = dot(oc, oc) - w.radius * w.radius;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  const double q = std::sqrt(disc);
  if (-b - q > tMin) return -b - q;
  if (-b + q > tMin) return -b + q;
  return -1.0;
}

double hitPlane(const World& w, D3 o, D3 d) {
  const double dn = dot(d, w.planeNormal);
  if (std::abs(dn) < 1e-300) return -1.0;
  return dot(w.planePoint - o, w.planeNormal) / dn;
}

// The specular split at the ball: (reflect weight, transmit weight, refracted direction).
struct Split {
  double reflect, transmit;
  D3 refracted;
};
Split split(const World& w, D3 d, D3 p) {
  D3 n = (1.0 / w.radius) * (p - w.centre);
  const bool entering = dot(d, n) < 0.0;
  if (!entering) n = -1.0 * n;
  const double eta = entering ? 1.0 / w.ior : w.ior;
  const double cosI = -dot(d, n);
  Split s{w.reflectance, w.transmittance, {0, 0, 0}};
  const double s2 = eta * eta * (1.0 - cosI * cosI);
  if (s2 >= 1.0) {
    s.reflect += s.transmit;
    s.transmit = 0.0;
    return s;
  }
  s.refracted = normalize(eta * d + (eta * cosI - std::sqrt(1.0 - s2)) * n);
  if (w.fresnel) {
    const double f = fresnel(cosI, eta);
    s.reflect += f * s.transmit;
    s.transmit *= 1.0 - f;
  }
  return s;
}
D3 reflectAt(const World& w, D3 d, D3 p) {
  const D3 n = (1.0 / w.radius) * (p - w.centre);
  return d - (2.0 * dot(d, n)) * n;
}

// The fine grid on the plane where flux is binned: origin, axes, bin size, resolution.
struct PlaneGrid {
  D3 origin, u, v;
  double bin = 0.0;
  int nu = 0, nv = 0;
  std::vector<double> flux;
  bool index(D3 x, size_t& at) const {
    const D3 rel = x - origin;
    const double a = dot(rel, u) / bin, b = dot(rel, v) / bin;
    if (!(a >= 0.0 && b >= 0.0 && a < nu && b < nv)) return false;
    at = static_cast<size_t>(b) * nu + static_cast<size_t>(a);
    return true;
  }
};

// Camera rays, as the scene format defines the pinhole and orthographic cameras.
struct Eye {
  D3 position, forward, right, up;
  double halfW, halfH;
  bool ortho;
  Eye(const World& w) {
    position = d3(w.camera.position);
    forward = normalize(d3(w.camera.lookAt) - position);
    right = normalize(cross(forward, d3(w.camera.up)));
    up = cross(right, forward);
    ortho = w.camera.projection == prism::Projection::Orthographic;
    const double aspect = static_cast<double>(w.width) / w.height;
    halfH =
        ortho ? 0.5 * w.camera.width / aspect : std::tan(0.5 * w.camera.fovDegrees * M_PI / 180);
    halfW = ortho ? 0.5 * w.camera.width : halfH * aspect;
  }
  // The image point (pixels) world point p projects to; false behind a perspective camera.
  bool project(const World& w, D3 p, double& x, double& y) const {
    const D3 v = p - position;
    double sx = dot(v, right), sy = dot(v, up);
    if (!ortho) {
      const double z = dot(v, forward);
      if (!(z > 0.0)) return false;
      sx /= z;
      sy /= z;
    }
    x = (sx / halfW + 1.0) * 0.5 * w.width;
    y = (1.0 - sy / halfH) * 0.5 * w.height;
    return true;
  }
  void ray(const World& w, double x, double y, D3& o, D3& d) const {
    const double sx = (2.0 * x / w.width - 1.0) * halfW, sy = (1.0 - 2.0 * y / w.height) * halfH;
    if (ortho) {
      o = position + sx * right + sy * up;
      d = forward;
    } else {
      o = position;
      d = normalize(forward + sx * right + sy * up);
    }
  }
};

// Calls visit(point on plane, weight) for every branch of an eye ray that meets the plane.
template <class Visit>
void traceEye(const World& w, D3 o, D3 d, double weight, int depth, Visit&& visit) {
  const double ts = hitSphere(w, o, d, 1e-9), tp = hitPlane(w, o, d);
  if (ts > 0.0 && (tp <= 0.0 || ts < tp)) {
    if (depth >= w.maxDepth) return;
    const D3 p = o + ts * d;
    const Split s = split(w, d, p);
    if (s.reflect > 0.0) traceEye(w, p, reflectAt(w, d, p), weight * s.reflect, depth + 1, visit);
    if (s.transmit > 0.0) traceEye(w, p, s.refracted, weight * s.transmit, depth + 1, visit);
  } else if (tp > 0.0) {
    visit(o + tp * d, weight);
  }
}

// Grid of bins over the plane covering [lo, hi] (plane coordinates) with bins of `bin`.
PlaneGrid gridOver(const World& w, const double lo[2], const double hi[2], double bin) {
  PlaneGrid g;
  g.u = normalize(std::abs(w.planeNormal[0]) < 0.9 ? cross(w.planeNormal, D3{1, 0, 0})
                                                   : cross(w.planeNormal, D3{0, 1, 0}));
  g.v = cross(w.planeNormal, g.u);
  constexpr int kMaxBins = 4096;
  g.bin = std::max({bin, (hi[0] - lo[0]) / kMaxBins, (hi[1] - lo[1]) / kMaxBins});
  g.origin = w.planePoint + lo[0] * g.u + lo[1] * g.v;
  g.nu = static_cast<int>(std::ceil((hi[0] - lo[0]) / g.bin)) + 1;
  g.nv = static_cast<int>(std::ceil((hi[1] - lo[1]) / g.bin)) + 1;
  g.flux.assign(static_cast<size_t>(g.nu) * g.nv, 0.0);
  return g;
}

// Nested grids: over the bounding box of where the camera sees the plane directly, and finer over
// where it sees the plane through the ball (which magnifies it); bins of 1/binsPerPixel of the
// median pixel footprint in each; then finer grids over where the light through the ball lands
// (below). Lookups use the finest grid that holds the point; an eye path that lands outside all
// is counted and reported.
std::vector<PlaneGrid> makeGrids(const World& w, const Eye& eye, int binsPerPixel) {
  const PlaneGrid axes =
      gridOver(w, std::array<double, 2>{0, 0}.data(), std::array<double, 2>{1, 1}.data(), 1.0);
  double lo[2][2] = {{1e300, 1e300}, {1e300, 1e300}},
         hi[2][2] = {{-1e300, -1e300}, {-1e300, -1e300}};
  const auto hits = [&](double x, double y, bool& through) {
    D3 o, d;
    eye.ray(w, x, y, o, d);
    const double ts = hitSphere(w, o, d, 1e-9), tp = hitPlane(w, o, d);
    through = ts > 0.0 && (tp <= 0.0 || ts < tp);
    std::vector<D3> out;
    traceEye(w, o, d, 1.0, 0, [&](D3 p, double) { out.push_back(p); });
    return out;
  };
  // Pass 1: footprints (distance between the transmitted hits of neighbouring pixels).
  struct Sample {
    D3 p;
    double footprint;
  };
  std::vector<Sample> samples[2];
  for (int y = 0; y <= w.height; y += std::max(1, w.height / 512)) {
    for (int x = 0; x <= w.width; x += std::max(1, w.width / 512)) {
      bool through = false, through2 = false;
      const std::vector<D3> a = hits(x, y, through), b = hits(x + 1, y, through2);
      // The last branch visited is the transmitted one (straight on, or in and out of the ball).
      if (a.empty() || b.empty() || through != through2) continue;
      const D3 step = b.back() - a.back();
      samples[through ? 1 : 0].push_back({a.back(), std::sqrt(dot(step, step))});
    }
  }
  if (samples[0].empty()) throw std::runtime_error("the camera sees no plane directly");
  std::vector<PlaneGrid> grids;
  for (int level = 0; level < 2; ++level) {
    if (samples[level].empty()) continue;
    std::vector<double> f;
    for (const Sample& s : samples[level]) f.push_back(s.footprint);
    // Directly: the median footprint over the whole view. Through the ball, which magnifies its
    // centre strongly: the 5th percentile, over the part of the view that fine.
    std::nth_element(f.begin(), f.begin() + f.size() / (level ? 20 : 2), f.end());
    const double footprint = f[f.size() / (level ? 20 : 2)];
    for (const Sample& s : samples[level]) {
      if (level == 1 && s.footprint > 4.0 * footprint) continue;
      const double pu = dot(s.p - w.planePoint, axes.u), pv = dot(s.p - w.planePoint, axes.v);
      lo[level][0] = std::min(lo[level][0], pu), hi[level][0] = std::max(hi[level][0], pu);
      lo[level][1] = std::min(lo[level][1], pv), hi[level][1] = std::max(hi[level][1], pv);
    }
    grids.push_back(gridOver(w, lo[level], hi[level], footprint / binsPerPixel));
  }
  // The caustic's core: where the light through the ball lands (a coarse grid of light rays in
  // and out of the ball), within the direct view, binned at the finest footprint seen there, so
  // a focus is resolved however wide the view.
  std::vector<double> us, vs;
  std::vector<std::pair<double, double>> landing;
  const D3 axis = normalize(w.centre - w.light), toCentre = w.centre - w.light;
  const double cosMax = std::sqrt(1.0 - w.radius * w.radius / dot(toCentre, toCentre));
  const D3 a =
      normalize(std::abs(axis[0]) < 0.9 ? cross(axis, D3{1, 0, 0}) : cross(axis, D3{0, 1, 0}));
  const D3 b = cross(axis, a);
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 512; ++j) {
      const double cosT = 1.0 - (i + 0.5) / 256 * (1.0 - cosMax),
                   phi = 2.0 * M_PI * (j + 0.5) / 512;
      const double sinT = std::sqrt(1.0 - cosT * cosT);
      const D3 d = cosT * axis + (sinT * std::cos(phi)) * a + (sinT * std::sin(phi)) * b;
      const double ts = hitSphere(w, w.light, d, 1e-9);
      if (!(ts > 0.0)) continue;
      const D3 p = w.light + ts * d;
      const Split sp = split(w, d, p);
      if (!(sp.transmit > 0.0)) continue;
      const D3 q = p + hitSphere(w, p, sp.refracted, 1e-9) * sp.refracted;
      const Split out = split(w, sp.refracted, q);
      if (!(out.transmit > 0.0)) continue;
      const double tp = hitPlane(w, q, out.refracted);
      if (!(tp > 0.0)) continue;
      const D3 x = q + tp * out.refracted;
      us.push_back(dot(x - w.planePoint, axes.u));
      vs.push_back(dot(x - w.planePoint, axes.v));
      landing.push_back({us.back(), vs.back()});  // us and vs are sorted apart below
    }
  }
  // Two nested grids: the 1st..99th percentiles of where it lands, at the finest footprint seen
  // there (directly or through the ball); and the central half, where a focus lies, twice as fine.
  if (us.size() > 100) {
    std::sort(us.begin(), us.end());
    std::sort(vs.begin(), vs.end());
    for (const auto& [tail, fineness] : {std::pair{100, 1}, std::pair{4, 2}}) {
      const size_t q0 = us.size() / tail, q1 = us.size() - 1 - us.size() / tail;
      const double pad = 0.05 * std::max(us[q1] - us[q0], vs[q1] - vs[q0]);
      double clo[2] = {std::max(lo[0][0], us[q0] - pad), std::max(lo[0][1], vs[q0] - pad)};
      double chi[2] = {std::min(hi[0][0], us[q1] + pad), std::min(hi[0][1], vs[q1] + pad)};
      std::vector<double> f;
      for (const auto& level : samples) {
        for (const Sample& s : level) {
          const double pu = dot(s.p - w.planePoint, axes.u), pv = dot(s.p - w.planePoint, axes.v);
          if (pu >= clo[0] && pu <= chi[0] && pv >= clo[1] && pv <= chi[1])
            f.push_back(s.footprint);
        }
      }
      if (clo[0] < chi[0] && clo[1] < chi[1] && !f.empty()) {
        std::nth_element(f.begin(), f.begin() + f.size() / 20, f.end());
        grids.push_back(gridOver(w, clo, chi, f[f.size() / 20] / (binsPerPixel * fineness)));
      }
    }
  }
  // The focus: the densest spot of the coarse landing points, with a window of 128 of the
  // finest footprints seen within it each way, binned at that footprint. Seen through the ball a
  // focus is magnified: its pixels see less of the plane than any pixel seeing it directly.
  if (us.size() > 100) {
    const double ulo = us[us.size() / 100], uhi = us[us.size() - 1 - us.size() / 100];
    const double vlo = vs[vs.size() / 100], vhi = vs[vs.size() - 1 - vs.size() / 100];
    constexpr int kCells = 256;
    std::vector<int> count(kCells * kCells, 0);
    for (const auto& [pu, pv] : landing) {
      const int cu = static_cast<int>((pu - ulo) / (uhi - ulo) * kCells);
      const int cv = static_cast<int>((pv - vlo) / (vhi - vlo) * kCells);
      if (cu >= 0 && cv >= 0 && cu < kCells && cv < kCells) ++count[cv * kCells + cu];
    }
    const int peak = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
    const double cu = ulo + (peak % kCells + 0.5) * (uhi - ulo) / kCells;
    const double cv = vlo + (peak / kCells + 0.5) * (vhi - vlo) / kCells;
    const double reach = 2.0 * std::max(uhi - ulo, vhi - vlo) / kCells;
    double finest = 1e300;
    for (const auto& level : samples) {
      for (const Sample& s : level) {
        const double pu = dot(s.p - w.planePoint, axes.u), pv = dot(s.p - w.planePoint, axes.v);
        if (std::abs(pu - cu) <= reach && std::abs(pv - cv) <= reach)
          finest = std::min(finest, s.footprint);
      }
    }
    if (finest < 1e300) {
      const double half = 128.0 * finest;
      const double flo[2] = {cu - half, cv - half}, fhi[2] = {cu + half, cv + half};
      grids.push_back(gridOver(w, flo, fhi, finest / binsPerPixel));
    }
  }
  // Coarsest first: the first grid counts the flux that lands outside every grid, lookups take
  // the finest grid that holds the point.
  std::stable_sort(grids.begin(), grids.end(),
                   [](const PlaneGrid& x, const PlaneGrid& y) { return x.bin > y.bin; });
  for (const PlaneGrid& g : grids)
    std::fprintf(stderr, "plane grid %d x %d bins of %.5g\n", g.nu, g.nv, g.bin);
  return grids;
}

// Light landing where the camera sees the plane directly, summed per pixel by projecting the
// landing point: the exact pixel average there (flux in the pixel's footprint over its area),
// where a lookup in plane bins would alias against the eye samples at a focus narrower than a bin
// (the focal pixel read 1991, 3312 and 2607 with three bin and sample settings).
struct DirectView {
  const Eye* eye = nullptr;
  std::vector<double> flux;  // per pixel
  void deposit(const World& w, D3 x, double power) {
    const D3 toEye = eye->ortho ? -1.0 * eye->forward : eye->position - x;
    const double distance = eye->ortho ? 1e300 : std::sqrt(dot(toEye, toEye));
    const D3 d = eye->ortho ? toEye : (1.0 / distance) * toEye;
    if (!(dot(d, w.planeNormal) > 0.0)) return;  // the camera sees the plane's other side
    const double ts = hitSphere(w, x, d, 1e-9);
    if (ts > 0.0 && ts < distance) return;  // the ball hides it
    double px, py;
    if (!eye->project(w, x, px, py) || px < 0.0 || py < 0.0 || px >= w.width || py >= w.height)
      return;
    flux[static_cast<size_t>(py) * w.width + static_cast<size_t>(px)] += power;
  }
};

// One light path through the ball: every branch that reaches the plane deposits its flux.
void traceLight(const World& w, D3 o, D3 d, double power, int bounces, bool first,
                std::vector<PlaneGrid>& grids, double& lost, DirectView& view) {
  const double ts = hitSphere(w, o, d, 1e-9), tp = hitPlane(w, o, d);
  if (ts > 0.0 && (tp <= 0.0 || ts < tp)) {
    const D3 p = o + ts * d;
    if (first) {  // the light's falloff relative to inverse square, at the first hit
      const double dist = ts;
      power /= w.falloff.constant / (dist * dist) + w.falloff.linear / dist + w.falloff.quadratic;
    }
    if (bounces >= w.maxBounces || power < 1e-14) return;
    const Split s = split(w, d, p);
    if (s.reflect > 0.0)
      traceLight(w, p, reflectAt(w, d, p), power * s.reflect, bounces + 1, false, grids, lost,
                 view);
    if (s.transmit > 0.0)
      traceLight(w, p, s.refracted, power * s.transmit, bounces + 1, false, grids, lost, view);
  } else if (tp > 0.0 && !first && dot(d, w.planeNormal) < 0.0) {
    size_t at;
    if (grids[0].index(o + tp * d, at))
      grids[0].flux[at] += power;
    else
      lost += power;
    for (size_t level = 1; level < grids.size(); ++level)
      if (grids[level].index(o + tp * d, at)) grids[level].flux[at] += power;
    view.deposit(w, o + tp * d, power);
  }
}

// The area of pixel (x, y)'s footprint on the plane (the quadrilateral its corner rays meet), or
// 0 where a corner ray misses the plane.
double footprintArea(const World& w, const Eye& eye, int x, int y) {
  D3 corner[4];
  for (int k = 0; k < 4; ++k) {
    D3 o, d;
    eye.ray(w, x + (k & 1), y + (k >> 1), o, d);
    const double t = hitPlane(w, o, d);
    if (!(t > 0.0)) return 0.0;
    corner[k] = o + t * d;
  }
  const D3 diagonal1 = corner[3] - corner[0], diagonal2 = corner[2] - corner[1];
  const D3 c = cross(diagonal1, diagonal2);
  return 0.5 * std::sqrt(dot(c, c));
}

prism::ImageRgb buildReference(const prism::SceneDescription& s, long rays, int samples,
                               int binsPerPixel, int threads) {
  const World w = readWorld(s);
  const Eye eye(w);
  std::vector<PlaneGrid> grid = makeGrids(w, eye, binsPerPixel);

  // Light side: the cone of directions that meets the ball, cut into n × 2n equal solid angles.
  const D3 axis = normalize(w.centre - w.light);
  const D3 toCentre = w.centre - w.light;
  const double cosMax = std::sqrt(1.0 - w.radius * w.radius / dot(toCentre, toCentre));
  const D3 a =
      normalize(std::abs(axis[0]) < 0.9 ? cross(axis, D3{1, 0, 0}) : cross(axis, D3{0, 1, 0}));
  const D3 b = cross(axis, a);
  const long n = std::max(1L, static_cast<long>(std::sqrt(rays / 2.0)));
  const double cellOmega = 2.0 * M_PI * (1.0 - cosMax) / (static_cast<double>(n) * 2 * n);
  std::vector<std::vector<PlaneGrid>> grids(threads, grid);
  std::vector<double> lost(threads, 0.0);
  std::vector<DirectView> views(threads);
  for (DirectView& v : views) {
    v.eye = &eye;
    v.flux.assign(static_cast<size_t>(w.width) * w.height, 0.0);
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (long i = t; i < n; i += threads) {
        std::mt19937_64 rng(0x5eed + i);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (long j = 0; j < 2 * n; ++j) {
          const double cosT = 1.0 - (i + u(rng)) / n * (1.0 - cosMax);
          const double phi = 2.0 * M_PI * (j + u(rng)) / (2.0 * n);
          const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
          const D3 d = cosT * axis + (sinT * std::cos(phi)) * a + (sinT * std::sin(phi)) * b;
          traceLight(w, w.light, d, w.intensity * cellOmega, 0, true, grids[t], lost[t], views[t]);
        }
      }
    });
  }
  for (auto& th : pool) th.join();
  double binned = 0.0, missed = 0.0;
  for (int t = 0; t < threads; ++t) {
    missed += lost[t];
    for (size_t level = 0; level < grid.size(); ++level)
      for (size_t k = 0; k < grid[level].flux.size(); ++k)
        grid[level].flux[k] += grids[t][level].flux[k];
  }
  grids.clear();
  std::vector<double> directFlux(static_cast<size_t>(w.width) * w.height, 0.0);
  for (const DirectView& v : views)
    for (size_t k = 0; k < directFlux.size(); ++k) directFlux[k] += v.flux[k];
  views.clear();
  for (double f : grid[0].flux) binned += f;
  std::fprintf(stderr, "flux on the plane grid %.6g W, outside it %.6g W\n", binned, missed);

  // Eye side: pixel-averaged albedo/π · E over S × S samples per pixel.
  prism::ImageRgb image(w.width, w.height);
  std::vector<double> outside(threads, 0.0);
  pool.clear();
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int y = t; y < w.height; y += threads) {
        for (int x = 0; x < w.width; ++x) {
          double sum = 0.0;
          // Where the pixel sees the plane directly, its light comes from the projected flux
          // (whole: the hidden part of the footprint got none); samples through the ball look
          // up the bins.
          const double area = footprintArea(w, eye, x, y);
          const bool projected = area > 0.0;
          for (int sy = 0; sy < samples; ++sy) {
            for (int sx = 0; sx < samples; ++sx) {
              D3 o, d;
              eye.ray(w, x + (sx + 0.5) / samples, y + (sy + 0.5) / samples, o, d);
              if (projected) {
                const double ts = hitSphere(w, o, d, 1e-9), tp = hitPlane(w, o, d);
                if (tp > 0.0 && !(ts > 0.0 && ts < tp)) continue;
              }
              traceEye(w, o, d, 1.0, 0, [&](D3 p, double weight) {
                size_t at;
                for (size_t level = grid.size(); level-- > 0;) {
                  if (grid[level].index(p, at)) {
                    sum += weight * grid[level].flux[at] / (grid[level].bin * grid[level].bin);
                    return;
                  }
                }
                outside[t] += weight;
              });
            }
          }
          double e = sum / (samples * samples);
          if (projected) e += directFlux[static_cast<size_t>(y) * w.width + x] / area;
          image.at(x, y) = prism::Color(static_cast<float>(e));
        }
      }
    });
  }
  for (auto& th : pool) th.join();
  double off = 0.0;
  for (double o : outside) off += o;
  std::fprintf(stderr, "eye-path weight landing off the plane grid: %.4g pixels' worth\n",
               off / (samples * samples));
  // Colour per channel: radiance is linear in the light's intensity and the plane's albedo.
  const prism::Color scale = s.lights[0].intensity * s.materials[s.planes[0].material].diffuse *
                             static_cast<float>(1.0 / (M_PI * w.intensity));
  for (auto& p : image.pixels) p *= scale;
  return image;
}

// Radial rings about the focus axis: the foot of the light–centre line on the plane. A box of
// pixels about the focus averages its sharpest parts away (a disc too bright inside a ring too
// dark keeps the box's flux); a ring of about 3 pixels at every radius sees where light moved
// towards or away from the focus and across the caustic's outer fold. Each pixel is placed at
// the plane point its centre ray's strongest branch lands on (directly, or through the ball),
// and a ring is `ringPixels` of the radial distance neighbouring pixels span there, so rings are
// about as wide in the image everywhere (a view through the ball magnifies the centre).
struct Ring {
  double lo = 0, hi = 0;  // plane radius
  double sx = 0, sr = 0;  // sums of the render's and the reference's caustic
  long pixels = 0;
  std::array<double, 8> sectorX{}, sectorR{};  // the same in 8 sectors: the ring's noise
  double ratio() const { return sr > 0 ? sx / sr : 0.0; }
  // Standard error of the ratio from the spread of the sectors' ratios (the caustic is round
  // about the axis, so the sectors differ by noise; pixels within a kernel are not independent,
  // sectors far apart are).
  double standardError() const {
    double m = 0, m2 = 0;
    int n = 0;
    for (size_t k = 0; k < sectorX.size(); ++k) {
      if (!(sectorR[k] > 0)) continue;
      const double q = sectorX[k] / sectorR[k];
      m += q, m2 += q * q, ++n;
    }
    if (n < 2) return 0.0;
    m /= n;
    return std::sqrt(std::max(0.0, (m2 / n - m * m) * n / (n - 1)) / n);
  }
};

struct RingScores {
  std::vector<Ring> rings;
  size_t fold = 0;  // the ring inside the outer fold (see scoreRings)
};

RingScores scoreRings(const World& w, const Eye& eye, int W, int H, const std::vector<double>& r,
                      const std::vector<double>& x, double threshold, int ringPixels) {
  const D3 axis = normalize(w.centre - w.light);
  const double along = dot(w.planePoint - w.light, w.planeNormal) / dot(axis, w.planeNormal);
  const D3 foot = w.light + along * axis;
  const D3 u = normalize(std::abs(w.planeNormal[0]) < 0.9 ? cross(w.planeNormal, D3{1, 0, 0})
                                                          : cross(w.planeNormal, D3{0, 1, 0}));
  const D3 v = cross(w.planeNormal, u);
  // Each pixel's plane radius and angle: where its centre ray's strongest branch lands.
  std::vector<double> rho(r.size(), -1.0), angle(r.size(), 0.0);
  for (int y = 0; y < H; ++y)
    for (int xx = 0; xx < W; ++xx) {
      D3 o, d;
      eye.ray(w, xx + 0.5, y + 0.5, o, d);
      double best = 0.0;
      D3 at{};
      traceEye(w, o, d, 1.0, 0, [&](D3 p, double weight) {
        if (weight > best) best = weight, at = p;
      });
      if (!(best > 0.0)) continue;
      const size_t i = static_cast<size_t>(y) * W + xx;
      const D3 rel = at - foot;
      rho[i] = std::sqrt(dot(rel, rel));
      angle[i] = std::atan2(dot(rel, v), dot(rel, u));
    }
  // How far in radius one pixel reaches, as a function of radius: the median, over the region's
  // pixels in 256 radius bins, of the larger radial step to the right or lower neighbour.
  double rhoMax = 0.0;
  for (size_t i = 0; i < r.size(); ++i)
    if (r[i] > threshold && rho[i] >= 0) rhoMax = std::max(rhoMax, rho[i]);
  RingScores out;
  if (!(rhoMax > 0.0)) return out;
  constexpr int kCoarse = 256;
  std::vector<std::vector<double>> steps(kCoarse);
  for (int y = 0; y + 1 < H; ++y)
    for (int xx = 0; xx + 1 < W; ++xx) {
      const size_t i = static_cast<size_t>(y) * W + xx;
      if (!(r[i] > threshold) || rho[i] < 0 || rho[i + 1] < 0 || rho[i + W] < 0) continue;
      const int c = std::min(kCoarse - 1, static_cast<int>(rho[i] / rhoMax * kCoarse));
      steps[c].push_back(std::max(std::abs(rho[i + 1] - rho[i]), std::abs(rho[i + W] - rho[i])));
    }
  std::vector<double> step(kCoarse, 0.0);
  for (int c = 0; c < kCoarse; ++c) {
    auto& s = steps[c];
    if (s.empty()) continue;
    std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
    step[c] = s[s.size() / 2];
  }
  for (int c = 1; c < kCoarse; ++c)  // bins without pixels take the nearer one inside
    if (step[c] == 0.0) step[c] = step[c - 1];
  for (int c = kCoarse - 2; c >= 0; --c)
    if (step[c] == 0.0) step[c] = step[c + 1];
  if (!(step[0] > 0.0)) return out;
  for (double edge = 0.0; edge <= rhoMax;) {
    const int c = std::min(kCoarse - 1, static_cast<int>(edge / rhoMax * kCoarse));
    Ring ring;
    ring.lo = edge;
    ring.hi = edge + ringPixels * step[c];
    out.rings.push_back(ring);
    edge = ring.hi;
  }
  for (size_t i = 0; i < r.size(); ++i) {
    if (rho[i] < 0 || !(r[i] > threshold)) continue;
    const auto it = std::upper_bound(out.rings.begin(), out.rings.end(), rho[i],
                                     [](double q, const Ring& ring) { return q < ring.hi; });
    if (it == out.rings.end()) continue;
    const int sector = std::min(7, static_cast<int>((angle[i] + M_PI) / (2 * M_PI) * 8));
    it->sx += x[i], it->sr += r[i], ++it->pixels;
    it->sectorX[sector] += x[i], it->sectorR[sector] += r[i];
  }
  // The outer fold: where the profile falls most steeply for its radius (the largest
  // −Δlog E/Δlog ρ over two rings), among rings of at least 16 pixels holding 0.1 % of the
  // region's light. A focus falls as a power of the radius (ρ^−4/3 for spherical aberration:
  // slope 4/3); a fold's edge, from an inverse square root inside to nothing outside, far faster.
  double total = 0.0, steepest = 0.0;
  for (const Ring& ring : out.rings) total += ring.sr;
  const auto mean = [&](size_t k) { return out.rings[k].sr / out.rings[k].pixels; };
  const auto centre = [&](size_t k) { return 0.5 * (out.rings[k].lo + out.rings[k].hi); };
  for (size_t k = 2; k + 2 < out.rings.size(); ++k) {
    const Ring &here = out.rings[k], &beyond = out.rings[k + 2];
    if (here.pixels < 16 || beyond.pixels < 16 || here.sr < 0.001 * total) continue;
    if (!(mean(k + 2) > 0.0)) continue;
    const double slope = std::log(mean(k) / mean(k + 2)) / std::log(centre(k + 2) / centre(k));
    if (slope > steepest) steepest = slope, out.fold = k;
  }
  return out;
}

int score(const std::string& refPath, const std::string& imagePath, const std::string& directPath,
          const std::string& scenePath, double regionFraction, const std::string& pngPrefix,
          const std::string& ringsCsv, int ringPixels, float exposure = 0.3f) {
  const prism::ImageRgb ref = prism::readImage(refPath), img = prism::readImage(imagePath),
                        direct = prism::readImage(directPath);
  if (img.width != ref.width || img.height != ref.height || direct.width != ref.width ||
      direct.height != ref.height)
    throw std::runtime_error("image sizes differ from the reference");
  const World w = readWorld(prism::loadScene(scenePath));
  const double h = dot(w.light - w.planePoint, w.planeNormal);
  const double threshold = regionFraction * w.albedo / M_PI * w.intensity / (h * h);
  const int W = ref.width, H = ref.height;
  std::vector<double> r(ref.pixels.size()), x(ref.pixels.size());
  for (size_t i = 0; i < r.size(); ++i) {
    r[i] = mean(ref.pixels[i]);
    x[i] = mean(img.pixels[i]) - mean(direct.pixels[i]);
  }
  // Singular pixels: a step of more than 25 % to a 4-neighbour; then dilated by 2.
  std::vector<char> steep(r.size(), 0), singular(r.size(), 0);
  for (int y = 0; y < H; ++y) {
    for (int xx = 0; xx < W; ++xx) {
      const size_t i = static_cast<size_t>(y) * W + xx;
      const auto jump = [&](int dx, int dy) {
        const int X = xx + dx, Y = y + dy;
        if (X < 0 || Y < 0 || X >= W || Y >= H) return false;
        const double o = r[static_cast<size_t>(Y) * W + X];
        return std::abs(o - r[i]) > 0.25 * std::max(o, r[i]) && std::max(o, r[i]) > threshold;
      };
      steep[i] = jump(1, 0) || jump(-1, 0) || jump(0, 1) || jump(0, -1);
    }
  }
  for (int y = 0; y < H; ++y)
    for (int xx = 0; xx < W; ++xx)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int X = xx + dx, Y = y + dy;
          if (X >= 0 && Y >= 0 && X < W && Y < H && steep[static_cast<size_t>(Y) * W + X])
            singular[static_cast<size_t>(y) * W + xx] = 1;
        }
  // Pixels that see the plane directly (not through the ball), where pixel sums are flux.
  const Eye eye(w);
  std::vector<char> seenDirectly(r.size(), 0);
  for (int y = 0; y < H; ++y)
    for (int xx = 0; xx < W; ++xx) {
      D3 o, d;
      eye.ray(w, xx + 0.5, y + 0.5, o, d);
      const double ts = hitSphere(w, o, d, 1e-9), tp = hitPlane(w, o, d);
      seenDirectly[static_cast<size_t>(y) * W + xx] = tp > 0.0 && !(ts > 0.0 && ts < tp);
    }
  double e2 = 0, r2 = 0, re2 = 0, rr2 = 0, sx = 0, sr = 0, de2 = 0, dr2 = 0, dsx = 0, dsr = 0;
  long region = 0, regular = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    if (!(r[i] > threshold)) continue;
    ++region;
    if (seenDirectly[i]) {
      de2 += (x[i] - r[i]) * (x[i] - r[i]);
      dr2 += r[i] * r[i];
      dsx += x[i];
      dsr += r[i];
    }
    e2 += (x[i] - r[i]) * (x[i] - r[i]);
    r2 += r[i] * r[i];
    sx += x[i];
    sr += r[i];
    if (!singular[i]) {
      ++regular;
      re2 += (x[i] - r[i]) * (x[i] - r[i]);
      rr2 += r[i] * r[i];
    }
  }
  if (!pngPrefix.empty()) {  // the two caustics side by side, for looking at
    prism::ImageRgb both(2 * W, H);
    for (int y = 0; y < H; ++y)
      for (int xx = 0; xx < W; ++xx) {
        both.at(xx, y) = ref.at(xx, y);
        both.at(W + xx, y) = img.at(xx, y) - direct.at(xx, y);
      }
    prism::writeImage(both, pngPrefix + ".png", exposure);
  }
  // The focus: the reference's brightest pixel, and the 9 × 9 pixels around it.
  const size_t peak = static_cast<size_t>(std::max_element(r.begin(), r.end()) - r.begin());
  double fx = 0, fr = 0;
  for (int dy = -4; dy <= 4; ++dy)
    for (int dx = -4; dx <= 4; ++dx) {
      const int X = static_cast<int>(peak % W) + dx, Y = static_cast<int>(peak / W) + dy;
      if (X < 0 || Y < 0 || X >= W || Y >= H) continue;
      fx += x[static_cast<size_t>(Y) * W + X];
      fr += r[static_cast<size_t>(Y) * W + X];
    }
  if (std::getenv("PRINT_FOCUS")) {  // the 7 × 7 pixels around the reference's peak
    for (int dy = -3; dy <= 3; ++dy) {
      for (int dx = -3; dx <= 3; ++dx) {
        const size_t i = static_cast<size_t>(static_cast<int>(peak / W) + dy) * W +
                         static_cast<size_t>(static_cast<int>(peak % W) + dx);
        std::printf("%6.0f/%-6.0f ", r[i], x[i]);
      }
      std::printf("\n");
    }
  }
  std::printf(
      "region_px %ld regular_px %ld rel_rmse %.5f rel_rmse_regular %.5f flux_ratio %.5f "
      "direct_rel_rmse %.5f direct_flux_ratio %.5f peak_ref %.5g peak_ratio %.4f "
      "focus9_ratio %.4f regular_share_of_error2 %.3f regular_share_of_ref2 %.3f\n",
      region, regular, std::sqrt(e2 / r2), std::sqrt(re2 / rr2), sx / sr, std::sqrt(de2 / dr2),
      dsx / dsr, r[peak], x[peak] / r[peak], fx / fr, re2 / e2, rr2 / r2);
  const RingScores rs = scoreRings(w, eye, W, H, r, x, threshold, ringPixels);
  if (!rs.rings.empty()) {
    // The rings that hold at least 0.5 % of the region's reference: the worst of them, in
    // relative error and in standard errors.
    double worst = 0, worstZ = 0;
    size_t worstAt = 0;
    for (size_t k = 0; k < rs.rings.size(); ++k) {
      const Ring& ring = rs.rings[k];
      if (ring.sr < 0.005 * sr) continue;
      const double dev = ring.ratio() - 1.0, se = ring.standardError();
      if (std::abs(dev) > std::abs(worst)) worst = dev, worstAt = k;
      if (se > 0 && std::abs(dev / se) > std::abs(worstZ)) worstZ = dev / se;
    }
    const Ring &inner = rs.rings[0], &fold = rs.rings[rs.fold];
    std::printf(
        "rings %zu ring_px %d ring0_ratio %.4f ring0_se %.4f ring1_ratio %.4f ring2_ratio %.4f "
        "fold_ring %zu fold_rho %.4g fold_ratio %.4f fold_se %.4f worst_ring %zu "
        "worst_ring_dev %.4f worst_ring_z %.2f\n",
        rs.rings.size(), ringPixels, inner.ratio(), inner.standardError(),
        rs.rings.size() > 1 ? rs.rings[1].ratio() : 0.0,
        rs.rings.size() > 2 ? rs.rings[2].ratio() : 0.0, rs.fold, 0.5 * (fold.lo + fold.hi),
        fold.ratio(), fold.standardError(), worstAt, worst, worstZ);
    if (!ringsCsv.empty()) {
      FILE* f = std::fopen(ringsCsv.c_str(), "w");
      if (!f) throw std::runtime_error("cannot write " + ringsCsv);
      std::fprintf(f, "ring,rho_lo,rho_hi,pixels,reference,render,ratio,standard_error\n");
      for (size_t k = 0; k < rs.rings.size(); ++k) {
        const Ring& ring = rs.rings[k];
        std::fprintf(f, "%zu,%.6g,%.6g,%ld,%.8g,%.8g,%.6f,%.6f\n", k, ring.lo, ring.hi, ring.pixels,
                     ring.sr, ring.sx, ring.ratio(), ring.standardError());
      }
      std::fclose(f);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene, out, reference, image, direct, png, compose, ringsCsv;
  long rays = 200000000;
  int samples = 8, binsPerPixel = 2, ringPixels = 3;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  double region = 0.01;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--out")
      out = next();
    else if (a == "--rays")
      rays = std::stol(next());
    else if (a == "--samples")
      samples = std::stoi(next());
    else if (a == "--bins-per-pixel")
      binsPerPixel = std::stoi(next());
    else if (a == "--threads")
      threads = std::stoi(next());
    else if (a == "--reference")
      reference = next();
    else if (a == "--score")
      image = next();
    else if (a == "--direct")
      direct = next();
    else if (a == "--scene")
      scene = next();
    else if (a == "--region")
      region = std::stod(next());
    else if (a == "--png")
      png = next();
    else if (a == "--compose")
      compose = next();
    else if (a == "--rings")
      ringsCsv = next();
    else if (a == "--ring-pixels")
      ringPixels = std::stoi(next());
    else if (scene.empty() && a[0] != '-')
      scene = a;
    else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  try {
    if (!compose.empty()) {  // direct light plus the exact caustic: a whole reference image
      prism::ImageRgb full = prism::readImage(reference);
      const prism::ImageRgb d = prism::readImage(direct);
      if (d.width != full.width || d.height != full.height)
        throw std::runtime_error("image sizes differ from the reference");
      for (size_t i = 0; i < full.pixels.size(); ++i) full.pixels[i] += d.pixels[i];
      prism::writeImage(full, compose);
      return 0;
    }
    if (!image.empty())
      return score(reference, image, direct, scene, region, png, ringsCsv, ringPixels,
                   static_cast<float>(
                       std::getenv("PNG_EXPOSURE") ? std::atof(std::getenv("PNG_EXPOSURE")) : 0.3));
    if (scene.empty() || out.empty()) {
      std::fprintf(stderr, "usage: see the comment at the top of sphere_caustic_reference.cpp\n");
      return 2;
    }
    const prism::ImageRgb ref =
        buildReference(prism::loadScene(scene), rays, samples, binsPerPixel, threads);
    prism::writeImage(ref, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
