// OpenImageIO, loaded on first use. Prism writes PNG and EXR with libpng and OpenEXR (PngFile.h,
// ExrFile.h); every other format, and the rare PNG or EXR variant those readers leave alone, goes
// through OpenImageIO. Linking OpenImageIO would cost every process ~0.35 s and ~120 MiB at start
// (Debian's build pulls in 260 shared libraries, docs/dependencies.md), so it lives in a module of
// its own, prism_image_oiio.so, that is dlopen()ed the first time such a file is read or written.
// A process that never touches one never maps libOpenImageIO.
#pragma once

#include <string>

#include "image/ImageIo.h"

namespace prism {

// What the module exports: plain functions that report failure through their return value and an
// error string, so no exception crosses the dlopen boundary. The module is built from the same
// sources in the same build as the executable; kOiioModuleVersion guards against a stale one.
inline constexpr int kOiioModuleVersion = 1;

struct OiioModuleApi {
  int version;
  // Writes width×height RGB pixels, row-major from the top left, to path (the format follows the
  // extension): 32-bit floats when floating, else bytes already display-encoded (sRGB).
  bool (*write)(const std::string& path, int width, int height, bool floating, const void* pixels,
                const ImageMetadata& metadata, std::string* error);
  // Reads the first three channels (one channel is grey) as floats, normalised as OpenImageIO
  // normalises integers (byte/255); *encoded tells whether the file stores integers, which hold
  // display-encoded values the caller linearises.
  bool (*read)(const std::string& path, ImageRgb* image, bool* encoded, std::string* error);
  // The text attribute name of path under OpenImageIO's naming; false when absent or unreadable.
  bool (*readText)(const std::string& path, const std::string& name, std::string* value);
  // Whether OpenImageIO has a writer for path's extension; *error says why not.
  bool (*canWrite)(const std::string& path, std::string* error);
};

// The entry point the module exports under C linkage (no name mangling to guess at in dlsym).
extern "C" {
using OiioModuleEntry = const OiioModuleApi* (*)();
}
inline constexpr const char* kOiioModuleEntryName = "prismOiioModule";

// Loads the module on first call (thread-safe) and returns its functions. Looks next to the
// running executable, then where the build put it; $PRISM_OIIO_MODULE, when set, replaces both.
// Throws std::runtime_error saying where it looked and what to do when it cannot be loaded; `what`
// names the file that needed it.
const OiioModuleApi& oiioModule(const std::string& what);

// Whether this process has loaded the module (for tests and the run summary).
bool oiioModuleLoaded();

}  // namespace prism
