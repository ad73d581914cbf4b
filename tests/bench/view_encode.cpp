// Bytes and time of a frame sent to a remote viewer (master/remote/ViewProtocol.h): a whole
// frame of display bytes as News, raw and zstd-compressed at several levels, for the default
// scene at 640x360 and 1920x1080, one sample per pixel (a frame while moving: noisy) and 16
// (a refined one). Prints medians and the link speed 30 frames/s need (docs/viewer.md).
// Usage: prism_view_encode [runs]
#include <zstd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "image/DisplayBytes.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/remote/ViewProtocol.h"
#include "parse/SceneLoader.h"

using namespace prism;
using bench::medianMs;

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  std::printf("%-10s %4s %10s %10s %8s %8s %10s\n", "frame", "spp", "codec", "bytes", "enc ms",
              "dec ms", "MB/s @30");
  for (const auto [width, height] : {std::pair{640, 360}, std::pair{1920, 1080}}) {
    for (const int spp : {1, 16}) {
      SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
      d.render.width = width;
      d.render.height = height;
      d.render.samplesPerPixel = spp;
      const Scene scene(d);
      const ImageRgb image = renderWithCaustics(scene, FrameOptions{}).image;
      DisplayNews news;
      news.started = true;
      news.width = width;
      news.height = height;
      news.patch = {0, 0, width, height};
      news.patchBytes = toDisplayBytes(image.pixels, d.render.exposure);
      const std::string size = std::to_string(width) + "x" + std::to_string(height);
      const double raw = static_cast<double>(news.patchBytes.size());
      std::printf("%-10s %4d %10s %10.0f %8s %8s %10.1f\n", size.c_str(), spp, "raw", raw, "-", "-",
                  raw * 30 / 1e6);
      for (const int level : {-5, -1, 1, 3}) {
        std::vector<uint8_t> packed(ZSTD_compressBound(news.patchBytes.size()));
        size_t bytes = 0;
        const double enc = medianMs(runs, [&] {
          bytes = ZSTD_compress(packed.data(), packed.size(), news.patchBytes.data(),
                                news.patchBytes.size(), level);
        });
        std::vector<uint8_t> back(news.patchBytes.size());
        const double dec = medianMs(
            runs, [&] { ZSTD_decompress(back.data(), back.size(), packed.data(), bytes); });
        const std::string codec = "zstd " + std::to_string(level);
        std::printf("%-10s %4d %10s %10zu %8.2f %8.2f %10.1f\n", size.c_str(), spp, codec.c_str(),
                    bytes, enc, dec, bytes * 30 / 1e6);
      }
      {  // PNG's Sub filter first: each byte minus the same channel of the pixel to its left
        std::vector<uint8_t> sub(news.patchBytes.size());
        for (size_t i = 0; i < sub.size(); ++i) {
          const bool rowStart = (i / 3) % static_cast<size_t>(width) == 0;
          sub[i] =
              static_cast<uint8_t>(news.patchBytes[i] - (rowStart ? 0 : news.patchBytes[i - 3]));
        }
        std::vector<uint8_t> packed(ZSTD_compressBound(sub.size()));
        size_t bytes = 0;
        const double enc = medianMs(runs, [&] {
          bytes = ZSTD_compress(packed.data(), packed.size(), sub.data(), sub.size(), 1);
        });
        std::printf("%-10s %4d %10s %10zu %8.2f %8s %10.1f\n", size.c_str(), spp, "sub+zstd 1",
                    bytes, enc, "-", bytes * 30 / 1e6);
      }
      // The message as the job sends it (level 1, fields and envelope included).
      size_t message = 0;
      const double send = medianMs(runs, [&] { message = view::encode(news).size(); });
      std::printf("%-10s %4d %10s %10zu %8.2f %8s %10.1f\n", size.c_str(), spp, "News msg", message,
                  send, "-", message * 30 / 1e6);
    }
  }
  return 0;
}
