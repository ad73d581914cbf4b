// The allowed range of every bounded numeric setting, in one place: the YAML and NFF parsers,
// the scene codec (through validate(), SceneValidation.h), the command line and `prism sweep`
// all check against these, so a value one accepts the others accept too. Each limit carries its
// scene-file key and its command-line option so every refusal can name both.
#pragma once

#include <cstdint>
#include <string_view>

namespace prism {

struct SettingLimit {
  std::string_view key;     // in scene files ("max_depth")
  std::string_view option;  // on the command line ("--max-depth"); empty when there is none
  int64_t min;
  int64_t max;

  bool allows(int64_t value) const { return value >= min && value <= max; }
};

namespace limits {

// Image sides: 2^20 keeps pixel indices far from overflow; memory refuses large frames first
// (master/frame/ResourceCheck.h).
inline constexpr SettingLimit kWidth{"width", "--width", 1, 1 << 20};
inline constexpr SettingLimit kHeight{"height", "--height", 1, 1 << 20};
// 65536 samples per pixel take days per frame at any resolution.
inline constexpr SettingLimit kSamples{"samples", "--spp", 1, 1 << 16};
// Deeper recursion risks the tracer's stack and never changes an image visibly.
inline constexpr SettingLimit kMaxDepth{"max_depth", "--max-depth", 0, 256};

// 2^40 photons: photon indices and counts stay exact; memory refuses far fewer first.
inline constexpr SettingLimit kPhotons{"photons", "--photons", 1, int64_t{1} << 40};
inline constexpr SettingLimit kGather{"gather", "--gather", 1, 100000};
// gather: auto's target noise: 1/√100000, so that its largest k stays within kGather.
inline constexpr float kSmallestGatherNoise = 0.0032f;
inline constexpr SettingLimit kMaxBounces{"max_bounces", "", 1, 256};
inline constexpr SettingLimit kPasses{"passes", "--passes", 1, 1 << 20};
inline constexpr SettingLimit kMapResolution{"map_resolution", "--map-resolution", 16, 4096};
inline constexpr SettingLimit kMapSteps{"map_steps", "--map-steps", 1, 64};
inline constexpr SettingLimit kMapBlurRadius{"map_blur_radius", "--map-blur-radius", 0, 64};

}  // namespace limits
}  // namespace prism
