// The TileJob message for a tile a slave is to render: its frame, tile and rectangle, and the
// pass's number and light terms, from which the slave picks the photon map it was sent for
// that pass. Shared by `prism render` (FrameRenderer) and the viewer (LiveRenderer).
#pragma once

#include "slave/TileWorkerPool.h"
#include "wire/Messages.h"

namespace prism {

wire::TileJobMessage tileJobMessage(const TileJob& job);

}  // namespace prism
