#include "wire/TileJobWire.h"

#include <utility>

namespace prism {

wire::TileJobMessage tileJobMessage(const TileJob& job) {
  wire::TileJobMessage message{job.frame, job.tileIndex, job.rect, 0, wire::kTermDirect};
  if (job.pass) {
    message.pass = job.pass->index;
    message.terms = wireTerms(*job.pass);
  }
  return message;
}

uint8_t wireTerms(const RenderPass& pass) {
  uint8_t caustics = 0;
  if (pass.source == CausticSource::PhotonMap) caustics = wire::kTermCaustics;
  if (pass.source == CausticSource::CausticMap) caustics = wire::kTermCausticMap;
  return static_cast<uint8_t>((pass.direct ? wire::kTermDirect : 0) | caustics);
}

PassTerms passTerms(const wire::TileJobMessage& message) {
  PassTerms terms{message.pass, (message.terms & wire::kTermDirect) != 0, CausticSource::None};
  if (message.terms & wire::kTermCaustics) terms.source = CausticSource::PhotonMap;
  if (message.terms & wire::kTermCausticMap) terms.source = CausticSource::CausticMap;
  return terms;
}

TileJob tileJobFromMessage(const wire::TileJobMessage& message,
                           std::shared_ptr<const RenderView> view,
                           std::shared_ptr<const RenderPass> pass) {
  return TileJob(message.tileIndex, message.rect, message.frame, std::move(view), std::move(pass));
}

}  // namespace prism
