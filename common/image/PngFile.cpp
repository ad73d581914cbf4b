#include "image/PngFile.h"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace prism {
namespace {

// libpng reports errors by longjmp()ing back to the setjmp() of the call that failed. Between
// the two only plain C data may live on the stack (a longjmp skips destructors), so each libpng
// session runs inside one function whose locals are all trivially destructible, and the message
// is copied into a fixed buffer that the caller turns into an exception.
struct PngError {
  char message[256] = "";
};

void onError(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof(error->message), "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // warnings never stop a read or a write

// The PNG keyword for an attribute name: OpenImageIO's convention, so files read the same
// whichever library wrote them.
const char* pngKeyword(const std::string& name) {
  return name == "ImageDescription" ? "Description" : name.c_str();
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File openFile(const std::string& path, const char* mode) {
  File file(std::fopen(path.c_str(), mode));
  if (!file) throw std::runtime_error(std::strerror(errno));
  return file;
}

bool encode(std::FILE* file, int width, int height, const uint8_t* rgb, png_text* texts,
            int textCount, const PngEncoding& encoding, PngError* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_compression_level(png, encoding.zlibLevel);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, encoding.filters);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  // sRGB with the gAMA and cHRM chunks that tell older readers the same thing.
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
  if (textCount > 0) png_set_text(png, info, texts, textCount);
  png_write_info(png, info);
  const size_t stride = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    png_write_row(png, rgb + static_cast<size_t>(y) * stride);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// A libpng read session. The steps below each set their own setjmp() and hold only plain data;
// the vectors they fill are sized by the caller between steps.
class PngReader {
 public:
  PngReader(std::FILE* file) {
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error_, onError, onWarning);
    if (png_) info_ = png_create_info_struct(png_);
    if (info_) png_init_io(png_, file);
  }
  ~PngReader() {
    if (png_) png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr);
  }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;

  // Reads everything up to the image data.
  bool readInfo() {
    if (!info_) return false;
    if (setjmp(png_jmpbuf(png_))) return false;
    png_read_info(png_, info_);
    return true;
  }

  // 8-bit RGB or grey without transparency: the PNGs read here.
  bool isPlain() const {
    const int colorType = png_get_color_type(png_, info_);
    return png_get_bit_depth(png_, info_) == 8 &&
           (colorType == PNG_COLOR_TYPE_RGB || colorType == PNG_COLOR_TYPE_GRAY) &&
           !png_get_valid(png_, info_, PNG_INFO_tRNS);
  }
  int width() const { return static_cast<int>(png_get_image_width(png_, info_)); }
  int height() const { return static_cast<int>(png_get_image_height(png_, info_)); }

  ImageMetadata texts() const {
    png_textp text = nullptr;
    int count = 0;
    png_get_text(png_, info_, &text, &count);
    ImageMetadata result;
    for (int i = 0; i < count; ++i) {
      const size_t length = text[i].text_length ? text[i].text_length : text[i].itxt_length;
      result.emplace_back(text[i].key, std::string(text[i].text, length));
    }
    return result;
  }

  // Decodes a plain PNG into rows (one pointer per row, 3·width bytes each).
  bool readRows(png_bytep* rows) {
    if (setjmp(png_jmpbuf(png_))) return false;
    if (png_get_color_type(png_, info_) == PNG_COLOR_TYPE_GRAY) png_set_gray_to_rgb(png_);
    png_set_interlace_handling(png_);
    png_read_update_info(png_, info_);
    png_read_image(png_, rows);
    png_read_end(png_, nullptr);
    return true;
  }

  std::string error() const { return *error_.message ? error_.message : "not a readable PNG"; }

 private:
  PngError error_;
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

// Bytes in memory as libpng's input.
struct MemoryInput {
  const uint8_t* data;
  size_t size;
  size_t at = 0;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* in = static_cast<MemoryInput*>(png_get_io_ptr(png));
  if (length > in->size - in->at) png_error(png, "the PNG data ends early");
  std::memcpy(out, in->data + in->at, length);
  in->at += length;
}

// decodePng's session: every libpng call between setjmp and return, plain data only on the
// stack (see PngError). Fills width, height and whether the rows are 16-bit and had alpha;
// sizeRows is called once the size is known and returns the row pointers (or null to stop).
template <class SizeRows>
bool decodeSession(MemoryInput* input, PngError* error, int* width, int* height, bool* sixteen,
                   bool* alpha, SizeRows&& sizeRows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, input, readFromMemory);
  png_read_info(png, info);
  *width = static_cast<int>(png_get_image_width(png, info));
  *height = static_cast<int>(png_get_image_height(png, info));
  const int colorType = png_get_color_type(png, info);
  *sixteen = png_get_bit_depth(png, info) == 16;
  *alpha = (colorType & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS);
  png_set_expand(png);  // palette to RGB, grey below 8 bits to 8, tRNS to alpha
  png_set_strip_alpha(png);
  if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA) {
    png_set_gray_to_rgb(png);
  }
  if (*sixteen) png_set_swap(png);  // little-endian 16-bit values
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_bytep* rows = sizeRows();
  if (!rows) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

PngPixels decodePng(std::span<const uint8_t> bytes, uint64_t maxPixels) {
  MemoryInput input{bytes.data(), bytes.size()};
  PngError error;
  int width = 0, height = 0;
  bool sixteen = false, alpha = false, tooLarge = false;
  std::vector<uint8_t> data;
  std::vector<png_bytep> rows;
  const bool decoded = decodeSession(&input, &error, &width, &height, &sixteen, &alpha, [&] {
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    if (pixels > maxPixels || width <= 0 || height <= 0) {
      tooLarge = true;
      return static_cast<png_bytep*>(nullptr);
    }
    const size_t stride = size_t(width) * 3 * (sixteen ? 2 : 1);
    data.resize(stride * size_t(height));
    rows.resize(size_t(height));
    for (int y = 0; y < height; ++y) rows[y] = data.data() + size_t(y) * stride;
    return rows.data();
  });
  if (tooLarge) {
    throw std::runtime_error("a " + std::to_string(width) + "x" + std::to_string(height) +
                             " image is larger than allowed");
  }
  if (!decoded) throw std::runtime_error(*error.message ? error.message : "not a readable PNG");
  PngPixels result;
  result.hadAlpha = alpha;
  if (!sixteen) {
    result.srgb = SrgbImage{width, height, std::move(data)};
    return result;
  }
  result.linear = ImageRgb(width, height);
  const size_t values = size_t(width) * size_t(height) * 3;
  for (size_t i = 0; i < values; ++i) {
    uint16_t v;
    std::memcpy(&v, data.data() + 2 * i, 2);
    const float encoded = static_cast<float>(v) * (1.0f / 65535.0f);
    const float linear =
        encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
    result.linear.pixels[i / 3][static_cast<int>(i % 3)] = linear;
  }
  return result;
}

void writePng(const std::string& path, int width, int height, const uint8_t* rgb,
              const ImageMetadata& metadata, const PngEncoding& encoding) {
  ImageMetadata all{{"Software", "Prism"}};
  all.insert(all.end(), metadata.begin(), metadata.end());
  std::vector<png_text> texts(all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    texts[i] = png_text{};
    texts[i].compression = PNG_TEXT_COMPRESSION_NONE;
    texts[i].key = const_cast<char*>(pngKeyword(all[i].first));
    texts[i].text = const_cast<char*>(all[i].second.c_str());
    texts[i].text_length = all[i].second.size();
  }
  const File file = openFile(path, "wb");
  PngError error;
  if (!encode(file.get(), width, height, rgb, texts.data(), static_cast<int>(texts.size()),
              encoding, &error)) {
    throw std::runtime_error(*error.message ? error.message : "libpng cannot write it");
  }
  if (std::fflush(file.get()) != 0 || std::ferror(file.get())) {
    throw std::runtime_error(std::strerror(errno));
  }
}

std::optional<SrgbImage> readPng(const std::string& path) {
  const File file = openFile(path, "rb");
  PngReader reader(file.get());
  if (!reader.readInfo()) throw std::runtime_error(reader.error());
  if (!reader.isPlain()) return std::nullopt;
  SrgbImage pixels;
  pixels.width = reader.width();
  pixels.height = reader.height();
  pixels.rgb.resize(static_cast<size_t>(pixels.width) * pixels.height * 3);
  std::vector<png_bytep> rows(pixels.height);
  for (int y = 0; y < pixels.height; ++y) {
    rows[y] = pixels.rgb.data() + static_cast<size_t>(y) * pixels.width * 3;
  }
  if (!reader.readRows(rows.data())) throw std::runtime_error(reader.error());
  return pixels;
}

std::optional<std::string> readPngText(const std::string& path, const std::string& name) {
  std::FILE* raw = std::fopen(path.c_str(), "rb");
  if (!raw) return std::nullopt;
  const File file(raw);
  PngReader reader(file.get());
  if (!reader.readInfo()) return std::nullopt;
  const std::string keyword = pngKeyword(name);
  for (const auto& [key, value] : reader.texts()) {
    if (key == keyword) return value;
  }
  return std::nullopt;
}

}  // namespace prism
