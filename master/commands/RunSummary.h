// The closing summary of a render: what was rendered, how long each stage took, rays traced
// and throughput, and where the image went.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "scene/Scene.h"

namespace prism {

struct RunSummary {
  std::string scenePath;
  std::string outputPath;
  RenderSettings settings;
  SceneBuildStats sceneStats;
  size_t lightCount = 0;
  std::vector<std::string> sceneNotes;  // SceneDescription::notes: choices made for the user
  const FrameResult* frame = nullptr;
  const CausticRunStats* caustics = nullptr;
  Schedule schedule = Schedule::Dynamic;
  double parseSeconds = 0.0;
  double broadcastSeconds = 0.0;  // MPI runs only
  size_t broadcastBytes = 0;
  std::string geometryShare;  // MPI runs: GeometrySharePlan::describe()
  double buildSeconds = 0.0;
  std::string instructionSet;  // JobInstructionSet::describe(): the kernels' set, and why
  double writeSeconds = 0.0;
  double totalSeconds = 0.0;
  // From the run's start to the first finished tile (what a big scene's set-up costs a user).
  std::optional<double> firstTileSeconds;
};

void printRunSummary(const RunSummary& summary, std::ostream& out);

// "12.3 M", "456 k", "789": counts for humans.
std::string formatCount(double count);

}  // namespace prism
