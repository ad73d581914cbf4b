#include "caustics/PhotonImage.h"

#include <algorithm>

namespace prism {

ImageRgb photonImage(const PhotonMap& map, const Camera& camera, int width, int height) {
  ImageRgb image(width, height);
  for (const Photon& photon : map.photons()) {
    const std::optional<Vec2> at = camera.project(photon.position);
    if (!at || !(at->x >= 0.0f && at->y >= 0.0f && at->x < width && at->y < height)) continue;
    const size_t i =
        static_cast<size_t>(at->y) * static_cast<size_t>(width) + static_cast<size_t>(at->x);
    image.pixels[i] += photon.power;
  }
  std::vector<float> lit;
  for (const Color& c : image.pixels) {
    const float v = maxComponent(c);
    if (v > 0.0f) lit.push_back(v);
  }
  if (lit.empty()) return image;
  const size_t at = lit.size() - 1 - lit.size() / 100;
  std::nth_element(lit.begin(), lit.begin() + static_cast<long>(at), lit.end());
  const float scale = 1.0f / lit[at];
  for (Color& c : image.pixels) c *= scale;
  return image;
}

}  // namespace prism
