#include "master/commands/PartialFrame.h"

#include <filesystem>
#include <stdexcept>

namespace prism {

std::string partialOutputPath(const std::string& outputPath) {
  const std::filesystem::path path(outputPath);
  return (path.parent_path() / (path.stem().string() + ".partial" + path.extension().string()))
      .string();
}

void markUnfinishedTiles(ImageRgb& image, const std::vector<TileRect>& tiles,
                         const std::vector<bool>& tileDone) {
  const Color magenta(1.0f, 0.0f, 1.0f);
  constexpr int kStripe = 4;  // pixels; diagonal, so even a one-pixel-high tile shows it
  for (size_t t = 0; t < tiles.size(); ++t) {
    if (t < tileDone.size() && tileDone[t]) continue;
    const TileRect& r = tiles[t];
    for (int y = r.y; y < r.y + r.height; ++y) {
      for (int x = r.x; x < r.x + r.width; ++x) {
        image.at(x, y) = ((x + y) / kStripe) % 2 == 0 ? magenta : Color(0.0f);
      }
    }
  }
}

ImageMetadata partialFrameMetadata(size_t tilesDone, size_t tileCount) {
  const std::string counts = std::to_string(tilesDone) + "/" + std::to_string(tileCount);
  return {{kPartialFrameAttribute, counts},
          {"ImageDescription", "Prism partial render (interrupted): " + std::to_string(tilesDone) +
                                   " of " + std::to_string(tileCount) +
                                   " tiles finished; unfinished tiles are striped magenta"}};
}

bool isPartialFrame(const std::string& path) {
  return !readImageText(path, kPartialFrameAttribute).empty();
}

void checkMayWriteFrame(const std::string& path, bool overwrite) {
  std::error_code error;
  if (overwrite || !std::filesystem::exists(path, error) || isPartialFrame(path)) return;
  throw std::runtime_error("'" + path +
                           "' already exists; pass --overwrite to replace it (nothing rendered)");
}

}  // namespace prism
