#include "master/SweepPlan.h"

#include <iterator>
#include <stdexcept>
#include <string>

namespace prism {
namespace {

std::vector<uint64_t> orDefault(const std::vector<uint64_t>& given,
                                std::vector<uint64_t> defaults) {
  return given.empty() ? defaults : given;
}

void requireRange(SweepFamily family, uint64_t value, uint64_t low, uint64_t high) {
  if (value < low || value > high) {
    throw std::invalid_argument(std::string("sweep ") + familyName(family) + ": " +
                                std::to_string(value) + " is outside " + std::to_string(low) +
                                ".." + std::to_string(high));
  }
}

struct FamilyText {
  const char* name;    // command line and CSV
  const char* method;  // the method its renders use
};

// Indexed by SweepFamily.
constexpr FamilyText kFamilyText[] = {
    {"photons", "photon map"},     {"k", "photon map"},      {"passes", "progressive photon map"},
    {"resolution", "caustic map"}, {"steps", "caustic map"}, {"blur", "caustic map"},
    {"spp", "scene's method"},
};

static_assert(std::size(kFamilyText) == static_cast<size_t>(SweepFamily::Samples) + 1);

const FamilyText& textOf(SweepFamily f) {
  return kFamilyText[static_cast<size_t>(f)];
}

}  // namespace

const char* familyName(SweepFamily f) {
  return textOf(f).name;
}

const char* familyMethod(SweepFamily f) {
  return textOf(f).method;
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
          requireRange(family, value, 1, uint64_t{1} << 40);
          p.caustics.photons = value;
          break;
        case SweepFamily::Gather:
          requireRange(family, value, 1, 100000);
          p.caustics.gather = static_cast<int>(value);
          break;
        case SweepFamily::Passes:
          requireRange(family, value, 1, 1 << 20);
          p.caustics.passes = static_cast<int>(value);
          break;
        case SweepFamily::Resolution:
          requireRange(family, value, kMinCausticMapResolution, kMaxCausticMapResolution);
          p.caustics.mapResolution = static_cast<int>(value);
          break;
        case SweepFamily::Steps:
          requireRange(family, value, 1, kMaxCausticMapSteps);
          p.caustics.mapSteps = static_cast<int>(value);
          break;
        case SweepFamily::Blur:
          requireRange(family, value, 0, kMaxCausticMapBlurRadius);
          p.caustics.mapBlurRadius = static_cast<int>(value);
          p.caustics.mapBlurSigma = 0.5f * static_cast<float>(value);
          break;
        case SweepFamily::Samples:
          requireRange(family, value, 1, 1 << 16);
          p.samplesPerPixel = static_cast<int>(value);
          break;
      }
      points.push_back(p);
    }
  }
  return points;
}

}  // namespace prism
