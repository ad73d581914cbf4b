#include "image/SrgbImage.h"

#include "image/ToneMap.h"
#include "util/HugePages.h"

namespace prism {

const std::array<float, 256>& linearOfSrgbByte() {
  // pow() once per byte value, not once per channel (60 ms of reading the default sky per texel).
  static const std::array<float, 256> table = [] {
    std::array<float, 256> linear;
    for (int b = 0; b < 256; ++b) linear[b] = srgbToLinear(static_cast<float>(b) * (1.0f / 255.0f));
    return linear;
  }();
  return table;
}

ImageRgb linearFromSrgb(const SrgbImage& source) {
  const std::array<float, 256>& linear = linearOfSrgbByte();
  ImageRgb image;
  image.width = source.width;
  image.height = source.height;
  // On huge pages where it is large: in 4 KiB pages the first touches of a big image's floats
  // cost more than the conversion.
  reserveOnHugePages(image.pixels, static_cast<size_t>(source.width) * source.height);
  image.pixels.resize(static_cast<size_t>(source.width) * source.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const uint8_t* p = &source.rgb[3 * i];
    image.pixels[i] = Color(linear[p[0]], linear[p[1]], linear[p[2]]);
  }
  return image;
}

SrgbTexels packedTexels(const SrgbImage& image) {
  // Appended, not resized and overwritten: zeroing 4 MiB first cost as much as the packing.
  SrgbTexels packed{image.width, image.height, {}};
  const size_t count = static_cast<size_t>(image.width) * image.height;
  packed.texels.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = &image.rgb[3 * i];
    packed.texels.push_back(uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16);
  }
  return packed;
}

SrgbTexels packedTexels(const ImageRgb& image) {
  static const DisplayEncoder encode(1.0f);  // its table takes longer to make than a small level
  SrgbTexels packed{image.width, image.height, {}};
  packed.texels.reserve(image.pixels.size());
  for (const Color& c : image.pixels) {
    packed.texels.push_back(uint32_t{encode(c.x)} | uint32_t{encode(c.y)} << 8 |
                            uint32_t{encode(c.z)} << 16);
  }
  return packed;
}

}  // namespace prism
