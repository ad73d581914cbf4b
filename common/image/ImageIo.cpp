#include "image/ImageIo.h"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include "image/ExrFile.h"
#include "image/OiioModule.h"
#include "image/PngFile.h"
#include "image/ToneMap.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

enum class Format { kPng, kExr, kOther };

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Format formatOf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") return Format::kPng;
  if (ext == ".exr") return Format::kExr;
  return Format::kOther;
}

// Formats that store floating-point radiance get it untouched; the rest are display formats.
bool isFloatFormat(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

std::vector<uint8_t> displayBytes(const ImageRgb& image, float exposure) {
  const DisplayEncoder encode(exposure);
  std::vector<uint8_t> bytes(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) bytes[3 * i + c] = encode(image.pixels[i][c]);
  }
  return bytes;
}

// Integer formats hold display-encoded (sRGB) values; float formats hold linear radiance.
void linearise(ImageRgb& image) {
  for (Color& c : image.pixels) c = Color(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z));
}

void writeWithOpenImageIo(const ImageRgb& image, const std::string& path,
                          const std::string& temporary, float exposure,
                          const ImageMetadata& metadata) {
  const OiioModuleApi& oiio = oiioModule("cannot write '" + path + "'");
  const bool floating = isFloatFormat(path);
  std::vector<uint8_t> bytes;
  if (!floating) bytes = displayBytes(image, exposure);
  std::string error;
  const void* pixels = floating ? static_cast<const void*>(image.pixels.data()) : bytes.data();
  if (!oiio.write(temporary, image.width, image.height, floating, pixels, metadata, &error)) {
    throw std::runtime_error(error);
  }
}

}  // namespace

ImageRgb readImageWithOpenImageIo(const std::string& path) {
  const OiioModuleApi& oiio = oiioModule("cannot read image '" + path + "'");
  ImageRgb image;
  bool encoded = false;
  std::string error;
  if (!oiio.read(path, &image, &encoded, &error)) {
    throw std::runtime_error("cannot read image '" + path + "': " + error);
  }
  if (encoded) linearise(image);
  return image;
}

bool isWritableImagePath(const std::string& path, std::string* why) {
  const std::string ext = fs::path(path).extension().string();
  if (ext.empty()) {
    if (why) *why = "output '" + path + "' has no extension (use .png or .exr)";
    return false;
  }
  if (formatOf(path) != Format::kOther) return true;
  std::string error;
  try {
    if (oiioModule("cannot write '" + ext + "' images").canWrite(path, &error)) return true;
  } catch (const std::runtime_error& e) {
    if (why) *why = e.what();
    return false;
  }
  if (why) *why = "cannot write '" + ext + "' images: " + error;
  return false;
}

namespace {

// Writes through a temporary file beside path (write(temporary) fills it), renamed on success.
template <class Write>
void writeThroughTemporary(const std::string& path, Write write) {
  const fs::path target(path);
  // Keep the extension on the temporary name: OpenImageIO picks the format from it.
  std::string name = ".";  // appended piecewise: GCC 12 warns (-Wrestrict) about "." + a + b
  name += target.stem().string();
  name += ".tmp-" + std::to_string(::getpid());
  name += target.extension().string();
  const fs::path temporary = target.parent_path() / name;
  try {
    write(temporary.string());
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    const std::string message = e.what();
    // The module's loader already names the file.
    if (message.rfind("cannot write '" + path + "'", 0) == 0) throw;
    throw std::runtime_error("cannot write '" + path + "': " + message);
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, error);
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

}  // namespace

void writeImage(const ImageRgb& image, const std::string& path, float exposure,
                const ImageMetadata& metadata) {
  writeThroughTemporary(path, [&](const std::string& temporary) {
    switch (formatOf(path)) {
      case Format::kPng: {
        const std::vector<uint8_t> bytes = displayBytes(image, exposure);
        writePng(temporary, image.width, image.height, bytes.data(), metadata);
        break;
      }
      case Format::kExr:
        writeExr(temporary, image, metadata);
        break;
      case Format::kOther:
        writeWithOpenImageIo(image, path, temporary, exposure, metadata);
        break;
    }
  });
}

void writeDisplayPng(const std::string& path, int width, int height,
                     const std::vector<uint8_t>& rgb) {
  if (formatOf(path) != Format::kPng) {
    throw std::runtime_error("cannot write '" + path + "': display bytes are written as PNG only");
  }
  if (rgb.size() != static_cast<size_t>(width) * height * 3) {
    throw std::runtime_error("cannot write '" + path + "': the bytes are not " +
                             std::to_string(width) + "x" + std::to_string(height) + " RGB");
  }
  writeThroughTemporary(path, [&](const std::string& temporary) {
    writePng(temporary, width, height, rgb.data(), {});
  });
}

std::string readImageText(const std::string& path, const std::string& name) {
  switch (formatOf(path)) {
    case Format::kPng:
      return readPngText(path, name).value_or("");
    case Format::kExr:
      return readExrText(path, name).value_or("");
    case Format::kOther:
      break;
  }
  std::string value;
  try {
    if (oiioModule(path).readText(path, name, &value)) return value;
  } catch (const std::runtime_error&) {
    // No module: the file's text cannot be read, which is what "" says.
  }
  return {};
}

std::optional<SrgbImage> readSrgbImage(const std::string& path) {
  if (formatOf(path) != Format::kPng) return std::nullopt;
  try {
    return readPng(path);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot read image '" + path + "': " + e.what());
  }
}

ImageRgb readImage(const std::string& path) {
  try {
    switch (formatOf(path)) {
      case Format::kPng:
        if (auto png = readPng(path)) return linearFromSrgb(*png);
        break;  // a PNG of another kind
      case Format::kExr:
        if (auto exr = readExr(path)) return std::move(*exr);
        break;  // an EXR of another kind
      case Format::kOther:
        break;
    }
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot read image '" + path + "': " + e.what());
  }
  return readImageWithOpenImageIo(path);
}

}  // namespace prism
