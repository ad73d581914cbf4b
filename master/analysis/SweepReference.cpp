#include "master/analysis/SweepReference.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "caustics/MirrorCausticEstimator.h"
#include "image/ImageIo.h"
#include "master/frame/CausticPasses.h"
#include "util/AtomicFile.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

using Progress = std::function<void(const std::string&, size_t, size_t)>;

FrameOptions frameOptions(int threads, const Progress& progress, const std::string& label) {
  FrameOptions o;
  o.distribution.threads = threads;
  if (progress) o.progress = [&progress, label](size_t d, size_t t) { progress(label, d, t); };
  return o;
}

SceneDescription withoutCaustics(SceneDescription d) {
  d.caustics.method = CausticMethod::None;
  return d;
}

SceneDescription progressiveSettings(SceneDescription d, const ReferenceRequest& r) {
  d.caustics.method = CausticMethod::PhotonMap;
  d.caustics.progressive = true;
  d.caustics.passes = r.passes;
  d.caustics.photons = r.photons;
  d.caustics.timeBudgetSeconds = 0.0;
  d.caustics.radius = 0.0f;
  d.caustics.gather = r.k;
  d.caustics.automaticGather = false;  // the reference's own k, whatever the scene says
  return d;
}

// The cache key: the scene with the reference's settings, as the wire carries it (geometry,
// materials, lights, camera, render and caustic settings), and the format of this cache.
std::string cacheKey(const SceneDescription& d) {
  std::vector<uint8_t> bytes = wire::encodeScene(d);
  const std::string tag = "prism sweep reference 1";
  bytes.insert(bytes.end(), tag.begin(), tag.end());
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(wire::fnv1a64(bytes.data(), bytes.size())));
  return hex;
}

const char* kConvergenceHeader = "passes,seconds,region_rel_rmse_vs_final,image_rel_rmse_vs_final";

bool readCache(const std::string& stem, const std::string& key, SweepReference& ref) {
  std::ifstream csv(stem + ".csv");
  std::string line;
  if (!csv || !std::getline(csv, line) || line != "# key " + key) return false;
  if (!std::filesystem::exists(stem + ".exr")) return false;
  std::getline(csv, line);  // the description
  ref.description = line.size() > 2 ? line.substr(2) : "";
  std::getline(csv, line);  // the header
  while (std::getline(csv, line)) {
    ReferenceConvergence c;
    if (std::sscanf(line.c_str(), "%d,%lf,%lf,%lf", &c.passes, &c.seconds, &c.regionRelRmse,
                    &c.imageRelRmse) == 4) {
      ref.convergence.push_back(c);
    }
  }
  ref.image = readImage(stem + ".exr");
  return true;
}

void writeCache(const std::string& stem, const std::string& key, const SweepReference& ref) {
  writeImage(ref.image, stem + ".exr");
  writeFileAtomically(stem + ".csv", [&](std::ostream& csv) {
    csv << "# key " << key << "\n# " << ref.description << "\n" << kConvergenceHeader << "\n";
    for (const ReferenceConvergence& c : ref.convergence) {
      char row[160];
      std::snprintf(row, sizeof row, "%d,%.4f,%.6g,%.6g\n", c.passes, c.seconds, c.regionRelRmse,
                    c.imageRelRmse);
      csv << row;
    }
  });
}

void renderProgressive(const SceneDescription& d, const ReferenceRequest& r,
                       const Progress& progress, SweepReference& ref) {
  const SceneDescription settings = progressiveSettings(d, r);
  const Scene scene(settings);
  // Snapshots at 1/16, 1/8, 1/4 and 1/2 of the passes, scored once the final image is known.
  std::vector<std::pair<ReferenceConvergence, ImageRgb>> snapshots;
  const auto start = SteadyClock::now();
  const ProgressiveSnapshot keep = [&](int passes, const ImageRgb& image) {
    for (int part = 16; part >= 2; part /= 2) {
      if (passes * part == r.passes) {
        ReferenceConvergence c;
        c.passes = passes;
        c.seconds = secondsSince(start);
        snapshots.emplace_back(c, image);
      }
    }
  };
  const PassProgress passProgress = [&](const std::string& label, size_t done, size_t total) {
    if (progress) progress("reference " + label, done, total);
  };
  const CausticFrame frame =
      renderWithCaustics(scene, frameOptions(r.threads, {}, ""), passProgress, keep);
  ref.image = frame.image;
  ref.region = causticMask(ref.image, ref.base);
  for (auto& [c, image] : snapshots) {
    c.regionRelRmse = imageError(image, ref.image, {}, ref.region).relRmse;
    c.imageRelRmse = imageError(image, ref.image).relRmse;
    ref.convergence.push_back(c);
  }
  char text[200];
  std::snprintf(text, sizeof text,
                "progressive photon map, %d passes x %llu photons, first radius from k = %d "
                "(%.0f s)",
                frame.caustics.passes,
                static_cast<unsigned long long>(frame.caustics.photonsPerPass), r.k,
                secondsSince(start));
  ref.description = text;
}

}  // namespace

ImageRgb renderWithoutCaustics(const SceneDescription& d, int threads) {
  const Scene scene(withoutCaustics(d));
  return renderFrame(scene, frameOptions(threads, {}, "")).image;
}

SweepReference makeSweepReference(const SceneDescription& d, const ReferenceRequest& r,
                                  const Progress& progress) {
  SweepReference ref;
  if (progress) progress("frame without caustics", 0, 1);
  ref.base = renderWithoutCaustics(d, r.threads);
  std::string kind = r.spec;
  if (kind == "auto" || kind == "analytic") {
    const Scene scene(withoutCaustics(d));
    try {
      auto estimator = std::make_shared<const MirrorCausticEstimator>(d, scene);
      FrameOptions o = frameOptions(r.threads, progress, "analytic reference");
      o.pass = RenderPass::withPhotons(0, true, estimator);
      ref.image = renderFrame(scene, o).image;
      ref.kind = "analytic";
      ref.description = "analytic (mirror images of the lights, " +
                        std::to_string(estimator->facetCount()) + " mirror facets)";
    } catch (const std::invalid_argument& e) {
      if (kind == "analytic") throw;
      kind = "progressive";
    }
  }
  if (kind == "progressive") {
    ref.kind = "progressive";
    const std::string key = cacheKey(progressiveSettings(d, r));
    if (!r.cacheStem.empty() && !r.refresh && readCache(r.cacheStem, key, ref)) {
      ref.cached = true;
      if (ref.image.width != d.render.width || ref.image.height != d.render.height) {
        throw std::runtime_error(r.cacheStem + ".exr does not match the key it is cached under");
      }
    } else {
      renderProgressive(d, r, progress, ref);
      if (!r.cacheStem.empty()) writeCache(r.cacheStem, key, ref);
    }
  } else if (ref.kind.empty()) {
    ref.kind = "given";
    ref.image = readImage(r.spec);
    if (ref.image.width != d.render.width || ref.image.height != d.render.height) {
      throw std::runtime_error("the reference " + r.spec + " is " +
                               std::to_string(ref.image.width) + "x" +
                               std::to_string(ref.image.height) + ", the sweep renders " +
                               std::to_string(d.render.width) + "x" +
                               std::to_string(d.render.height) + " (set --width/--height)");
    }
    ref.description = "given: " + r.spec;
  }
  ref.region = causticMask(ref.image, ref.base);
  return ref;
}

}  // namespace prism
