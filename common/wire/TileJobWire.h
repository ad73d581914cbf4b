// A TileJob on the wire, both ways. The master sends a tile's frame, index and rectangle, and
// its pass's number and light terms; the slave rebuilds the job with the view of that frame and
// the pass it holds for that number (the photon map it was sent, or the caustic maps it built).
#pragma once

#include <memory>

#include "cluster/TileJob.h"
#include "wire/Messages.h"

namespace prism {

wire::TileJobMessage tileJobMessage(const TileJob& job);

// A pass's light terms as the wire carries them (wire::kTerm* bits), and back: what the tile
// of a received job adds up, for the slave to make the same RenderPass with its factories.
uint8_t wireTerms(const RenderPass& pass);
struct PassTerms {
  uint32_t index = 0;
  bool direct = true;
  CausticSource source = CausticSource::None;
};
PassTerms passTerms(const wire::TileJobMessage& message);

// The job a received message names; view null: the scene's own camera (`prism render`).
TileJob tileJobFromMessage(const wire::TileJobMessage& message,
                           std::shared_ptr<const RenderView> view,
                           std::shared_ptr<const RenderPass> pass);

}  // namespace prism
