// Closed meshes for intersection tests.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "math/Vec.h"

namespace prism::test {

struct TestMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // three per triangle, consistently wound outwards
};

// An icosahedron subdivided `levels` times and pushed onto a sphere of the given centre and
// radius: closed, with every edge shared by exactly two triangles.
inline TestMesh icosphere(int levels, Vec3 centre, float radius) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> unit = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                            {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                            {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& v : unit) v = glm::normalize(v);
  std::vector<uint32_t> faces = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      unit.push_back(glm::normalize(unit[a] + unit[b]));
      const uint32_t index = static_cast<uint32_t>(unit.size() - 1);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<uint32_t> next;
    for (size_t f = 0; f < faces.size(); f += 3) {
      const uint32_t a = faces[f], b = faces[f + 1], c = faces[f + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    faces = std::move(next);
  }
  TestMesh mesh;
  for (const Vec3& v : unit) mesh.positions.push_back(centre + radius * v);
  mesh.indices = std::move(faces);
  return mesh;
}

}  // namespace prism::test
