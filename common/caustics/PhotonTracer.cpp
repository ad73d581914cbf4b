#include "caustics/PhotonTracer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "math/LowDiscrepancy.h"
#include "math/Random.h"
#include "shading/LightFalloff.h"
#include "shading/MaterialEval.h"
#include "shading/SpecularSplit.h"
#include "util/Parallel.h"

namespace prism {
namespace {

// Keeps photon streams apart from the pixel streams, which are keyed by (x, y).
constexpr uint64_t kPhotonStreamBase = 0x5048'4f54'0000'0000ULL;  // "PHOT"

// The Halton bases of the stratified roulette decisions: coprime to 2, so that the photons of a
// cell within one of its (0, 2)-sequence's boxes (indices in one class mod 2^m) spread over them.
constexpr uint32_t kRouletteBases[kStratifiedRoulette] = {3, 5, 7, 11};

// One cell's rotation of its points: two for the position, then one per roulette decision.
struct CellRotation {
  float position[2];
  float roulette[kStratifiedRoulette];
};

// The integer coprime to `cells` nearest cells · (√5 − 1)/2: stepping by it visits every cell once
// a round, consecutive steps far apart and any run of them spread evenly (Weyl's golden-ratio
// sequence, as integers).
uint64_t goldenCellStride(uint64_t cells) {
  if (cells <= 2) return 1;
  const auto stride = static_cast<uint64_t>(std::llround(0.6180339887498949 * cells));
  for (uint64_t d = 0;; ++d) {
    if (stride + d < cells && std::gcd(stride + d, cells) == 1) return stride + d;
    if (d < stride && std::gcd(stride - d, cells) == 1) return stride - d;
  }
}

// Pass 0 (every classic render) takes stream kPhotonStreamBase − 1, later passes the streams
// below it, apart from the photons' own (kPhotonStreamBase + pass).
CellRotation cellRotation(uint64_t seed, size_t light, uint64_t cell, uint32_t pass) {
  Pcg32 rng = Pcg32::forKey(seed, (static_cast<uint64_t>(light) << 32) | cell,
                            kPhotonStreamBase - 1 - pass);
  CellRotation r;
  for (float& s : r.position) s = rng.nextFloat();
  for (float& s : r.roulette) s = rng.nextFloat();
  return r;
}

}  // namespace

PhotonTracer::PhotonTracer(const Scene& scene, uint64_t photons, int maxBounces)
    : scene_(scene), maxBounces_(maxBounces) {
  const std::vector<CasterBounds>& casters = scene.causticCasters();
  if (casters.empty() || photons == 0) return;
  std::vector<double> flux;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const PointLightDesc& light = scene.lights()[i];
    ProjectionMap map(light.position, casters);
    const double f = map.coveredSolidAngle() * std::max(0.0f, meanComponent(light.intensity));
    if (map.empty() || !(f > 0.0)) continue;
    plans_.push_back({i, std::move(map), 0, 0, Color(0.0f)});
    flux.push_back(f);
  }
  if (plans_.empty()) return;

  // Photon counts in proportion to flux; the remainder goes to the largest fractions.
  double totalFlux = 0.0;
  for (double f : flux) totalFlux += f;
  std::vector<std::pair<double, size_t>> fractions;
  uint64_t assigned = 0;
  for (size_t j = 0; j < plans_.size(); ++j) {
    const double exact = static_cast<double>(photons) * flux[j] / totalFlux;
    plans_[j].count = static_cast<uint64_t>(std::floor(exact));
    assigned += plans_[j].count;
    fractions.push_back({exact - std::floor(exact), j});
  }
  std::stable_sort(fractions.begin(), fractions.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; assigned < photons; ++i, ++assigned) ++plans_[fractions[i].second].count;

  uint64_t first = 0;
  for (PhotonLightPlan& plan : plans_) {
    plan.cellStride = goldenCellStride(plan.map.coveredCellCount());
    plan.first = first;
    first += plan.count;
    if (plan.count > 0) {
      const PointLightDesc& light = scene.lights()[plan.light];
      plan.powerPerPhoton = light.intensity * static_cast<float>(plan.map.coveredSolidAngle() /
                                                                 static_cast<double>(plan.count));
    }
  }
  total_ = first;
}

PhotonTraceStats PhotonTracer::trace(uint32_t pass, uint64_t first, uint64_t count,
                                     std::vector<Photon>& out) const {
  PhotonTraceStats stats;
  const uint64_t end = std::min(first + count, total_);
  auto plan = plans_.begin();
  for (uint64_t i = first; i < end; ++i) {
    while (i >= plan->first + plan->count) ++plan;
    tracePhoton(pass, i, *plan, out, stats);
  }
  return stats;
}

void PhotonTracer::tracePhoton(uint32_t pass, uint64_t index, const PhotonLightPlan& plan,
                               std::vector<Photon>& out, PhotonTraceStats& stats) const {
  ++stats.emitted;
  Pcg32 rng = Pcg32::forKey(scene_.settings().seed, index, kPhotonStreamBase + pass);
  const PointLightDesc& light = scene_.lights()[plan.light];
  // Round the marked cells in turn, continued from pass to pass (a cell that got a photon more
  // than others in one pass does not get it in every pass), then along the cell's own
  // (0, 2)-sequence from its start in each pass, rotated afresh each pass, so that the passes'
  // errors are independent and average away (see PhotonTracer.h).
  const uint64_t passStart = static_cast<uint64_t>(pass) * plan.count;
  const uint64_t sequenceIndex = passStart + (index - plan.first);
  const uint64_t cells = plan.map.coveredCellCount();
  const uint64_t positionInRound = sequenceIndex % cells;
  const uint64_t cell = positionInRound * plan.cellStride % cells;  // cells < 2^32
  // The cell's photons in earlier passes: the rounds that reached its position before passStart.
  const uint64_t earlier =
      passStart > positionInRound ? (passStart - positionInRound + cells - 1) / cells : 0;
  const uint64_t inCell = sequenceIndex / cells - earlier;
  const CellRotation rotation = cellRotation(scene_.settings().seed, plan.light, cell, pass);
  const float u1 = rotateUnit(radicalInverse(2, inCell), rotation.position[0]);
  const float u2 = rotateUnit(sobolSecond(inCell), rotation.position[1]);
  Ray ray{light.position, plan.map.sampleCell(cell, u1, u2)};
  Color power = plan.powerPerPhoton;

  int decisions = 0;  // roulette decisions taken so far
  for (int bounce = 0;; ++bounce) {
    HitRecord hit;
    if (!scene_.intersect(ray, hit)) {
      ++(bounce == 0 ? stats.missed : stats.absorbed);
      return;
    }
    if (bounce == 0) power *= falloffRelativeToInverseSquare(light.attenuation, hit.t);
    const SurfaceHit s = scene_.surface(ray, hit);
    if (bounce > 0 && (s.caustic & kReceivesCaustics)) {
      Photon photon;
      photon.position = s.position;
      photon.power = power;
      photon.setDirection(ray.direction);
      out.push_back(photon);
      ++stats.stored;
    }
    if (!(s.caustic & kCastsCaustics) || bounce >= maxBounces_) {  // bounce 0: not a caster
      ++(bounce == 0 ? stats.missed : stats.absorbed);
      return;
    }
    const MaterialDesc& m = scene_.materials()[s.material];
    const SpecularSplit split = splitSpecular(m, s, ray.direction);
    float reflectP = std::max(0.0f, meanComponent(split.reflectWeight));
    float transmitP = split.refracted ? std::max(0.0f, meanComponent(split.transmitWeight)) : 0.0f;
    const float sum = reflectP + transmitP;
    if (sum > 1.0f) {
      reflectP /= sum;
      transmitP /= sum;
    }
    const float u = decisions < kStratifiedRoulette
                        ? rotateUnit(radicalInverse(kRouletteBases[decisions], inCell),
                                     rotation.roulette[decisions])
                        : rng.nextFloat();
    ++decisions;
    Vec3 direction;
    if (u < reflectP) {
      power *= split.reflectWeight / reflectP;
      direction = reflectedDirection(s, ray.direction);
    } else if (u < reflectP + transmitP) {
      power *= split.transmitWeight / transmitP;
      direction = *split.refracted;
    } else {
      ++stats.absorbed;  // by roulette, at a caster
      return;
    }
    ray = Ray{s.rayOrigin(direction), direction};
  }
}

std::vector<Photon> tracePhotons(const PhotonTracer& tracer, uint32_t pass, uint64_t first,
                                 uint64_t count, int threads, PhotonTraceStats* stats,
                                 const std::atomic<bool>* cancel) {
  constexpr uint64_t kChunk = 4096;
  const uint64_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<std::vector<Photon>> results(chunks);
  std::vector<PhotonTraceStats> chunkStats(chunks);
  parallelFor(chunks, threads, [&](uint64_t c) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    const uint64_t begin = first + c * kChunk;
    chunkStats[c] = tracer.trace(pass, begin, std::min(kChunk, first + count - begin), results[c]);
  });

  size_t total = 0;
  for (const auto& r : results) total += r.size();
  std::vector<Photon> photons;
  photons.reserve(total);
  for (uint64_t c = 0; c < chunks; ++c) {
    photons.insert(photons.end(), results[c].begin(), results[c].end());
    if (stats) *stats += chunkStats[c];
  }
  return photons;
}

}  // namespace prism
