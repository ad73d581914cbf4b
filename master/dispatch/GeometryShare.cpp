#include "master/dispatch/GeometryShare.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "transport/Transport.h"
#include "util/MemorySize.h"
#include "util/Stopwatch.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism {
namespace {

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", s);
  return text;
}

}  // namespace

const char* geometryShareModeName(GeometryShareMode mode) {
  switch (mode) {
    case GeometryShareMode::Auto:
      return "auto";
    case GeometryShareMode::Broadcast:
      return "broadcast";
    case GeometryShareMode::Local:
      return "local";
  }
  return "auto";
}

GeometryShareMode parseGeometryShareMode(const std::string& text) {
  for (GeometryShareMode mode :
       {GeometryShareMode::Auto, GeometryShareMode::Broadcast, GeometryShareMode::Local}) {
    if (text == geometryShareModeName(mode)) return mode;
  }
  throw std::invalid_argument("--bvh-share: expected auto, broadcast or local, not '" + text + "'");
}

double BuildPlace::pace() const {
  return std::max(1e-3, std::min(static_cast<double>(threads),
                                 static_cast<double>(cores) / std::max(1, ranksOnNode)));
}

std::string GeometrySharePlan::describe() const {
  std::string text = broadcast ? "broadcast by rank 0" : "built on every rank";
  text += std::string(" (") + geometryShareModeName(requested);
  if (requested == GeometryShareMode::Auto) {
    text += ": predicted " + seconds(broadcastSeconds) + " broadcasting against " +
            seconds(eachBuildsSeconds) + " building on every rank; link " +
            formatBytes(linkBytesPerSecond) + "/s";
  }
  text += ")";
  if (broadcast)
    text += ", " + formatBytes(static_cast<double>(sentBytes)) + " in " + seconds(sentSeconds) +
            (sentWhileRendering ? " while rank 0 rendered" : "");
  return text;
}

GeometrySharePlan planGeometryShare(GeometryShareMode requested, size_t triangles,
                                    size_t descriptionBytes, double descriptionSeconds,
                                    const BuildPlace& rank0,
                                    const std::vector<BuildPlace>& slaves) {
  GeometrySharePlan plan;
  plan.requested = requested;
  plan.linkBytesPerSecond = descriptionSeconds > 0.0
                                ? static_cast<double>(descriptionBytes) / descriptionSeconds
                                : std::numeric_limits<double>::infinity();
  const double work = static_cast<double>(triangles) * kBuildThreadSecondsPerTriangle;
  double slowest = work / rank0.pace();
  for (const BuildPlace& slave : slaves) slowest = std::max(slowest, work / slave.pace());
  plan.eachBuildsSeconds = slowest;
  const BuildPlace alone{rank0.threads, rank0.cores, 1};
  const double bytes = static_cast<double>(triangles) * kGeometryBytesPerTriangle;
  plan.transferSeconds = bytes / plan.linkBytesPerSecond + bytes / kGeometryCodecBytesPerSecond;
  plan.broadcastSeconds = work / alone.pace() + plan.transferSeconds;
  switch (requested) {
    case GeometryShareMode::Auto:
      plan.broadcast = !slaves.empty() && plan.broadcastSeconds < plan.eachBuildsSeconds;
      break;
    case GeometryShareMode::Broadcast:
      plan.broadcast = !slaves.empty();
      break;
    case GeometryShareMode::Local:
      plan.broadcast = false;
      break;
  }
  return plan;
}

void broadcastGeometry(Transport& transport, const SceneGeometry& geometry, bool rank0Renders,
                       GeometrySharePlan& plan) {
  plan.sentWhileRendering = rank0Renders;
  const auto start = SteadyClock::now();
  std::vector<uint8_t> bytes = wire::encode(geometry);
  transport.broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  plan.sentBytes = bytes.size();
  plan.sentSeconds = secondsSince(start);
}

}  // namespace prism
