// Writes the wire fuzzer's seeds into tests/fuzz/corpus/wire: one full message of each type (for
// the envelope checks) and the same payload behind a type byte (the harness's second form), so
// the fuzzer starts inside every payload decoder. Scenes come from the example scene files.
// (the long runs then merged more inputs into that folder):
//   build/tests/fuzz/prism_fuzz_wire_seeds tests/fuzz/corpus/wire
//       scenes/caustic-{glass-sphere,ring}.yaml scenes/caustic-map-*.yaml scenes/lambert-plane.yaml
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "parse/SceneLoader.h"
#include "wire/Messages.h"

namespace {

using namespace prism;
using namespace prism::wire;

void writeFile(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

void writeSeed(const std::string& dir, const std::string& name, const std::vector<uint8_t>& bytes) {
  writeFile(dir + "/" + name + ".msg", bytes);
  // The payload behind its type byte.
  const Message message = decodeMessage(bytes);
  std::vector<uint8_t> typed = {static_cast<uint8_t>(message.type)};
  typed.insert(typed.end(), message.payload.begin(), message.payload.end());
  writeFile(dir + "/" + name + ".typed", typed);
}

std::vector<Photon> somePhotons() {
  std::vector<Photon> photons(3);
  for (int i = 0; i < 3; ++i) {
    photons[i].position = Vec3(float(i), 1.0f, -2.0f);
    photons[i].power = Color(0.5f, 0.25f, 0.125f);
    photons[i].setDirection(glm::normalize(Vec3(0.0f, -1.0f, 0.1f * float(i))));
  }
  return photons;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR [SCENE...]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string path = argv[i];
    const std::string stem = path.substr(path.find_last_of('/') + 1);
    writeSeed(dir, "scene-" + stem.substr(0, stem.find('.')), encodeScene(loadScene(path)));
  }
  writeSeed(dir, "ready", encodeReady({0.25, 8}));
  writeSeed(dir, "tile-job",
            encodeTileJob({3, 7, {16, 32, 16, 16}, 1, kTermDirect | kTermCaustics}));
  TileResultMessage result;
  result.frame = 3;
  result.result.tileIndex = 7;
  result.result.rect = {16, 32, 2, 2};
  result.result.pixels.assign(4, Color(0.5f, 1.0f, 2.0f));
  result.result.rays = {4, 8, 16};
  result.result.seconds = 0.01;
  writeSeed(dir, "tile-result", encodeTileResult(result));
  result.displayExposure = 1.5f;  // a frame only shown: display bytes
  writeSeed(dir, "tile-result-display", encodeTileResult(result));
  writeSeed(dir, "shutdown", encodeShutdown());
  writeSeed(dir, "error", encodeError({"slave 2: out of memory"}));
  writeSeed(dir, "progress", encodeProgress({3, 12, {4, 5, 9}}));
  writeSeed(dir, "photon-job", encodePhotonJob({1, 1000, 500, 4000}));
  PhotonShareMessage share;
  share.pass = 1;
  share.first = 1000;
  share.count = 500;
  share.stats = {500, 3, 400, 100};
  share.seconds = 0.5;
  share.photons = somePhotons();
  writeSeed(dir, "photon-share", encodePhotonShare(share));
  writeSeed(dir, "photon-map", encodePhotonMap(1, PhotonGatherSettings{}, somePhotons()));
  ViewMessage view;
  view.frame = 4;
  view.liveFrom = 3;
  view.view.camera = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml").camera;
  view.view.width = 320;
  view.view.height = 240;
  view.view.samplesPerPixel = 2;
  view.view.seed = 99;
  view.view.displayExposure = 1.5f;
  writeSeed(dir, "view", encodeView(view));
  writeSeed(dir, "echo", encodeEcho({5, std::string(64, 'x')}));
  writeSeed(dir, "photon-cancel", encodePhotonCancel({3}));
  writeSeed(dir, "photon-map-again", encodePhotonMapAgain({9, 4}));
  writeSeed(dir, "photon-radii-job", encodePhotonRadiiJob({9, 64, 200}));
  writeSeed(dir, "photon-radii-share", encodePhotonRadiiShare({9, 64, {0.5f, 0.25f, 0.125f}}));
  writeSeed(dir, "photon-radii", encodePhotonRadii({9, {0.5f, 0.25f, 0.125f}}));
  // Refused ones: a truncated message and a flipped payload byte.
  std::vector<uint8_t> bytes = encodeReady({0.25, 8});
  bytes.pop_back();
  writeFile(dir + "/bad-truncated.msg", bytes);
  bytes = encodeError({"flipped"});
  bytes.back() ^= 1;
  writeFile(dir + "/bad-checksum.msg", bytes);
  return 0;
}
