// The field lists of what the view protocol carries (master/remote/ViewProtocol.h) from the
// layers below it: the view a viewer asks for, what it opens with, the display news and the
// statistics. One list per struct serves encoding, decoding and comparison (wire/Fields.h).
#pragma once

#include <algorithm>
#include <vector>

#include "master/live/DisplayNews.h"
#include "master/live/LiveSource.h"
#include "wire/MessageParts.h"
#include "wire/SceneCodec.h"
#include "wire/WireEnums.h"

namespace prism::wire {

// Display bytes on the wire after PNG's Sub filter (each byte less the same channel of the
// pixel to its left in its row): zstd then packs a frame about 20 % smaller (docs/viewer.md).
// `width` is the rows' pixel count, a field read before this one.
template <class Bytes, class Width>
struct SubFilteredRows {
  Bytes& bytes;
  Width& width;

  void write(ByteWriter& w) const {
    w.writeCount(bytes.size());
    if (bytes.empty()) return;
    w.writeRaw(bytes.data(), bytes.size());
    uint8_t* filtered = w.lastBytes(bytes.size());  // filtered where it was copied
    const size_t row = rowBytes();
    for (size_t start = 0; start < bytes.size(); start += row) {
      const size_t end = std::min(start + row, bytes.size());
      for (size_t i = start + 3; i < end; ++i) {
        filtered[i] = static_cast<uint8_t>(bytes[i] - bytes[i - 3]);
      }
    }
  }
  void read(ByteReader& r) {
    bytes = r.readU8s();
    const size_t row = rowBytes();
    for (size_t start = 0; start < bytes.size(); start += row) {
      const size_t end = std::min(start + row, bytes.size());
      for (size_t i = start + 3; i < end; ++i) {
        bytes[i] = static_cast<uint8_t>(bytes[i] + bytes[i - 3]);
      }
    }
  }
  size_t rowBytes() const {
    return width > 0 ? static_cast<size_t>(width) * 3 : std::max<size_t>(bytes.size(), 1);
  }
};
template <class Bytes, class Width>
SubFilteredRows<Bytes, Width> subFilteredRows(Bytes& bytes, Width& width) {
  return {bytes, width};
}

template <>
struct Fields<ViewSettings> {
  static void fields(auto& self, auto&& visit) {
    auto& [camera, samplesPerPixel, debugView, caustics, photonsPerPass, causticMapBlur, tag,
           maxPasses, frameTimeSeconds] = self;
    visit(camera, samplesPerPixel, debugView, caustics, photonsPerPass,
          flag(causticMapBlur, "caustic-map blur flag"), tag, maxPasses, frameTimeSeconds);
  }
  // Samples per pixel 1 to 65536, passes 0 to 1 << 20, photons at most 1 << 32, a frame time
  // below an hour (negative: unchanged).
  static void check(const ViewSettings& view);
};

template <>
struct Fields<ViewerStart> {
  static void fields(auto& self, auto&& visit) {
    auto& [sceneName, width, height, exposure, home, view, resume, causticMapsRefusal,
           lightSpaceRefusal, instructionSet] = self;
    visit(sceneName, width, height, exposure, home, view, flag(resume, "resume flag"),
          causticMapsRefusal, lightSpaceRefusal, instructionSet);
  }
  // A frame of 1 to 16384 pixels a side, a positive finite exposure.
  static void check(const ViewerStart& start);
};

template <>
struct Fields<FrameScale> {
  PRISM_WIRE_FIELDS(numerator, denominator)
  static void check(const FrameScale& scale);  // both 1 to 1024
};

template <>
struct Fields<DisplayPass> {
  static void fields(auto& self, auto&& visit) {
    auto& [frame, viewId, viewTag, pass, scale, firstOfView, camera, samplesPerPixel, caustics,
           tiles] = self;
    visit(frame, viewId, viewTag, pass, scale, flag(firstOfView, "first-of-view flag"), camera,
          samplesPerPixel, caustics, tiles);
  }
};

template <>
struct Fields<DisplayTile> {
  // The rectangle as four numbers: a tile of a reduced frame may cover no display pixel.
  static void fields(auto& self, auto&& visit) {
    auto& [rect, rank] = self;
    visit(rect.x, rect.y, rect.width, rect.height, rank);
  }
};

template <>
struct Fields<RankStats> {
  static void fields(auto& self, auto&& visit) {
    auto& [rank, threads, tiles, rays, busySeconds, buildSeconds, startSeconds, mpiInitSeconds,
           staleTiles, lostTiles, retired] = self;
    visit(rank, threads, tiles, rays, busySeconds, buildSeconds, startSeconds, mpiInitSeconds,
          staleTiles, lostTiles, flag(retired, "retired flag"));
  }
};

template <>
struct Fields<FrameTimeStats> {
  PRISM_WIRE_FIELDS(frames, medianSeconds, p95Seconds, framesPerSecond, shownWidth, shownHeight,
                    fullResolutionFrames, reducedFrames)
};

template <>
struct Fields<PhotonPassStats> {
  PRISM_WIRE_FIELDS(trace, traceSeconds, buildSeconds, distributeSeconds, radiiSeconds, mapBytes,
                    sentBytes, photonsByRank, radiiByRank)
};

template <>
struct Fields<PhotonLiveStats> {
  static void fields(auto& self, auto&& visit) {
    auto& [method, noCasters, photonsPerPass, passes, reused, last, radius, mapResolution, mapViews,
           mapBlur, mapBuildSeconds] = self;
    visit(method, flag(noCasters, "no-casters flag"), photonsPerPass, passes,
          flag(reused, "reused flag"), last, radius, mapResolution, mapViews,
          flag(mapBlur, "map blur flag"), mapBuildSeconds);
  }
};

template <>
struct Fields<LiveStats> {
  PRISM_WIRE_FIELDS(frame, viewId, pass, passesDone, ranks, raysPerSecond, lastPassSeconds,
                    lastPassBusySeconds, totalThreads, previewLatencySeconds, firstFullSeconds,
                    frameTimes, frameTimeTargetSeconds, photons)
  static void check(const LiveStats& stats);  // at most 1 << 20 ranks
};

template <>
struct Fields<DisplayNews> {
  static void fields(auto& self, auto&& visit) {
    auto& [started, pass, tilesDone, completedPass, fullPassesDone, staleTiles, completed, inFlight,
           width, height, patch, patchBytes, stats] = self;
    visit(flag(started, "started flag"), pass, tilesDone, completedPass, fullPassesDone, staleTiles,
          completed, inFlight, width, height, patch.x, patch.y, patch.width, patch.height,
          subFilteredRows(patchBytes, patch.width), stats);
  }
  // A frame of 1 to 16384 pixels a side; the patch (if any) inside it with its bytes; at most
  // kMaxCompleted completed passes.
  static void check(const DisplayNews& news);
};

}  // namespace prism::wire
