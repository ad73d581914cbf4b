// What a command that renders takes from the command line: the scene, the settings that
// override the scene's own, and how the work is distributed (master/commands/Cli.cpp fills it).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cluster/DistributionOptions.h"
#include "master/dispatch/GeometryShare.h"
#include "scene/SceneDescription.h"

namespace prism {

struct RenderOptions {
  std::string scenePath;
  std::string outputPath;  // empty: <scene name>.png in the current folder
  // Scene settings given on the command line (master/commands/Cli.cpp binds each option straight to
  // its field, bounded and named as in scene files); applyOverrides writes the given ones over the
  // scene's. Unset: the scene's value stands.
  std::optional<int> width, height, samples, maxDepth;
  std::optional<uint64_t> seed;
  std::optional<float> exposure;
  std::optional<TriangleTest> triangleTest;
  // The kernels' instruction set: Auto (the best every rank runs) or one forced with --isa.
  InstructionSet instructionSet = InstructionSet::Auto;
  // The camera's position and look-at point (what the viewer prints for the view it saved).
  std::optional<Vec3> cameraPosition, lookAt;
  // Caustics: override the scene's `caustics` section.
  std::optional<CausticMethod> causticMethod;
  std::optional<uint64_t> photons;
  std::optional<int> gather, passes;
  std::optional<bool> progressive;
  std::optional<float> gatherRadius;  // k-NN cap, or the first progressive radius
  std::optional<float> gatherNoise;   // automatic k per photon (gather: auto) for this noise
  std::optional<double> timeBudget;
  std::string photonImagePath;  // debug: where the stored photons landed
  std::optional<int> mapResolution, mapSteps, mapBlurRadius;  // caustic mapping
  std::optional<float> mapBlurSigma;
  std::optional<CausticMapPaths> mapPaths;
  std::string causticMapDebugPrefix;    // debug: the caustic maps as images
  bool quiet = false;                   // no progress bar and no summary
  bool overwrite = false;               // replace a finished frame at the output path
  bool savePartial = false;             // interrupted: write the finished tiles (PartialFrame.h)
  std::optional<uint64_t> memoryLimit;  // bytes a run may plan to use; default: physical memory
  // MPI runs: whether rank 0 broadcasts the geometry it built or every rank builds its own.
  GeometryShareMode geometryShare = GeometryShareMode::Auto;
  // Threads, tiles, and (MPI runs) how tiles are handed out and when a slave is given up on.
  DistributionOptions distribution;
  std::string statusFile;  // testing only: "stage done total", rewritten as tiles finish
};

// Applies the overrides the user gave to the scene's own settings.
void applyOverrides(const RenderOptions& options, RenderSettings& settings);
void applyOverrides(const RenderOptions& options, CausticSettings& caustics);
void applyOverrides(const RenderOptions& options, CameraDesc& camera);

// "X,Y,Z" as three floats (each as printed with 9 significant digits comes back exactly; the
// viewer prints a view so: master/live/CameraOptionsText.h). Throws std::invalid_argument.
Vec3 parseVec3(const std::string& text);

}  // namespace prism
