#include "master/ResourceCheck.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace prism {

uint64_t frameMemoryBytes(const RenderSettings& s) {
  const double pixels = static_cast<double>(s.width) * static_cast<double>(s.height);
  const double bytes = 2.0 * pixels * sizeof(Color);  // frame buffer + tiles in flight
  return bytes >= 1.8e19 ? UINT64_MAX : static_cast<uint64_t>(bytes);
}

uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return UINT64_MAX;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize);
}

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

void checkRenderFits(const RenderSettings& s, uint64_t availableBytes) {
  const uint64_t needed = frameMemoryBytes(s);
  // Leave room for the scene, the BVH and the rest of the system.
  if (needed > availableBytes / 2) {
    throw std::runtime_error(
        "a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image needs " +
        formatBytes(static_cast<double>(needed)) + " for its frame buffer; this machine has " +
        formatBytes(static_cast<double>(availableBytes)) + " of memory (reduce --width/--height)");
  }
}

uint64_t photonMemoryBytes(const CausticSettings& c) {
  if (c.method != CausticMethod::PhotonMap) return 0;
  // 28-byte photons held three times (shares, map, outgoing message) plus a 4-byte tree index
  // and about one 8-byte node share per photon.
  constexpr double kBytesPerPhoton = 3.0 * 28.0 + 4.0 + 8.0;
  const double bytes = static_cast<double>(c.photons) * kBytesPerPhoton;
  return bytes >= 1.8e19 ? UINT64_MAX : static_cast<uint64_t>(bytes);
}

void checkCausticsFit(const CausticSettings& c, uint64_t availableBytes) {
  const uint64_t needed = photonMemoryBytes(c);
  if (needed > availableBytes / 2) {
    throw std::runtime_error(std::to_string(c.photons) + " photons per pass may need " +
                             formatBytes(static_cast<double>(needed)) +
                             " for the photon map; this machine has " +
                             formatBytes(static_cast<double>(availableBytes)) +
                             " of memory (reduce --photons, or use more --passes of fewer)");
  }
}

}  // namespace prism
