// What `prism sweep` renders: one family of points per caustic method and parameter, each point
// the scene's own settings with that one parameter changed. Families:
//   photons     photon map, k-NN gather: photons per pass
//   k           photon map: photons gathered per estimate
//   autok       photon map, automatic k (gather: auto): the largest k, from the target noise
//   passes      progressive photon map: passes (one run, scored after each listed pass)
//   resolution  caustic map: texels per side of each light-space view
//   steps       caustic map: iterations of the receiver-distance estimate
//   blur        caustic map: Gaussian blur half-width in texels (σ = half of it)
//   spp         the scene's own method: samples per pixel
#pragma once

#include <string>
#include <vector>

#include "scene/SceneDescription.h"
#include "scene/SettingNames.h"

namespace prism {

enum class SweepFamily { Photons, Gather, AutoGather, Passes, Resolution, Steps, Blur, Samples };

// "photons", "k", ...: the names the command line and the CSV use.
inline constexpr NamedValue<SweepFamily> kSweepFamilyList[] = {
    {"photons", SweepFamily::Photons},
    {"k", SweepFamily::Gather},
    {"autok", SweepFamily::AutoGather},
    {"passes", SweepFamily::Passes},
    {"resolution", SweepFamily::Resolution},
    {"steps", SweepFamily::Steps},
    {"blur", SweepFamily::Blur},
    {"spp", SweepFamily::Samples}};
inline constexpr NameTable<SweepFamily> kSweepFamilyNames{kSweepFamilyList};

const char* familyName(SweepFamily family);
// The method a family's renders use, for the CSV and the chart ("photon map", ...).
const char* familyMethod(SweepFamily family);

// The values each family sweeps; empty: the family's defaults.
struct SweepValues {
  std::vector<uint64_t> photons, gather, autoGather, passes, resolution, steps, blur, samples;
};

struct SweepPoint {
  SweepFamily family = SweepFamily::Photons;
  uint64_t value = 0;
  CausticSettings caustics;  // the scene's, with this point's parameter set
  int samplesPerPixel = 1;
};

// The families' points for this scene, in family order and rising value. Throws
// std::invalid_argument for a value the method does not accept (e.g. a resolution of 8).
std::vector<SweepPoint> planSweep(const std::vector<SweepFamily>& families,
                                  const SweepValues& values, const SceneDescription& scene);

// The default families: one per parameter that sets a method's cost (photons, passes,
// resolution), plus k, steps and blur, which trade accuracy at about the same cost.
std::vector<SweepFamily> defaultSweepFamilies();

}  // namespace prism
