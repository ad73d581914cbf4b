#include "caustics/CausticMap.h"

#include <algorithm>
#include <cmath>

#include "math/FloorToInt.h"
#include "math/Simd.h"
#include "shading/LightFalloff.h"
#include "shading/SpecularSplit.h"
#include "util/Parallel.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

constexpr int kMaxInterfaces = 8;    // caster surfaces a traced path may cross
constexpr float kMinWeight = 1e-3f;  // branches below this share of the texel's flux are dropped

// The region of space whose lookups can read texel (i, j) of a view (receiver at `distance`,
// depth tolerance `tolerance`): a lookup reads the texels around where the point projects, so
// the point lies within a texel of this one's centre, at most `tolerance` nearer or further from
// the light than its receiver. The window taken is half a texel wider on every side, and the
// far corners are pushed out so that the sphere of the far distance stays inside: the box holds
// the region with room to spare for rounding.
Aabb texelReach(const LightFrustum& frustum, const Vec3& light, int view, int i, int j,
                float distance, float tolerance) {
  const Vec3 centre = frustum.direction(view, i + 0.5f, j + 0.5f);
  const float x0 = static_cast<float>(i) - 1.0f, x1 = static_cast<float>(i) + 2.0f;
  const float y0 = static_cast<float>(j) - 1.0f, y1 = static_cast<float>(j) + 2.0f;
  const Vec3 corners[4] = {frustum.direction(view, x0, y0), frustum.direction(view, x1, y0),
                           frustum.direction(view, x0, y1), frustum.direction(view, x1, y1)};
  float minCos = 1.0f;
  for (const Vec3& c : corners) minCos = std::min(minCos, glm::dot(c, centre));
  const float nearest = std::max(distance - tolerance, 0.0f);
  const float farthest = (distance + tolerance) / std::max(minCos, 0.5f);
  Aabb box;
  for (const Vec3& c : corners) {
    box.extend(light + nearest * c);
    box.extend(light + farthest * c);
  }
  return box;
}

struct Splat {
  uint32_t texel;
  Color flux;
};

// Carries one caster texel's flux through the casters to its splats.
class TexelTransport {
 public:
  TexelTransport(const Scene& scene, const LightFrustum& frustum, const ReceiverMap& receivers,
                 const CausticSettings& settings, std::vector<Splat>& out, CausticMapStats& stats)
      : scene_(scene),
        frustum_(frustum),
        receivers_(receivers),
        settings_(settings),
        out_(out),
        stats_(stats) {}

  void start(const SurfaceHit& s, const Vec3& direction, const Color& flux) {
    minFlux_ = kMinWeight * maxComponent(flux);
    scatter(s, direction, flux, 1);
  }

 private:
  // Light arriving along `direction` at caster surface s leaves reflected and refracted.
  void scatter(const SurfaceHit& s, const Vec3& direction, const Color& flux, int interfaces) {
    const SpecularSplit split = splitSpecular(scene_.materials()[s.material], s, direction);
    if (!isBlack(split.reflectWeight)) {
      leave(s, reflectedDirection(s, direction), flux * split.reflectWeight, interfaces);
    }
    if (split.refracted && !isBlack(split.transmitWeight)) {
      leave(s, *split.refracted, flux * split.transmitWeight, interfaces);
    }
  }

  void leave(const SurfaceHit& s, const Vec3& direction, const Color& flux, int interfaces) {
    if (maxComponent(flux) < minFlux_) return;
    if (settings_.mapPaths == CausticMapPaths::Traced) {
      // The exact next surface: another caster (the sphere's back, a second object) takes the
      // light on; anything else ends the path, whose receiver the iteration estimates.
      const Ray ray{s.rayOrigin(direction), direction};
      HitRecord hit;
      if (scene_.intersect(ray, hit)) {
        const SurfaceHit next = scene_.surface(ray, hit);
        if (next.caustic & kCastsCaustics) {
          if (interfaces < kMaxInterfaces) scatter(next, direction, flux, interfaces + 1);
          return;
        }
      }
    }
    land(s.position, direction, flux);
  }

  // The thesis's estimate of where the ray P + t·dir meets the receivers, then the splat.
  void land(const Vec3& p, const Vec3& dir, const Color& flux) {
    ++stats_.paths;
    float d = 1.0f;
    for (int k = 0; k < settings_.mapSteps; ++k) {
      const std::optional<LightSpacePoint> q = frustum_.project(p + d * dir);
      if (!q) return lost();
      const ReceiverTexel& r = receivers_.nearest(*q);
      if (!r.valid) return lost();
      d = glm::length(r.position - p);
    }
    const std::optional<LightSpacePoint> e = frustum_.project(p + d * dir);
    if (!e) return lost();
    const int n = receivers_.resolution();
    const float fx = e->x - 0.5f, fy = e->y - 0.5f;
    const int i0 = floorToInt<int>(fx), j0 = floorToInt<int>(fy);
    const float ax = fx - static_cast<float>(i0), ay = fy - static_cast<float>(j0);
    int index[4];
    float weight[4];
    float sum = 0.0f;
    for (int c = 0; c < 4; ++c) {
      const int i = i0 + (c & 1), j = j0 + (c >> 1);
      weight[c] = ((c & 1) ? ax : 1.0f - ax) * ((c >> 1) ? ay : 1.0f - ay);
      index[c] = -1;
      if (i < 0 || j < 0 || i >= n || j >= n || !receivers_.at(e->view, i, j).valid) continue;
      index[c] = (e->view * n + j) * n + i;
      sum += weight[c];
    }
    if (!(sum > 0.0f)) return lost();
    // Renormalised over the receiver texels, so a splat at a receiver's edge keeps its flux.
    for (int c = 0; c < 4; ++c) {
      if (index[c] >= 0 && weight[c] > 0.0f) {
        out_.push_back({static_cast<uint32_t>(index[c]), flux * (weight[c] / sum)});
      }
    }
    ++stats_.splatted;
    stats_.splattedFlux += meanComponent(flux);
  }

  void lost() { ++stats_.lost; }

  const Scene& scene_;
  const LightFrustum& frustum_;
  const ReceiverMap& receivers_;
  const CausticSettings& settings_;
  std::vector<Splat>& out_;
  CausticMapStats& stats_;
  float minFlux_ = 0.0f;
};

// Flux to irradiance, in place: a receiver texel covers Ω·d²/cos θ of its surface. Row by row
// on every thread (n texels a row, view-major).
void fluxToIrradiance(const LightFrustum& frustum, const ReceiverMap& receivers, int n,
                      uint64_t rowCount, int threads, HugePageVector<Color>& flux) {
  HugePageVector<Color>& irradiance = flux;
  parallelFor(rowCount, threads, [&](uint64_t r) {
    const int view = static_cast<int>(r) / n, j = static_cast<int>(r) % n;
    for (int i = 0; i < n; ++i) {
      const ReceiverTexel& t = receivers.at(view, i, j);
      const size_t k = static_cast<size_t>(r) * n + i;
      if (!t.valid) {
        irradiance[k] = Color(0.0f);
        continue;
      }
      const double area = frustum.texelSolidAngle(i, j) * t.distance * t.distance / t.cosine;
      irradiance[k] = flux[k] * static_cast<float>(1.0 / area);
    }
  });
}

// The settings' Gaussian blur of the irradiance: separable, over receiver texels only and not
// across depth jumps (a receiver's edge), with the weights renormalised over the texels taken.
// Each pass writes the other buffer; the result ends in irradiance.
void blurIrradiance(const ReceiverMap& receivers, int n, uint64_t rowCount, float texelSize,
                    const CausticSettings& settings, int threads,
                    HugePageVector<Color>& irradiance) {
  const int radius = settings.mapBlurRadius;
  std::vector<float> kernel(static_cast<size_t>(radius) + 1);
  for (int k = 0; k <= radius; ++k) {
    kernel[static_cast<size_t>(k)] = std::exp(-0.5f * static_cast<float>(k * k) /
                                              (settings.mapBlurSigma * settings.mapBlurSigma));
  }
  HugePageVector<Color> blurred(irradiance.size());
  const auto pass = [&](int di, int dj) {
    parallelFor(rowCount, threads, [&](uint64_t r) {
      const int view = static_cast<int>(r) / n, j = static_cast<int>(r) % n;
      for (int i = 0; i < n; ++i) {
        const ReceiverTexel& c = receivers.at(view, i, j);
        Color& out = blurred[static_cast<size_t>(r) * n + i];
        if (!c.valid) {
          out = Color(0.0f);
          continue;
        }
        const float tol = CausticMap::depthTolerance(c, texelSize);
        Color acc(0.0f);
        float wsum = 0.0f;
        for (int k = -radius; k <= radius; ++k) {
          const int ii = i + k * di, jj = j + k * dj;
          if (ii < 0 || jj < 0 || ii >= n || jj >= n) continue;
          const ReceiverTexel& t = receivers.at(view, ii, jj);
          if (!t.valid || std::abs(t.distance - c.distance) > tol * std::abs(k)) continue;
          const float w = kernel[static_cast<size_t>(std::abs(k))];
          acc += w * irradiance[(static_cast<size_t>(view) * n + jj) * n + ii];
          wsum += w;
        }
        out = acc / wsum;
      }
    });
    irradiance.swap(blurred);
  };
  pass(1, 0);
  pass(0, 1);
}

}  // namespace

CausticMapStats& CausticMapStats::operator+=(const CausticMapStats& o) {
  views += o.views;
  receiverTexels += o.receiverTexels;
  casterTexels += o.casterTexels;
  paths += o.paths;
  splatted += o.splatted;
  lost += o.lost;
  emittedFlux += o.emittedFlux;
  splattedFlux += o.splattedFlux;
  receiverSeconds += o.receiverSeconds;
  casterSeconds += o.casterSeconds;
  filterSeconds += o.filterSeconds;
  return *this;
}

float CausticMap::depthTolerance(const ReceiverTexel& t, float texelSize) {
  return t.distance * (2e-3f + 1.5f * texelSize / std::max(t.cosine, 0.1f));
}

CausticMap::CausticMap(const Scene& scene, size_t lightIndex, const CausticSettings& settings,
                       int threads)
    : frustum_(scene.lights()[lightIndex].position, scene.causticCasters(),
               settings.mapResolution) {
  if (frustum_.empty()) return;
  const PointLightDesc& light = scene.lights()[lightIndex];
  const int n = frustum_.resolution();
  const int views = static_cast<int>(frustum_.views().size());
  const size_t texels = static_cast<size_t>(views) * n * n;
  stats_.views = views;

  auto start = SteadyClock::now();
  receivers_ = std::make_unique<ReceiverMap>(scene, frustum_, threads);
  stats_.receiverTexels = receivers_->validCount();
  stats_.receiverSeconds = secondsSince(start);

  start = SteadyClock::now();
  casters_.resize(texels);
  const int rows = views * n;
  std::vector<std::vector<Splat>> rowSplats(static_cast<size_t>(rows));
  std::vector<CausticMapStats> rowStats(static_cast<size_t>(rows));
  parallelFor(static_cast<uint64_t>(rows), threads, [&](uint64_t r) {
    const int row = static_cast<int>(r);
    const int view = row / n, j = row % n;
    CausticMapStats& st = rowStats[static_cast<size_t>(row)];
    TexelTransport transport(scene, frustum_, *receivers_, settings,
                             rowSplats[static_cast<size_t>(row)], st);
    for (int i = 0; i < n; ++i) {
      const Ray ray{light.position, frustum_.direction(view, i + 0.5f, j + 0.5f)};
      HitRecord hit;
      if (!scene.intersect(ray, hit)) continue;
      const SurfaceHit s = scene.surface(ray, hit);
      if (!(s.caustic & kCastsCaustics)) continue;
      casters_[static_cast<size_t>(row) * n + i] = {s.position, s.shadingNormal, true};
      ++st.casterTexels;
      const Color flux = light.intensity * static_cast<float>(frustum_.texelSolidAngle(i, j)) *
                         falloffRelativeToInverseSquare(light.attenuation, hit.t);
      st.emittedFlux += meanComponent(flux);
      transport.start(s, ray.direction, flux);
    }
  });
  HugePageVector<Color> flux(texels, Color(0.0f));
  for (int row = 0; row < rows; ++row) {  // in texel order: the same sums for any thread count
    for (const Splat& s : rowSplats[static_cast<size_t>(row)]) flux[s.texel] += s.flux;
    stats_ += rowStats[static_cast<size_t>(row)];
  }
  stats_.casterSeconds = secondsSince(start);

  start = SteadyClock::now();
  // Row by row on every thread from here on: each row's texels depend on the rows before only
  // through what the previous step wrote, so the results are the same for any thread count.
  const uint64_t rowCount = static_cast<uint64_t>(rows);
  HugePageVector<Color>& irradiance = flux;  // converted in place
  fluxToIrradiance(frustum_, *receivers_, n, rowCount, threads, irradiance);
  const float texelSize = 2.0f * frustum_.views()[0].tanHalf / static_cast<float>(n);
  if (settings.mapBlurRadius > 0 && settings.mapBlurSigma > 0.0f) {
    blurIrradiance(*receivers_, n, rowCount, texelSize, settings, threads, irradiance);
  }
  lookup_.resize(texels);
  // The lit box row by row, then joined: a box's bounds are minima and maxima, the same in any
  // order.
  std::vector<Aabb> rowLit(static_cast<size_t>(rows));
  parallelFor(rowCount, threads, [&](uint64_t r) {
    const int view = static_cast<int>(r) / n, j = static_cast<int>(r) % n;
    for (int i = 0; i < n; ++i) {
      const ReceiverTexel& t = receivers_->at(view, i, j);
      const size_t k = static_cast<size_t>(r) * n + i;
      lookup_[k].irradiance = irradiance[k];
      if (!t.valid) continue;
      const float tolerance = depthTolerance(t, texelSize);
      lookup_[k].normal = t.normal;
      lookup_[k].distance = t.distance;
      lookup_[k].tolerance = tolerance;
      if (!isBlack(irradiance[k])) {
        rowLit[static_cast<size_t>(r)].extend(
            texelReach(frustum_, light.position, view, i, j, t.distance, tolerance));
      }
    }
  });
  for (const Aabb& box : rowLit) lit_.extend(box);
  stats_.filterSeconds = secondsSince(start);
}

bool CausticMap::locate(const Vec3& position, TexelCorners& at) const {
  // Most receiver points see no caustic: the answer there is 0, found without projecting.
  if (!lit_.contains(position)) return false;
  const std::optional<LightSpacePoint> p = frustum_.project(position);
  if (!p) return false;
  const int n = frustum_.resolution();
  const float fx = p->x - 0.5f, fy = p->y - 0.5f;
  const int i0 = floorToInt<int>(fx), j0 = floorToInt<int>(fy);
  at.ax = fx - static_cast<float>(i0);
  at.ay = fy - static_cast<float>(j0);
  at.distance = p->distance;
  const LookupTexel* view = &lookup_[static_cast<size_t>(p->view) * n * n];
  const int iLow = std::clamp(i0, 0, n - 1), iHigh = std::clamp(i0 + 1, 0, n - 1);
  const LookupTexel* rowLow = view + static_cast<size_t>(std::clamp(j0, 0, n - 1)) * n;
  const LookupTexel* rowHigh = view + static_cast<size_t>(std::clamp(j0 + 1, 0, n - 1)) * n;
  at.corners[0] = rowLow + iLow;
  at.corners[1] = rowLow + iHigh;
  at.corners[2] = rowHigh + iLow;
  at.corners[3] = rowHigh + iHigh;
  return true;
}

Color CausticMap::blend(const TexelCorners& at, const Vec3& normal) {
  // The four corners as the lanes of one vector each.
  using simd::Float4;
  const LookupTexel* const* corners = at.corners;
  // Rows (normal, distance) of the corners, transposed to lanes of each.
  Float4 nx = simd::load<Float4>(&corners[0]->normal.x);
  Float4 ny = simd::load<Float4>(&corners[1]->normal.x);
  Float4 nz = simd::load<Float4>(&corners[2]->normal.x);
  Float4 distance = simd::load<Float4>(&corners[3]->normal.x);
  simd::transpose(nx, ny, nz, distance);
  const Float4 tolerance{corners[0]->tolerance, corners[1]->tolerance, corners[2]->tolerance,
                         corners[3]->tolerance};
  // The shadow-map test: only the receiver the light sees in a texel gets its caustic (a texel
  // without one has a zero normal and fails it). The dot product in glm::dot's order.
  const Float4 dot = (Float4{normal.x, normal.x, normal.x, normal.x} * nx +
                      Float4{normal.y, normal.y, normal.y, normal.y} * ny) +
                     Float4{normal.z, normal.z, normal.z, normal.z} * nz;
  const Float4 gap = distance - Float4{at.distance, at.distance, at.distance, at.distance};
  const simd::Int4 magnitude = reinterpret_cast<simd::Int4>(gap) & 0x7fffffff;  // std::abs
  const simd::Int4 fails = (dot <= 0.0f) | (reinterpret_cast<Float4>(magnitude) > tolerance);
  // Bilinear weights, zero (+0) for the corners that fail. The sums below start at +0 and add
  // products of non-negative numbers, so adding a +0 leaves them exactly as skipping it would.
  const float ax = at.ax, ay = at.ay;
  const Float4 weights = simd::select(
      fails, Float4{}, Float4{1.0f - ax, ax, 1.0f - ax, ax} * Float4{1.0f - ay, 1.0f - ay, ay, ay});
  // Each texel's irradiance as lanes 1–3 of its second half (lane 0 holds the tolerance); a
  // failing corner's product is left out whatever its texel holds.
  Float4 acc{};
  for (int c = 0; c < 4; ++c) {
    const Float4 w{weights[c], weights[c], weights[c], weights[c]};
    const simd::Int4 left = {fails[c], fails[c], fails[c], fails[c]};
    acc += simd::select(left, Float4{}, w * simd::load<Float4>(&corners[c]->tolerance));
  }
  const float wsum = ((weights[0] + weights[1]) + weights[2]) + weights[3];
  if (!(wsum > 1e-4f)) return Color(0.0f);
  const Float4 average = acc / Float4{wsum, wsum, wsum, wsum};  // one division for the three
  return Color(average[1], average[2], average[3]);
}

Color CausticMap::irradiance(const Vec3& position, const Vec3& normal) const {
  TexelCorners at;
  return locate(position, at) ? blend(at, normal) : Color(0.0f);
}

void CausticMap::addIrradiance(const SurfaceHit* const* points, int count, Color* sums) const {
  constexpr int kBatch = 8;
  for (int first = 0; first < count; first += kBatch) {
    const int n = std::min(kBatch, count - first);
    TexelCorners at[kBatch];
    bool found[kBatch];
    for (int i = 0; i < n; ++i) found[i] = locate(points[first + i]->position, at[i]);
    for (int i = 0; i < n; ++i) {
      sums[first + i] += found[i] ? blend(at[i], points[first + i]->geometricNormal) : Color(0.0f);
    }
  }
}

}  // namespace prism
