#include "gui/LightSpaceImage.h"

#include <algorithm>

#include "caustics/CausticMapImages.h"
#include "image/ToneMap.h"

namespace prism {
namespace {

const char* imageName(LightSpaceMap which) {
  switch (which) {
    case LightSpaceMap::Casters:
      return "casters";
    case LightSpaceMap::Receivers:
      return "receivers";
    case LightSpaceMap::Caustics:
      return "caustics";
  }
  return "caustics";
}

}  // namespace

QImage lightSpaceImage(const CausticMapEstimator& maps, LightSpaceMap which) {
  std::vector<ImageRgb> images;
  int width = 0, height = 0;
  for (const auto& map : maps.maps()) {
    for (NamedImage& named : causticMapImages(*map)) {
      if (named.name != imageName(which)) continue;
      width = std::max(width, named.image.width);
      height += named.image.height;
      images.push_back(std::move(named.image));
    }
  }
  if (images.empty()) return {};
  QImage out(width, height, QImage::Format_RGB888);
  out.fill(Qt::black);
  int top = 0;
  for (const ImageRgb& image : images) {
    for (int y = 0; y < image.height; ++y) {
      uchar* line = out.scanLine(top + y);
      for (int x = 0; x < image.width; ++x) {
        const Color& c = image.at(x, y);
        line[3 * x + 0] = toDisplayByte(c.r, 1.0f);
        line[3 * x + 1] = toDisplayByte(c.g, 1.0f);
        line[3 * x + 2] = toDisplayByte(c.b, 1.0f);
      }
    }
    top += image.height;
  }
  return out;
}

QString lightSpaceCaption(const CausticMapEstimator& maps, LightSpaceMap which, bool blur) {
  const char* what = which == LightSpaceMap::Casters     ? "caster positions (R)"
                     : which == LightSpaceMap::Receivers ? "receiver positions (P)"
                                                         : "caustic map (C)";
  if (maps.empty()) {
    return QString("%1: none, no light reaches a caustic caster · n: back to the image").arg(what);
  }
  const CausticMapStats s = maps.stats();
  const int n = maps.maps().front()->frustum().resolution();
  return QString(
             "%1 · light space, %2 light(s), %3 view(s) of %4x%4 texels · blur %5 (b) · n: "
             "back to the image")
      .arg(what)
      .arg(maps.maps().size())
      .arg(s.views)
      .arg(n)
      .arg(blur ? "on" : "off");
}

}  // namespace prism
