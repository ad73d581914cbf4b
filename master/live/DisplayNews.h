// What a viewer shows of the live renderer, as news since it last looked: the pass on screen, the
// tiles in flight, the display bytes of the pixels that changed, the passes completed meanwhile
// and the latest statistics. LiveFeed makes it on the rendering side, DisplayFrame applies it on
// the showing side; in one process it is handed over as it is, over a connection it travels
// (master/remote/ViewProtocol.h). News waits on a NewsBoard, merged, never queued: a viewer
// that looks rarely gets the newest picture, not every step on the way.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "master/live/FrameScale.h"
#include "master/live/LiveRenderer.h"
#include "render/Tile.h"
#include "scene/SceneDescription.h"

namespace prism {

// A pass as the viewer needs it (PassInfo without the tiles' jobs and the light terms).
struct DisplayPass {
  uint32_t frame = 0;
  uint64_t viewId = 0;
  uint64_t viewTag = 0;  // ViewSettings::tag of the view it renders
  int32_t pass = 0;      // 0: a frame while moving, not averaged
  FrameScale scale;
  bool firstOfView = false;
  CameraDesc camera;
  int32_t samplesPerPixel = 0;
  CausticMethod caustics = CausticMethod::None;  // the light term its tiles add (None: direct)
  uint32_t tiles = 0;
};

// A tile being rendered, in display pixels, and the rank rendering it.
struct DisplayTile {
  TileRect rect;
  int32_t rank = 0;
};

struct DisplayNews {
  // At most this many completed passes are kept for a viewer that has not looked (the oldest
  // go first): each is a line in a benchmark, the pixels are in the patch anyway.
  static constexpr size_t kMaxCompleted = 64;

  bool started = false;  // a pass has begun (until then the rest is empty)
  DisplayPass pass;      // the pass on screen now
  uint32_t tilesDone = 0;
  int32_t completedPass = -1;          // the highest pass of the view with every tile in (-1: none)
  int32_t fullPassesDone = 0;          // full-resolution passes of the view completed
  uint64_t staleTiles = 0;             // tiles of frames no longer shown, since the start
  std::vector<DisplayPass> completed;  // passes completed since the last news, oldest first
  std::vector<DisplayTile> inFlight;
  // The display bytes (R, G, B per pixel, rows from the top) of the rectangle patch of the frame
  // (width 0: no pixel changed). The frame is width × height display pixels.
  int32_t width = 0;
  int32_t height = 0;
  TileRect patch{0, 0, 0, 0};
  std::vector<uint8_t> patchBytes;
  std::optional<LiveStats> stats;

  bool hasPixels() const { return patch.width > 0 && patch.height > 0; }
  // Takes other's state: the pass, counts and tiles in flight (not its pixels, completed
  // passes or statistics).
  void copyStateFrom(const DisplayNews& other) {
    started = other.started;
    pass = other.pass;
    tilesDone = other.tilesDone;
    completedPass = other.completedPass;
    fullPassesDone = other.fullPassesDone;
    staleTiles = other.staleTiles;
    inFlight = other.inFlight;
  }
};

}  // namespace prism
