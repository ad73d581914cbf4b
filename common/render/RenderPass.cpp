#include "render/RenderPass.h"

#include <utility>

#include "caustics/CausticMapEstimator.h"

namespace prism {

std::shared_ptr<const RenderPass> RenderPass::directOnly(uint32_t index) {
  return std::make_shared<const RenderPass>(RenderPass{index, true, nullptr, CausticSource::None});
}

std::shared_ptr<const RenderPass> RenderPass::withPhotons(
    uint32_t index, bool direct, std::shared_ptr<const CausticEstimator> gather) {
  if (!gather) return directOnly(index);
  return std::make_shared<const RenderPass>(
      RenderPass{index, direct, std::move(gather), CausticSource::PhotonMap});
}

std::shared_ptr<const RenderPass> RenderPass::withCausticMaps(
    uint32_t index, std::shared_ptr<const CausticMapEstimator> maps) {
  if (!maps || maps->empty()) return directOnly(index);
  return std::make_shared<const RenderPass>(
      RenderPass{index, true, std::move(maps), CausticSource::CausticMap});
}

}  // namespace prism
