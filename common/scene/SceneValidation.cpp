#include "scene/SceneValidation.h"

#include <cmath>
#include <string>

#include "scene/SettingLimits.h"

namespace prism {
namespace {

[[noreturn]] void refuse(std::string_view section, std::string_view key, std::string_view option,
                         const std::string& problem) {
  std::string message = std::string(section) + " setting '" + std::string(key) + "' " + problem;
  if (!option.empty()) message += " (" + std::string(option) + " on the command line)";
  throw SettingError(message);
}

void check(std::string_view section, const SettingLimit& limit, int64_t value) {
  if (value < limit.min) {
    refuse(section, limit.key, limit.option,
           "must be at least " + std::to_string(limit.min) + ", found " + std::to_string(value));
  }
  if (value > limit.max) {
    refuse(section, limit.key, limit.option,
           "must be at most " + std::to_string(limit.max) + ", found " + std::to_string(value));
  }
}

void check(std::string_view section, const SettingLimit& limit, uint64_t value) {
  if (value > static_cast<uint64_t>(limit.max)) {
    refuse(section, limit.key, limit.option,
           "must be at most " + std::to_string(limit.max) + ", found " + std::to_string(value));
  }
  check(section, limit, static_cast<int64_t>(value));
}

// Real-valued settings: finite and not below zero (or above it, when positive is asked for).
void checkReal(std::string_view section, std::string_view key, std::string_view option,
               double value, bool positive) {
  if (!std::isfinite(value)) refuse(section, key, option, "must be finite");
  if (positive && !(value > 0.0)) {
    refuse(section, key, option, "must be greater than 0, found " + std::to_string(value));
  }
  if (value < 0.0)
    refuse(section, key, option, "must not be negative, found " + std::to_string(value));
}

}  // namespace

void validate(const RenderSettings& s) {
  constexpr std::string_view kRender = "render";
  check(kRender, limits::kWidth, int64_t{s.width});
  check(kRender, limits::kHeight, int64_t{s.height});
  check(kRender, limits::kSamples, int64_t{s.samplesPerPixel});
  check(kRender, limits::kMaxDepth, int64_t{s.maxDepth});
  checkReal(kRender, "min_contribution", "", s.minContribution, false);
  checkReal(kRender, "exposure", "--exposure", s.exposure, true);
}

void validate(const CausticSettings& c) {
  constexpr std::string_view kCaustics = "caustics";
  check(kCaustics, limits::kPhotons, c.photons);
  check(kCaustics, limits::kGather, int64_t{c.gather});
  check(kCaustics, limits::kMaxBounces, int64_t{c.maxBounces});
  check(kCaustics, limits::kPasses, int64_t{c.passes});
  check(kCaustics, limits::kMapResolution, int64_t{c.mapResolution});
  check(kCaustics, limits::kMapSteps, int64_t{c.mapSteps});
  check(kCaustics, limits::kMapBlurRadius, int64_t{c.mapBlurRadius});
  checkReal(kCaustics, "max_radius", "--gather-radius", c.maxRadius, false);
  checkReal(kCaustics, "radius", "--gather-radius", c.radius, false);
  checkReal(kCaustics, "time_budget", "--time-budget", c.timeBudgetSeconds, false);
  checkReal(kCaustics, "map_blur_sigma", "--map-blur-sigma", c.mapBlurSigma, false);
  // noise n asks for up to ⌈1/n²⌉ photons per estimate: at most the largest gather.
  if (!(c.gatherNoise >= limits::kSmallestGatherNoise && c.gatherNoise <= 1.0f)) {
    refuse(kCaustics, "noise", "--gather-noise",
           "must lie between " + std::to_string(limits::kSmallestGatherNoise) + " and 1, found " +
               std::to_string(c.gatherNoise));
  }
  if (!(c.alpha > 0.0f && c.alpha < 1.0f)) {
    refuse(kCaustics, "alpha", "",
           "must lie strictly between 0 and 1, found " + std::to_string(c.alpha));
  }
}

void validate(const SceneDescription& d) {
  validate(d.render);
  validate(d.caustics);
}

}  // namespace prism
