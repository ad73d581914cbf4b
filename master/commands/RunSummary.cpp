#include "master/commands/RunSummary.h"

#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>

#include "master/dispatch/ScheduleNames.h"
#include "master/frame/ResourceCheck.h"

namespace prism {
namespace {

const char* triangleTestTitle(TriangleTest test) {
  switch (test) {
    case TriangleTest::MollerTrumbore:
      return "Moller-Trumbore";
    case TriangleTest::PlaneThenInside:
      return "plane-then-inside";
    case TriangleTest::Watertight:
      return "watertight";
  }
  return "?";
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string milliseconds(double seconds) {
  return fixed(seconds * 1000.0, 1) + " ms";
}

// Per-rank lines in an MPI run; one line of threads otherwise.
void printWorkers(const RunSummary& s, std::ostream& out) {
  const FrameResult& f = *s.frame;
  if (f.workers.size() <= 1) {
    out << "threads   " << f.threads << " (busy " << fixed(f.busyThreadSeconds, 2)
        << " thread-s)\n";
    return;
  }
  out << "ranks     " << f.workers.size() << ", " << kScheduleNames.nameOf(s.schedule)
      << " schedule; scene broadcast " << formatBytes(static_cast<double>(s.broadcastBytes))
      << " in " << milliseconds(s.broadcastSeconds);
  if (f.reissuedTiles > 0) out << "; " << f.reissuedTiles << " tiles re-issued";
  out << "\n";
  if (!s.geometryShare.empty()) out << "  geometry " << s.geometryShare << "\n";
  for (const RankStats& w : f.workers) {
    if (w.rank > 0 && w.threads == 0 && w.tiles == 0 && !w.retired) {
      out << "  rank " << w.rank << ": still building its scene when the frame was done\n";
      continue;
    }
    out << "  rank " << w.rank << ": " << w.threads << " threads, " << w.tiles << " tiles, "
        << formatCount(static_cast<double>(w.rays.total())) << " rays, busy "
        << fixed(w.busySeconds, 2) << " thread-s";
    if (w.rank > 0) out << ", scene built in " << milliseconds(w.buildSeconds);
    if (w.staleTiles > 0) out << ", " << w.staleTiles << " late or duplicate tiles dropped";
    if (w.lostTiles > 0) out << ", lost " << w.lostTiles << " tiles (re-issued)";
    if (w.retired) out << "; STOPPED ANSWERING, its tiles were re-issued";
    out << "\n";
  }
}

// What caustic mapping did: its parameters, texel counts and the time of each stage.
void printCausticMap(const CausticRunStats& c, std::ostream& out) {
  if (c.noCasters) {
    out << "caustics  caustic map asked for, but no light sees a caster: no maps built\n";
    return;
  }
  const CausticSettings& p = c.settings;
  const CausticMapStats& m = c.map;
  out << "caustics  caustic map: " << p.mapResolution << "x" << p.mapResolution << " x " << m.views
      << (m.views == 1 ? " view" : " views") << ", " << p.mapSteps
      << (p.mapSteps == 1 ? " step" : " steps") << ", blur ";
  if (p.mapBlurRadius > 0 && p.mapBlurSigma > 0.0f) {
    out << "sigma " << fixed(p.mapBlurSigma, 2) << " radius " << p.mapBlurRadius;
  } else {
    out << "off";
  }
  out << ", paths " << (p.mapPaths == CausticMapPaths::Traced ? "traced" : "front face") << "\n"
      << "          texels: " << formatCount(static_cast<double>(m.receiverTexels)) << " receiver, "
      << formatCount(static_cast<double>(m.casterTexels)) << " caster; "
      << formatCount(static_cast<double>(m.paths)) << " paths, "
      << formatCount(static_cast<double>(m.splatted)) << " splatted, "
      << formatCount(static_cast<double>(m.lost)) << " lost; flux splatted "
      << fixed(100.0 * m.splattedFlux / std::max(1e-30, m.emittedFlux), 1)
      << " % of that through caster texels\n"
      << "          receiver map " << milliseconds(m.receiverSeconds) << ", casters+splat "
      << milliseconds(m.casterSeconds) << ", irradiance+blur " << milliseconds(m.filterSeconds)
      << " (build " << milliseconds(c.mapBuildSeconds) << "), frame with lookups "
      << fixed(c.gatherRenderSeconds, 3) << " s\n";
}

// What a progressive run's time budget bounded, and what it did.
std::string budgetLine(const CausticRunStats& c) {
  std::ostringstream line;
  line << "budget    " << fixed(c.settings.timeBudgetSeconds, 2)
       << " s for the whole run, start to written image: ";
  if (c.stoppedByBudget) {
    line << c.passes;
    if (!passesUntilBudget(c.settings)) line << " of " << c.settings.passes;
    line << (c.passes == 1 ? " pass; at " : " passes; at ") << fixed(c.budgetStopSeconds, 2)
         << " s one more (up to " << fixed(c.longestPassSeconds, 2) << " s) and the write ("
         << fixed(c.budgetWriteSeconds, 2) << " s budgeted) would not have fitted\n";
  } else {
    line << "all " << c.passes << " passes fitted\n";
  }
  return line.str();
}

// What the photon passes did: counts, sizes and times.
void printCaustics(const RunSummary& s, std::ostream& out) {
  const CausticRunStats& c = *s.caustics;
  if (c.method == CausticMethod::None) return;
  if (c.method == CausticMethod::CausticMap) return printCausticMap(c, out);
  if (c.noCasters) {
    out << "caustics  photon map asked for, but no light reaches a caster: no photons traced\n";
    return;
  }
  const PhotonPassStats& p = c.photons;
  const double stored = static_cast<double>(p.trace.stored);
  out << "caustics  photon map" << (c.progressive ? " (progressive)" : "") << ": "
      << formatCount(static_cast<double>(c.photonsPerPass)) << " photons x " << c.passes
      << (c.passes == 1 ? " pass" : " passes") << ", " << formatCount(stored) << " stored ("
      << fixed(100.0 * stored / std::max<double>(1.0, static_cast<double>(p.trace.emitted)), 1)
      << " %), " << sizeof(Photon) << " B per photon, map "
      << formatBytes(static_cast<double>(p.mapBytes)) << "\n"
      << "          ";
  if (c.progressive && c.settings.radius > 0.0f) {
    out << "gather radius " << fixed(c.firstRadius, 4) << " -> " << fixed(c.lastRadius, 4);
  } else {
    // gather: auto names the largest k; each photon took its own up to it.
    const std::string k = c.settings.automaticGather
                              ? "own k-NN radius (k <= " + std::to_string(c.k) + ", auto)"
                              : std::to_string(c.k) + "-NN radius";
    out << "each photon over its " << k << " within " << fixed(c.firstRadius, 4);
    if (c.progressive) out << ", shrunk to " << fixed(c.lastRadius, 4);
  }
  out << "; trace " << milliseconds(p.traceSeconds) << ", kd-tree " << milliseconds(p.buildSeconds);
  if (p.radiiSeconds > 0.0) out << ", photon radii " << milliseconds(p.radiiSeconds);
  if (p.sentBytes > 0) {
    out << ", maps sent " << formatBytes(static_cast<double>(p.sentBytes)) << " in "
        << milliseconds(p.distributeSeconds);
  }
  out << ", frames with gathers " << fixed(c.gatherRenderSeconds, 3) << " s\n";
  if (c.progressive && c.settings.timeBudgetSeconds > 0.0) out << budgetLine(c);
  if (p.photonsByRank.size() > 1) {
    const auto byRank = [&](const std::vector<uint64_t>& counts) {
      for (size_t r = 0; r < counts.size(); ++r) {
        out << (r ? ", " : " ") << r << ": " << formatCount(static_cast<double>(counts[r]));
      }
    };
    out << "          photons traced by rank:";
    byRank(p.photonsByRank);
    if (p.radiiByRank.size() > 1) {
      out << "; radii found by rank:";
      byRank(p.radiiByRank);
    }
    out << "\n";
  }
}

}  // namespace

std::string formatCount(double count) {
  if (count >= 1e9) return fixed(count / 1e9, 2) + " G";
  if (count >= 1e6) return fixed(count / 1e6, 2) + " M";
  if (count >= 1e4) return fixed(count / 1e3, 1) + " k";
  return fixed(count, 0);
}

namespace {

// "3 spheres, 2 cones (5 BVH parts), " for the kinds the scene holds (geometry/ShapeKinds.h).
std::string shapeCounts(const SceneBuildStats& g) {
  std::string line;
#define PRISM_SHAPE_COUNT_TEXT(Shape, plural)                           \
  if (g.plural.count > 0) {                                             \
    line += std::to_string(g.plural.count) + " " #plural;               \
    if (g.plural.bvhParts != g.plural.count) {                          \
      line += " (" + std::to_string(g.plural.bvhParts) + " BVH parts)"; \
    }                                                                   \
    line += ", ";                                                       \
  }
  PRISM_SHAPE_KINDS(PRISM_SHAPE_COUNT_TEXT)
#undef PRISM_SHAPE_COUNT_TEXT
  return line;
}

}  // namespace

void printRunSummary(const RunSummary& s, std::ostream& out) {
  const FrameResult& f = *s.frame;
  const SceneBuildStats& g = s.sceneStats;
  const RenderSettings& r = s.settings;
  const double mrays =
      f.seconds > 0.0 ? static_cast<double>(f.rays.total()) / f.seconds / 1e6 : 0.0;
  out << "scene     " << s.scenePath << " (parsed in " << milliseconds(s.parseSeconds) << ")\n"
      << "geometry  " << shapeCounts(g) << g.triangles << " triangles ("
      << triangleTestTitle(r.triangleTest) << "), " << g.planes << " planes, " << s.lightCount
      << " lights\n";
  for (const std::string& note : s.sceneNotes) out << "          " << note << "\n";
  out << "bvh       " << g.bvh.nodeCount << " nodes, depth " << g.bvh.maxDepth << ", "
      << formatBytes(static_cast<double>(g.accelerationBytes())) << " (+"
      << formatBytes(static_cast<double>(g.geometryBytes)) << " geometry), built in "
      << milliseconds(g.bvh.seconds) << " (scene build " << milliseconds(s.buildSeconds) << ")\n"
      << "kernels   " << s.instructionSet << "\n"
      << "image     " << r.width << "x" << r.height << ", " << r.samplesPerPixel
      << " spp, max depth " << r.maxDepth << ", " << f.tileCount << " tiles of " << f.tileSize
      << " px\n";
  printWorkers(s, out);
  if (s.caustics) printCaustics(s, out);
  out << "rays      " << formatCount(static_cast<double>(f.rays.total()))
      << " total: " << formatCount(static_cast<double>(f.rays.primary)) << " primary, "
      << formatCount(static_cast<double>(f.rays.shadow)) << " shadow, "
      << formatCount(static_cast<double>(f.rays.secondary)) << " reflected/refracted\n";
  // Said every time, so a log without it is a log of a run that could not check.
  if (f.rays.nonFinite == 0) {
    out << "numbers   every sample finite\n";
  } else {
    out << "numbers   " << f.rays.nonFinite
        << " samples or pixels were NaN or infinite (an extreme light, a light on a surface, "
           "degenerate geometry?) and are black in the image\n";
  }
  out << "time      render " << fixed(f.seconds, 3) << " s, ";
  if (s.firstTileSeconds) out << "first tile at " << fixed(*s.firstTileSeconds, 3) << " s, ";
  out << "write " << milliseconds(s.writeSeconds) << ", total " << fixed(s.totalSeconds, 3)
      << " s\n"
      << "speed     " << fixed(mrays, 2) << " Mrays/s (" << fixed(mrays / std::max(1, f.threads), 2)
      << " per thread)\n"
      << "written   " << s.outputPath << "\n";
}

}  // namespace prism
