// Load time of a big glTF model in its three forms (.glb, .gltf + .bin, .gltf with a base64 data
// URI) against the same mesh as binary PLY, alternating, medians (docs/dependencies.md, "glTF
// parsers measured"). The model is a grid of 2·N² triangles with positions, normals and u32
// indices, written to a temporary folder and removed afterwards.
// Usage: prism_gltf_load [N (default 1582: 5 M triangles)] [runs (default 7)]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "MedianTime.h"
#include "common/parse/GltfAssets.h"
#include "parse/GltfLoader.h"
#include "parse/PlyLoader.h"

using namespace prism;

namespace {

struct Grid {
  std::vector<float> positions, normals;
  std::vector<uint32_t> indices;
};

Grid grid(int n) {
  Grid g;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      g.positions.insert(g.positions.end(),
                         {float(i) / n, 0.01f * ((i * 7 + j * 3) % 11), float(j) / n});
      g.normals.insert(g.normals.end(), {0.0f, 1.0f, 0.0f});
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      g.indices.insert(g.indices.end(), {a, c, b, b, c, d});
    }
  }
  return g;
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ply(const Grid& g) {
  const size_t vertices = g.positions.size() / 3, triangles = g.indices.size() / 3;
  std::string out =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nelement face " +
      std::to_string(triangles) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (size_t v = 0; v < vertices; ++v) {
    out.append(reinterpret_cast<const char*>(&g.positions[3 * v]), 12);
    out.append(reinterpret_cast<const char*>(&g.normals[3 * v]), 12);
  }
  for (size_t t = 0; t < triangles; ++t) {
    out += '\3';
    out.append(reinterpret_cast<const char*>(&g.indices[3 * t]), 12);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::stoi(argv[1]) : 1582;
  const int runs = argc > 2 ? std::stoi(argv[2]) : 7;
  const auto dir = std::filesystem::temp_directory_path() / "prism-gltf-load";
  std::filesystem::create_directories(dir);
  uint64_t dataBytes = 0;
  {
    const Grid g = grid(n);
    gltftest::GltfAssets a;
    const int p = a.floats(g.positions, "VEC3", 3), nn = a.floats(g.normals, "VEC3", 3);
    const int i = a.indices32(g.indices);
    const std::string body =
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":" +
        std::to_string(p) + ",\"NORMAL\":" + std::to_string(nn) +
        "},\"indices\":" + std::to_string(i) + "}]}]";
    write(dir / "big.glb", a.glb(body));
    write(dir / "ext.gltf", a.json(body, "ext.bin"));
    write(dir / "ext.bin", a.bin);
    write(dir / "uri.gltf", a.gltf(body));
    write(dir / "big.ply", ply(g));
    dataBytes = a.bin.size();
    std::printf("%zu triangles, %zu vertices, %zu bytes of binary data; median of %d runs\n",
                g.indices.size() / 3, g.positions.size() / 3, a.bin.size(), runs);
  }
  for (const char* name : {"big.glb", "ext.gltf", "uri.gltf", "big.ply"}) {
    const std::string path = (dir / name).string();
    const bool isPly = path.ends_with(".ply");
    const double ms = bench::medianMs(runs, [&] {
      if (isPly) {
        loadPlyMesh(path, {});
      } else {
        loadGltfModel(path, {});
      }
    });
    std::printf("%-9s %10.1f ms  %6.2f GB/s of mesh data\n", name, ms, dataBytes / ms / 1e6);
  }
  std::filesystem::remove_all(dir);
}
