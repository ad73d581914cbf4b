// The read of a model file alone (loadModelFile: an OBJ with its materials, a PLY), timed in one
// process: the median of ROUNDS reads, after one read that warms the page cache, and a checksum
// of the meshes' arrays (positions, normals, indices), so that two builds' binaries run side by
// side show they read the same mesh (docs/journal/2026-12-02-obj-mtl-and-ply-attributes.md):
//   build/tests/prism_model_read DIR/5m/big-mesh.obj 7
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "parse/ModelFile.h"

namespace {

// FNV-1a over the bytes of v.
template <class T>
uint64_t checksum(uint64_t hash, const std::vector<T>& v) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
  for (size_t i = 0; i < v.size() * sizeof(T); ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  return hash;
}

}  // namespace

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
    uint64_t hash = 14695981039346656037ull;
    for (const prism::MeshDesc& mesh : prism::loadModelFile(path, prism::FileLoc{}).meshes) {
      hash = checksum(checksum(checksum(hash, mesh.positions), mesh.normals), mesh.indices);
    }
    std::printf("%s: %zu triangles, checksum %016llx, median of %d reads %.1f ms\n", path.c_str(),
                triangles, static_cast<unsigned long long>(hash), rounds, ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
