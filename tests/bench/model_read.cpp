// The read of a model file alone (loadModelFile: an OBJ with its materials, a PLY), timed in one
// process: the median of ROUNDS reads, after one read that warms the page cache. Run two
// builds' binaries side by side to compare loaders (docs/performance.md):
//   build/tests/prism_model_read DIR/5m/big-mesh.obj 7
#include <cstdio>
#include <cstdlib>
#include <string>

#include "MedianTime.h"
#include "parse/ModelFile.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: prism_model_read FILE [ROUNDS (default 5)]\n");
    return 2;
  }
  const std::string path = argv[1];
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 5;
  size_t triangles = 0;
  const auto read = [&] {
    triangles = prism::loadModelFile(path, prism::FileLoc{}).triangleCount();
  };
  try {
    read();
    const double ms = prism::bench::medianMs(rounds, read);
    std::printf("%s: %zu triangles, median of %d reads %.1f ms\n", path.c_str(), triangles, rounds,
                ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
