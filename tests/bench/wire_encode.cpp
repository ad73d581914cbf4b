// Time to encode and decode a photon map message (rank 0 sends one to every slave per photon
// pass; each slave decodes it) and the share of the FNV-1a checksum in both
// (docs/journal/2026-11-26-photon-radii-across-ranks.md), then the tile results of a 1920x1080
// frame in 32x32 tiles, as radiance and as display bytes (a frame only shown). Prints the median
// of the runs.
// Usage: prism_wire_encode [photons (415000: caustic-glass-sphere.yaml's stored)] [runs (5)]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "wire/Messages.h"

using namespace prism;
using bench::medianMs;

namespace {

// Every tile of a 1920x1080 frame in 32x32 tiles (2040 tiles), encoded, then decoded.
bool tileResults(int runs) {
  std::vector<wire::TileResultMessage> tiles;
  for (int y = 0; y < 1080; y += 32) {
    for (int x = 0; x < 1920; x += 32) {
      wire::TileResultMessage m;
      m.frame = 1;
      m.result.tileIndex = static_cast<uint32_t>(tiles.size());
      m.result.rect = {x, y, 32, std::min(32, 1080 - y)};
      m.result.pixels.resize(static_cast<size_t>(m.result.rect.pixelCount()));
      for (size_t i = 0; i < m.result.pixels.size(); ++i) {
        m.result.pixels[i] = Color(0.001f * static_cast<float>(i % 997), 0.5f, 2.0f);
      }
      m.result.seconds = 0.01;
      tiles.push_back(std::move(m));
    }
  }
  bool ok = true;
  for (const float exposure : {0.0f, 1.0f}) {
    std::vector<std::vector<uint8_t>> bytes(tiles.size());
    const double encode = medianMs(runs, [&] {
      for (size_t i = 0; i < tiles.size(); ++i) {
        tiles[i].displayExposure = exposure;
        bytes[i] = wire::encode(tiles[i]);
      }
    });
    size_t pixels = 0;
    const double decode = medianMs(runs, [&] {
      pixels = 0;
      for (const std::vector<uint8_t>& b : bytes) {
        pixels +=
            wire::decode<wire::TileResultMessage>(wire::decodeMessage(b)).result.pixels.size();
      }
    });
    std::printf(
        "tile results of a 1920x1080 frame as %s (%zu tiles): encode %.2f ms, decode %.2f ms "
        "(medians of %d)\n",
        exposure > 0.0f ? "display bytes" : "radiance", tiles.size(), encode, decode, runs);
    ok = ok && pixels == size_t{1920} * 1080;
  }
  return ok;
}

}  // namespace

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
  const double decode = medianMs(runs, [&] {
    decoded = wire::decode<wire::PhotonMapMessage>(wire::decodeMessage(received)).photons.size();
  });
  volatile uint64_t sink = 0;
  const double checksum = medianMs(runs, [&] { sink = wire::fnv1a64(bytes.data(), bytes.size()); });
  std::printf(
      "photon map of %zu photons (%zu bytes, %zu decoded): encode %.1f ms, decode %.1f ms, "
      "checksum %.1f ms each way (medians of %d)\n",
      count, bytes.size(), decoded, encode, decode, checksum, runs);
  return decoded == count && tileResults(runs) ? 0 : 1;
}
