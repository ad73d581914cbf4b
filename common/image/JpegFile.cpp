#include "image/JpegFile.h"

// jpeglib.h needs FILE and size_t declared before it.
#include <cstddef>
#include <cstdio>
// clang-format off
#include <jpeglib.h>
// clang-format on

#include <csetjmp>
#include <stdexcept>
#include <string>
#include <vector>

namespace prism {
namespace {

// libjpeg reports errors through error_exit, which must not return: it longjmp()s back to the
// session's setjmp with the message copied, as PngFile.cpp does for libpng.
struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "";
};

void onError(j_common_ptr info) {
  auto* error = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->jump, 1);
}

void onMessage(j_common_ptr, int) {}  // warnings and traces never stop a read

// The session: plain data only between setjmp and return. sizeRows is called once the output
// size is known and returns where the rows go (null to stop).
template <class SizeRows>
bool decodeSession(std::span<const uint8_t> bytes, JpegError* error, int* width, int* height,
                   SizeRows&& sizeRows) {
  jpeg_decompress_struct info;
  info.err = jpeg_std_error(&error->manager);
  error->manager.error_exit = onError;
  error->manager.emit_message = onMessage;
  if (setjmp(error->jump)) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;  // grey, YCbCr and CMYK alike
  jpeg_start_decompress(&info);
  *width = static_cast<int>(info.output_width);
  *height = static_cast<int>(info.output_height);
  uint8_t* out = sizeRows();
  if (!out || info.output_components != 3) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  const size_t stride = size_t(*width) * 3;
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = out + size_t(info.output_scanline) * stride;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

}  // namespace

SrgbImage decodeJpeg(std::span<const uint8_t> bytes, uint64_t maxPixels) {
  JpegError error;
  SrgbImage image;
  bool tooLarge = false;
  const bool decoded = decodeSession(bytes, &error, &image.width, &image.height, [&] {
    const uint64_t pixels = uint64_t(image.width) * uint64_t(image.height);
    if (pixels > maxPixels || image.width <= 0 || image.height <= 0) {
      tooLarge = true;
      return static_cast<uint8_t*>(nullptr);
    }
    image.rgb.resize(size_t(pixels) * 3);
    return image.rgb.data();
  });
  if (tooLarge) {
    throw std::runtime_error("a " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " image is larger than allowed");
  }
  if (!decoded) throw std::runtime_error(*error.message ? error.message : "not a readable JPEG");
  return image;
}

}  // namespace prism
