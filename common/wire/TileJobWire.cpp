#include "wire/TileJobWire.h"

#include <utility>

namespace prism {

wire::TileJobMessage tileJobMessage(const TileJob& job) {
  wire::TileJobMessage message{job.frame, job.tileIndex, job.rect, 0, wire::kTermDirect};
  if (job.pass) {
    message.pass = job.pass->index;
    const uint8_t caustics = job.pass->causticMap ? wire::kTermCausticMap : wire::kTermCaustics;
    message.terms = static_cast<uint8_t>((job.pass->direct ? wire::kTermDirect : 0) |
                                         (job.pass->caustics ? caustics : 0));
  }
  return message;
}

TileJob tileJobFromMessage(const wire::TileJobMessage& message,
                           std::shared_ptr<const RenderView> view,
                           std::shared_ptr<const RenderPass> pass) {
  return TileJob(message.tileIndex, message.rect, message.frame, std::move(view), std::move(pass));
}

}  // namespace prism
