#include "parse/TextureFile.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "image/ImageIo.h"
#include "image/JpegFile.h"
#include "image/PngFile.h"
#include "parse/SceneLoader.h"

namespace prism {

namespace {

// What a texture holds per pixel at most, everything a rank keeps of it counted: its bytes or
// floats as read (3 or 12), and the mip pyramid the scene builds (4/3 of a level's 4-byte packed
// texels or 12-byte floats: 16), with room to spare.
constexpr uint64_t kTextureBytesPerPixel = 32;

uint64_t maxPixels(const MemoryLimit& limit) {
  return limit.bytes / kTextureBytesPerPixel;
}

[[noreturn]] void refuse(const FileLoc& at, const std::string& name, const std::string& why) {
  throw SceneError(at, "texture '" + name + "': " + why);
}

std::string lowercaseExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

bool looksLikePng(std::span<const uint8_t> bytes) {
  static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

bool looksLikeJpeg(std::span<const uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

TextureDesc decodeTexture(std::span<const uint8_t> bytes, const std::string& name,
                          const FileLoc& referencedFrom, const MemoryLimit& limit) {
  TextureDesc texture;
  texture.path = name;
  try {
    if (looksLikePng(bytes)) {
      PngPixels png = decodePng(bytes, maxPixels(limit));
      texture.srgb = std::move(png.srgb);
      texture.linear = std::move(png.linear);
      return texture;
    }
    if (looksLikeJpeg(bytes)) {
      texture.srgb = decodeJpeg(bytes, maxPixels(limit));
      return texture;
    }
  } catch (const std::runtime_error& e) {
    std::string why = e.what();
    if (why.ends_with("larger than allowed")) {
      why += " by the memory limit (" + limit.source + ")";
    }
    refuse(referencedFrom, name, why);
  }
  refuse(referencedFrom, name, "not a PNG or JPEG image");
}

TextureDesc loadTextureFile(const std::string& path, const FileLoc& referencedFrom,
                            const MemoryLimit& limit) {
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (error) refuse(referencedFrom, path, "cannot read it: " + error.message());
  // An encoded image is smaller than its pixels: a file larger than the pixels allowed cannot fit.
  if (size / 3 > maxPixels(limit)) {
    refuse(referencedFrom, path,
           memoryRefusal("a " + std::to_string(size) + "-byte image file",
                         size / 3 * kTextureBytesPerPixel, limit,
                         "use a smaller texture or raise --memory-limit"));
  }
  const std::string text = readTextFile(path, referencedFrom);
  const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  if (looksLikePng(bytes) || looksLikeJpeg(bytes)) {
    return decodeTexture(bytes, path, referencedFrom, limit);
  }
  // Any other format (EXR, HDR, TIFF, ...) through OpenImageIO, as linear radiance.
  const std::string extension = lowercaseExtension(path);
  if (extension == ".png" || extension == ".jpg" || extension == ".jpeg") {
    refuse(referencedFrom, path,
           "not a " + extension.substr(1) + " image (its first bytes say so)");
  }
  TextureDesc texture;
  texture.path = path;
  try {
    texture.linear = readImage(path);
  } catch (const std::runtime_error& e) {
    refuse(referencedFrom, path, e.what());
  }
  if (texture.linear.pixels.empty()) refuse(referencedFrom, path, "the image has no pixels");
  return texture;
}

}  // namespace prism
