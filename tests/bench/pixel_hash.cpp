// prism_pixel_hash IMAGE...: one line per image, "HASH WIDTHxHEIGHT PATH", where HASH is FNV-1a 64
// of the image's float pixels as Prism reads them (EXR: the radiance itself). Two renders are the
// same image exactly when their hashes match, whatever the file's metadata says (the run summary
// in an EXR's comments differs between runs). Used by tests/bench/image_hashes.sh.
#include <cstdio>
#include <exception>

#include "image/ImageIo.h"
#include "wire/Messages.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: prism_pixel_hash IMAGE...\n");
    return 2;
  }
  int failures = 0;
  for (int i = 1; i < argc; ++i) {
    try {
      const prism::ImageRgb image = prism::readImage(argv[i]);
      const auto* bytes = reinterpret_cast<const uint8_t*>(image.pixels.data());
      const uint64_t hash =
          prism::wire::fnv1a64(bytes, image.pixels.size() * sizeof(image.pixels[0]));
      std::printf("%016llx %dx%d %s\n", static_cast<unsigned long long>(hash), image.width,
                  image.height, argv[i]);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "prism_pixel_hash: %s: %s\n", argv[i], e.what());
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
