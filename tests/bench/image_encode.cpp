// Time and size of the PNG and EXR encoders on a rendered frame, for each zlib level, PNG row
// filter and EXR compression worth considering (docs/journal/2026-11-23-png-and-exr-encoding.md).
// Prints the median of the runs; the image is an EXR render (linear radiance), by default
// scenes/default.yaml at 512², made with
//   build/prism render scenes/default.yaml -W 512 -H 512 -o /tmp/frame.exr
// Usage: prism_image_encode [frame.exr] [runs]
#include <OpenEXR/openexr.h>
#include <png.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "image/ExrFile.h"
#include "image/ImageIo.h"
#include "image/PngFile.h"
#include "image/ToneMap.h"

using namespace prism;
using bench::medianMs;

namespace {

double kib(const std::string& path) {
  return std::filesystem::file_size(path) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string input = argc > 1 ? argv[1] : "/tmp/frame.exr";
  const int runs = argc > 2 ? std::stoi(argv[2]) : 15;
  const ImageRgb image = readImage(input);
  const std::string out = (std::filesystem::temp_directory_path() / "prism-image-encode").string();
  std::printf("%s: %dx%d, median of %d runs\n", input.c_str(), image.width, image.height, runs);

  // Tone mapping alone (part of every PNG write).
  std::vector<uint8_t> bytes(image.pixels.size() * 3);
  const double toneMs = medianMs(runs, [&] {
    const DisplayEncoder encode(1.0f);
    for (size_t i = 0; i < image.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) bytes[3 * i + c] = encode(image.pixels[i][c]);
  });
  std::printf("tone map to sRGB bytes: %.2f ms\n", toneMs);

  struct Filter {
    const char* name;
    int bits;
  };
  const Filter filters[] = {{"none", PNG_FILTER_NONE},  {"sub", PNG_FILTER_SUB},
                            {"up", PNG_FILTER_UP},      {"paeth", PNG_FILTER_PAETH},
                            {"fast", PNG_FAST_FILTERS}, {"all", PNG_ALL_FILTERS}};
  std::printf("\nPNG (libpng %s, encode only)\n%-8s %6s %10s %10s\n", PNG_LIBPNG_VER_STRING,
              "filter", "level", "ms", "KiB");
  for (const Filter& f : filters) {
    for (int level : {0, 1, 2, 3, 6}) {
      const PngEncoding encoding{level, f.bits};
      const std::string path = out + ".png";
      const double ms = medianMs(
          runs, [&] { writePng(path, image.width, image.height, bytes.data(), {}, encoding); });
      std::printf("%-8s %6d %10.2f %10.1f\n", f.name, level, ms, kib(path));
    }
  }
  {
    const std::string path = out + "-default.png";
    const double ms = medianMs(runs, [&] { writeImage(image, path); });
    std::printf("writeImage(.png), the default, tone mapping included: %.2f ms, %.1f KiB\n", ms,
                kib(path));
  }

  struct Compression {
    const char* name;
    int value;
  };
  const Compression compressions[] = {{"none", EXR_COMPRESSION_NONE},
                                      {"rle", EXR_COMPRESSION_RLE},
                                      {"zips", EXR_COMPRESSION_ZIPS},
                                      {"zip", EXR_COMPRESSION_ZIP},
                                      {"piz", EXR_COMPRESSION_PIZ}};
  std::printf("\nEXR (OpenEXRCore, 32-bit float RGB)\n%-8s %6s %10s %10s\n", "method", "level",
              "ms", "KiB");
  for (const Compression& c : compressions) {
    const bool zip = c.value == EXR_COMPRESSION_ZIP || c.value == EXR_COMPRESSION_ZIPS;
    for (int level : zip ? std::vector<int>{1, 4, 6} : std::vector<int>{0}) {
      const std::string path = out + ".exr";
      const double ms = medianMs(runs, [&] {
        writeExr(path, image, {}, ExrEncoding{c.value, level});
      });
      std::printf("%-8s %6d %10.2f %10.1f\n", c.name, level, ms, kib(path));
    }
  }
  {
    const std::string path = out + "-default.exr";
    const double ms = medianMs(runs, [&] { writeImage(image, path); });
    std::printf("writeImage(.exr), the default: %.2f ms, %.1f KiB\n", ms, kib(path));
  }
  for (const char* suffix : {".png", "-default.png", ".exr", "-default.exr"}) {
    std::filesystem::remove(out + suffix);
  }
}
