#include "image/ImageIo.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include "image/ToneMap.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

// Formats that store floating-point radiance get it untouched; the rest are display formats.
bool isFloatFormat(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace

bool isWritableImagePath(const std::string& path, std::string* why) {
  const std::string ext = fs::path(path).extension().string();
  if (ext.empty()) {
    if (why) *why = "output '" + path + "' has no extension (use .png or .exr)";
    return false;
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    if (why) *why = "cannot write '" + ext + "' images: " + OIIO::geterror();
    return false;
  }
  return true;
}

void writeImage(const ImageRgb& image, const std::string& path, float exposure,
                const ImageMetadata& metadata) {
  const fs::path target(path);
  // Keep the extension on the temporary name: OpenImageIO picks the format from it.
  const fs::path temporary =
      target.parent_path() / ("." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                              target.extension().string());
  auto out = OIIO::ImageOutput::create(temporary.string());
  if (!out) throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());

  const bool asFloat = isFloatFormat(path);
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       asFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", asFloat ? "Linear" : "sRGB");
  spec.attribute("Software", "Prism");
  // zlib level 3 writes a 512² PNG about 3x faster than the default 6 for files ~10 % larger.
  spec.attribute("png:compressionLevel", 3);
  for (const auto& [name, value] : metadata) spec.attribute(name, value);
  if (!out->open(temporary.string(), spec)) {
    throw std::runtime_error("cannot write '" + path + "': " + out->geterror());
  }
  bool ok;
  if (asFloat) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  } else {
    const DisplayEncoder encode(exposure);
    std::vector<uint8_t> bytes(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      for (int c = 0; c < 3; ++c) bytes[3 * i + c] = encode(image.pixels[i][c]);
    }
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  }
  ok = out->close() && ok;
  if (!ok) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + out->geterror());
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, error);
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

std::string readImageText(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    OIIO::geterror();  // clear the error, nobody asks for it
    return {};
  }
  return in->spec().get_string_attribute(name);
}

ImageRgb readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read image '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw std::runtime_error("cannot read image '" + path + "': it has no pixels");
  }
  std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    throw std::runtime_error("cannot read image '" + path + "': " + in->geterror());
  }
  // Integer formats hold display-encoded (sRGB) values; float formats hold linear radiance.
  const bool encoded = !spec.format.is_floating_point();
  ImageRgb image(spec.width, spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* p = &data[i * spec.nchannels];
    Color c = spec.nchannels >= 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
    if (encoded) c = Color(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z));
    image.pixels[i] = c;
  }
  return image;
}

}  // namespace prism
