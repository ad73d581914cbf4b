#include "master/analysis/SweepPlan.h"

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "scene/SettingLimits.h"

namespace prism {
namespace {

std::vector<uint64_t> orDefault(const std::vector<uint64_t>& given,
                                std::vector<uint64_t> defaults) {
  return given.empty() ? defaults : given;
}

// The same bounds as the scene file and the command line.
void requireRange(SweepFamily family, uint64_t value, const SettingLimit& limit) {
  const uint64_t low = static_cast<uint64_t>(limit.min), high = static_cast<uint64_t>(limit.max);
  if (value < low || value > high) {
    throw std::invalid_argument(std::string("sweep ") + familyName(family) + ": " +
                                std::to_string(value) + " is outside " + std::to_string(low) +
                                ".." + std::to_string(high));
  }
}

// The method each family's renders use, indexed by SweepFamily.
constexpr const char* kFamilyMethod[] = {
    "photon map",
    "photon map",
    "photon map (automatic k)",
    "progressive photon map",
    "caustic map",
    "caustic map",
    "caustic map",
    "scene's method",
};

static_assert(std::size(kFamilyMethod) == static_cast<size_t>(SweepFamily::Samples) + 1);

}  // namespace

const char* familyName(SweepFamily f) {
  return kSweepFamilyNames.nameOf(f).data();  // a literal: null-terminated
}

const char* familyMethod(SweepFamily f) {
  return kFamilyMethod[static_cast<size_t>(f)];
}

std::vector<SweepFamily> defaultSweepFamilies() {
  return {SweepFamily::Photons,    SweepFamily::Gather, SweepFamily::Passes,
          SweepFamily::Resolution, SweepFamily::Steps,  SweepFamily::Blur};
}

std::vector<SweepPoint> planSweep(const std::vector<SweepFamily>& families,
                                  const SweepValues& values, const SceneDescription& scene) {
  std::vector<SweepPoint> points;
  const CausticSettings& base = scene.caustics;
  // Photon mapping keeps the scene's budget where the family does not sweep it, or a common
  // 200 000 when the scene does not use photon mapping at all.
  const uint64_t photons = base.method == CausticMethod::PhotonMap ? base.photons : 200000;
  for (const SweepFamily family : families) {
    SweepPoint point;
    point.family = family;
    point.caustics = base;
    point.caustics.progressive = false;
    point.caustics.timeBudgetSeconds = 0.0;
    point.samplesPerPixel = scene.render.samplesPerPixel;
    std::vector<uint64_t> list;
    switch (family) {
      case SweepFamily::Photons:
        list = orDefault(values.photons, {25000, 50000, 100000, 200000, 400000, 800000, 1600000});
        point.caustics.method = CausticMethod::PhotonMap;
        break;
      case SweepFamily::Gather:
        list = orDefault(values.gather, {10, 25, 50, 100, 200, 400});
        point.caustics.method = CausticMethod::PhotonMap;
        point.caustics.photons = photons;
        point.caustics.automaticGather = false;
        break;
      case SweepFamily::AutoGather:
        list = orDefault(values.autoGather, {25, 100, 400, 1600});
        point.caustics.method = CausticMethod::PhotonMap;
        point.caustics.photons = photons;
        point.caustics.automaticGather = true;
        break;
      case SweepFamily::Passes:
        list = orDefault(values.passes, {1, 2, 4, 8, 16, 32});
        point.caustics.method = CausticMethod::PhotonMap;
        point.caustics.progressive = true;
        point.caustics.photons = photons;
        break;
      case SweepFamily::Resolution:
        list = orDefault(values.resolution, {64, 128, 256, 512, 1024});
        point.caustics.method = CausticMethod::CausticMap;
        break;
      case SweepFamily::Steps:
        list = orDefault(values.steps, {1, 2, 3, 5, 10, 20});
        point.caustics.method = CausticMethod::CausticMap;
        break;
      case SweepFamily::Blur:
        list = orDefault(values.blur, {0, 1, 2, 4, 8});
        point.caustics.method = CausticMethod::CausticMap;
        break;
      case SweepFamily::Samples:
        list = orDefault(values.samples, {1, 2, 4, 8, 16});
        break;
    }
    for (const uint64_t value : list) {
      SweepPoint p = point;
      p.value = value;
      switch (family) {
        case SweepFamily::Photons:
          requireRange(family, value, limits::kPhotons);
          p.caustics.photons = value;
          break;
        case SweepFamily::Gather:
          requireRange(family, value, limits::kGather);
          p.caustics.gather = static_cast<int>(value);
          break;
        case SweepFamily::AutoGather:  // the noise whose largest k is value
          requireRange(family, value, limits::kGather);
          p.caustics.gather = static_cast<int>(value);
          p.caustics.gatherNoise = static_cast<float>(1.0 / std::sqrt(static_cast<double>(value)));
          break;
        case SweepFamily::Passes:
          requireRange(family, value, limits::kPasses);
          p.caustics.passes = static_cast<int>(value);
          break;
        case SweepFamily::Resolution:
          requireRange(family, value, limits::kMapResolution);
          p.caustics.mapResolution = static_cast<int>(value);
          break;
        case SweepFamily::Steps:
          requireRange(family, value, limits::kMapSteps);
          p.caustics.mapSteps = static_cast<int>(value);
          break;
        case SweepFamily::Blur:
          requireRange(family, value, limits::kMapBlurRadius);
          p.caustics.mapBlurRadius = static_cast<int>(value);
          p.caustics.mapBlurSigma = 0.5f * static_cast<float>(value);
          break;
        case SweepFamily::Samples:
          requireRange(family, value, limits::kSamples);
          p.samplesPerPixel = static_cast<int>(value);
          break;
      }
      points.push_back(p);
    }
  }
  return points;
}

}  // namespace prism
