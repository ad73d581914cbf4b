// Where caustic mapping fails, measured: every case of tests/common/caustics/CausticMapCases.h
// scored against a high-budget photon reference, cell by cell (CausticFluxGrid.h), printed as the
// Markdown tables of docs/caustics.md. For each configuration: the map's build time, and per
// scored region the relative L1 error of the cell fluxes and the flux ratio (map / reference).
// The reference's own noise is shown by scoring a quarter of its photons against all of them, and
// a classic photon map (k = 100) at a normal budget is scored the same way for comparison.
//
// usage: prism_caustic_map_study [--photons N] [--threads N]
//   N reference photons (default 8000000); threads 0 = all cores.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include "caustics/CausticMapEstimator.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonTracer.h"
#include "master/frame/CausticPasses.h"
#include "tests/common/caustics/CausticMapCases.h"
#include "util/Stopwatch.h"

namespace prism::test {
namespace {

// Lookups per cell side: a 2048² map resolves features of about 0.001 on these floors, so the
// cells (0.05) are integrated on a sub-grid fine enough not to miss the focus.
constexpr int kLookupsPerSide = 32;

struct Reference {
  std::vector<std::vector<double>> full, quarter;  // per region
};

Reference traceReference(const CausticCase& c, uint64_t photons, int threads) {
  const Scene scene(c.scene);
  const PhotonTracer tracer(scene, photons, 16);
  const std::vector<Photon> all = tracePhotons(tracer, 0, 0, photons, threads);
  // The first quarter of the emission order is a quarter-budget run of the same sequence.
  const PhotonTracer quarterTracer(scene, photons / 4, 16);
  const std::vector<Photon> quarter = tracePhotons(quarterTracer, 0, 0, photons / 4, threads);
  Reference r;
  for (const ScoredRegion& region : c.regions) {
    r.full.push_back(photonCellFlux(region.grid, all));
    r.quarter.push_back(photonCellFlux(region.grid, quarter));
  }
  return r;
}

void printHeader(const CausticCase& c) {
  std::printf("\n### %s\n\n| configuration | build s |", c.name.c_str());
  for (const ScoredRegion& r : c.regions)
    std::printf(" %s: L1 error | flux ratio |", r.name.c_str());
  std::printf("\n|---|---|");
  for (size_t i = 0; i < c.regions.size(); ++i) std::printf("---|---|");
  std::printf("\n");
}

void printScores(const std::string& label, double seconds, const CausticCase& c,
                 const std::vector<std::vector<double>>& reference,
                 const std::function<std::vector<double>(const FluxGrid&)>& cellFlux) {
  std::printf("| %s | %s |", label.c_str(),
              seconds >= 0.0 ? std::to_string(seconds).substr(0, 5).c_str() : "—");
  for (size_t i = 0; i < c.regions.size(); ++i) {
    const std::vector<double> cells = cellFlux(c.regions[i].grid);
    const double ref = totalFlux(reference[i]);
    if (ref <= 0.0) {
      std::printf(" — | %.3g W (reference 0) |", totalFlux(cells));
    } else {
      std::printf(" %.3f | %.3f |", relativeL1(cells, reference[i]), totalFlux(cells) / ref);
    }
  }
  std::printf("\n");
  std::fflush(stdout);
}

void scoreMap(const std::string& label, const CausticCase& c, SceneDescription d,
              const Reference& ref, int threads) {
  const Scene scene(d);
  const auto start = SteadyClock::now();
  const CausticMapEstimator maps(scene, threads);
  const double seconds = secondsSince(start);
  printScores(label, seconds, c, ref.full,
              [&](const FluxGrid& g) { return estimatorCellFlux(g, maps, kLookupsPerSide); });
}

void scoreReferenceAndPhotonMap(const CausticCase& c, const Reference& ref, int threads) {
  size_t region = 0;
  printScores("reference, ¼ of its photons", -1.0, c, ref.full,
              [&](const FluxGrid&) { return ref.quarter[region++]; });
  const Scene scene(c.scene);
  constexpr uint64_t kPhotonMapPhotons = 500'000;
  const auto start = SteadyClock::now();
  const PhotonTracer tracer(scene, kPhotonMapPhotons, 16);
  // Pass 1 continues the emission sequence past the reference's pass 0 photons.
  auto map =
      std::make_shared<const PhotonMap>(tracePhotons(tracer, 1, 0, kPhotonMapPhotons, threads));
  const PhotonGather gather(map, {false, 100, automaticMaxRadius(scene), PhotonFilter::Cone});
  const double seconds = secondsSince(start);
  printScores("photon map, 500 k photons, k = 100", seconds, c, ref.full,
              [&](const FluxGrid& g) { return estimatorCellFlux(g, gather, kLookupsPerSide); });
}

int run(uint64_t photons, int threads) {
  std::printf("Reference: %llu photons per case, binned per cell (no kernel).\n",
              static_cast<unsigned long long>(photons));
  {
    const CausticCase c = glassSphereCase();
    const Reference ref = traceReference(c, photons, threads);
    printHeader(c);
    scoreReferenceAndPhotonMap(c, ref, threads);
    for (const int n : {16, 32, 64, 128, 256, 512, 1024, 2048}) {
      SceneDescription d = c.scene;
      d.caustics.mapResolution = n;
      scoreMap("map " + std::to_string(n) + "², traced", c, d, ref, threads);
    }
    for (const int n : {128, 512}) {
      SceneDescription d = c.scene;
      d.caustics.mapResolution = n;
      d.caustics.mapBlurRadius = 0;
      scoreMap("map " + std::to_string(n) + "², traced, no blur", c, d, ref, threads);
    }
    for (const int steps : {1, 2, 3, 5}) {
      SceneDescription d = c.scene;
      d.caustics.mapSteps = steps;
      scoreMap("map 512², traced, " + std::to_string(steps) + " steps", c, d, ref, threads);
    }
    for (const int n : {128, 512, 2048}) {
      SceneDescription d = c.scene;
      d.caustics.mapResolution = n;
      d.caustics.mapPaths = CausticMapPaths::FrontFace;
      scoreMap("map " + std::to_string(n) + "², front face", c, d, ref, threads);
    }
  }
  // The other cases: does resolution help, do more steps?
  std::vector<CausticCase> cases{hiddenReceiverCase()};
  for (const float elevation : {90.0f, 60.0f, 45.0f, 30.0f, 20.0f, 10.0f}) {
    cases.push_back(grazingCase(elevation));
  }
  for (const CausticCase& c : cases) {
    const Reference ref = traceReference(c, photons, threads);
    printHeader(c);
    scoreReferenceAndPhotonMap(c, ref, threads);
    for (const int n : {512, 2048}) {
      SceneDescription d = c.scene;
      d.caustics.mapResolution = n;
      scoreMap("map " + std::to_string(n) + "², traced", c, d, ref, threads);
    }
    SceneDescription d = c.scene;
    d.caustics.mapSteps = 3;
    scoreMap("map 512², traced, 3 steps", c, d, ref, threads);
  }
  return 0;
}

}  // namespace
}  // namespace prism::test

int main(int argc, char** argv) {
  uint64_t photons = 8'000'000;
  int threads = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--photons") && i + 1 < argc) {
      photons = std::strtoull(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--photons N] [--threads N]\n", argv[0]);
      return 2;
    }
  }
  if (photons < 4) {
    std::fprintf(stderr, "--photons must be at least 4\n");
    return 2;
  }
  return prism::test::run(photons, threads);
}
