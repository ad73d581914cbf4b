// The OpenImageIO module (prism_image_oiio.so, see image/OiioModule.h): the only code that
// includes OpenImageIO. Built as a CMake MODULE library and dlopen()ed by image/OiioModule.cpp the
// first time a process reads or writes a format other than PNG and EXR.
#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "image/OiioModule.h"

namespace prism {
namespace {

bool write(const std::string& path, int width, int height, bool floating, const void* pixels,
           const ImageMetadata& metadata, std::string* error) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    *error = OIIO::geterror();
    return false;
  }
  const OIIO::TypeDesc type = floating ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(width, height, 3, type);
  spec.attribute("oiio:ColorSpace", floating ? "Linear" : "sRGB");
  spec.attribute("Software", "Prism");
  for (const auto& [name, value] : metadata) spec.attribute(name, value);
  if (!out->open(path, spec)) {
    *error = out->geterror();
    return false;
  }
  bool ok = out->write_image(type, pixels);
  ok = out->close() && ok;
  if (!ok) *error = out->geterror();
  return ok;
}

bool read(const std::string& path, ImageRgb* image, bool* encoded, std::string* error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    *error = OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    *error = "it has no pixels";
    return false;
  }
  std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    *error = in->geterror();
    return false;
  }
  *encoded = !spec.format.is_floating_point();
  *image = ImageRgb(spec.width, spec.height);
  for (size_t i = 0; i < image->pixels.size(); ++i) {
    const float* p = &data[i * spec.nchannels];
    image->pixels[i] = spec.nchannels >= 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
  }
  return true;
}

bool readText(const std::string& path, const std::string& name, std::string* value) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    OIIO::geterror();  // clear the error, nobody asks for it
    return false;
  }
  *value = in->spec().get_string_attribute(name);
  return !value->empty();
}

bool canWrite(const std::string& path, std::string* error) {
  if (OIIO::ImageOutput::create(path)) return true;
  *error = OIIO::geterror();
  return false;
}

const OiioModuleApi kApi{kOiioModuleVersion, write, read, readText, canWrite};

}  // namespace
}  // namespace prism

extern "C" __attribute__((visibility("default"))) const prism::OiioModuleApi* prismOiioModule() {
  return &prism::kApi;
}
