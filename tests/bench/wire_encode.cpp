// Time to encode and decode a photon map message (rank 0 sends one to every slave per photon
// pass; each slave decodes it) and the share of the FNV-1a checksum in both
// (docs/journal/2026-11-26-photon-radii-across-ranks.md). Prints the median of the runs.
// Usage: prism_wire_encode [photons (415000: caustic-glass-sphere.yaml's stored)] [runs (5)]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "wire/Messages.h"

using namespace prism;
using bench::medianMs;

int main(int argc, char** argv) {
  const size_t count = argc > 1 ? std::stoul(argv[1]) : 415000;
  const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 5;
  std::vector<Photon> photons(count);
  for (size_t i = 0; i < count; ++i) {
    photons[i].position = Vec3(0.001f * static_cast<float>(i), 0.0f, 1.0f);
    photons[i].power = Color(1e-6f);
    photons[i].setDirection(Vec3(0.0f, -1.0f, 0.0f));
  }
  std::vector<uint8_t> bytes;
  const double encode =
      medianMs(runs, [&] { bytes = wire::encodePhotonMap(1, PhotonGatherSettings{}, photons); });
  // Decoded from a buffer of its own, as a slave receives it (the encoder's buffer is allocated
  // differently and reads at another speed).
  const std::vector<uint8_t> received(bytes.begin(), bytes.end());
  size_t decoded = 0;
  const double decode = medianMs(
      runs, [&] { decoded = wire::decodePhotonMap(wire::decodeMessage(received)).photons.size(); });
  volatile uint64_t sink = 0;
  const double checksum = medianMs(runs, [&] { sink = wire::fnv1a64(bytes.data(), bytes.size()); });
  std::printf(
      "photon map of %zu photons (%zu bytes, %zu decoded): encode %.1f ms, decode %.1f ms, "
      "checksum %.1f ms each way (medians of %d)\n",
      count, bytes.size(), decoded, encode, decode, checksum, runs);
  return decoded == count ? 0 : 1;
}
