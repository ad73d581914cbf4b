// One tile to render: which tile of which frame, and what to render it with. Every rank uses it:
// rank 0's render threads take jobs from the dispatcher, a slave's from the jobs the master
// sent (common/wire/TileJobWire.h maps it to and from the wire).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "render/RenderPass.h"
#include "render/RenderView.h"
#include "render/Tile.h"

namespace prism {

struct TileJob {
  TileJob() = default;
  TileJob(uint32_t tile, const TileRect& r, uint32_t f = 0,
          std::shared_ptr<const RenderView> v = nullptr,
          std::shared_ptr<const RenderPass> p = nullptr)
      : tileIndex(tile), rect(r), frame(f), view(std::move(v)), pass(std::move(p)) {}

  uint32_t tileIndex = 0;
  TileRect rect;
  // Which frame the job belongs to, and (the viewer) what it renders. Without a view the
  // tile is rendered with the scene's own camera and settings, as `prism render` does.
  uint32_t frame = 0;
  std::shared_ptr<const RenderView> view;
  std::shared_ptr<const RenderPass> pass;  // the light terms; null: direct light only
  // Set once the job's frame has ended (a camera move ends the viewer's frames still running):
  // the tile is then abandoned after its current row and gives no result. Null: never.
  std::shared_ptr<const std::atomic<bool>> frameEnded;
};

}  // namespace prism
