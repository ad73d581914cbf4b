#include "master/TileJobWire.h"

namespace prism {

wire::TileJobMessage tileJobMessage(const TileJob& job) {
  wire::TileJobMessage message{job.frame, job.tileIndex, job.rect, 0, wire::kTermDirect};
  if (job.pass) {
    message.pass = job.pass->index;
    message.terms = static_cast<uint8_t>((job.pass->direct ? wire::kTermDirect : 0) |
                                         (job.pass->caustics ? wire::kTermCaustics : 0));
  }
  return message;
}

}  // namespace prism
