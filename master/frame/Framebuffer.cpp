#include "master/frame/Framebuffer.h"

#include <algorithm>

#include "util/HugePages.h"

namespace prism {

Framebuffer::Framebuffer(int width, int height, size_t tileCount) : received_(tileCount, false) {
  // Black, on 2 MiB pages where it can be (util/HugePages.h): zero-filling a 1920×1080 frame in
  // 4 KiB pages takes 6 000 page faults, 14 % of a 1-spp `prism render` on a virtual machine.
  image_.width = width;
  image_.height = height;
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  reserveOnHugePages(image_.pixels, pixels);
  image_.pixels.resize(pixels, Color(0.0f));
}

bool Framebuffer::insert(const TileResult& tile) {
  const TileRect& r = tile.rect;
  const bool fits = r.x >= 0 && r.y >= 0 && r.width > 0 && r.height > 0 &&
                    r.x + r.width <= image_.width && r.y + r.height <= image_.height &&
                    tile.pixels.size() == static_cast<size_t>(r.pixelCount());
  if (!fits || tile.tileIndex >= received_.size() || received_[tile.tileIndex]) return false;
  received_[tile.tileIndex] = true;
  ++tilesDone_;
  for (int row = 0; row < r.height; ++row) {
    const Color* source = tile.pixels.data() + static_cast<size_t>(row) * r.width;
    std::copy(source, source + r.width, &image_.at(r.x, r.y + row));
  }
  return true;
}

}  // namespace prism
