#include "wire/SceneCodec.h"

#include <algorithm>

#include "scene/SceneValidation.h"
#include "wire/FieldCodec.h"

namespace prism::wire {
namespace {

// "sphere 3 (scene.yaml:12:5)", so a bad entity can be found in the file it came from.
std::string describe(const char* kind, size_t index, const FileLoc& loc) {
  std::string s = std::string(kind) + " " + std::to_string(index);
  const std::string where = loc.toString();
  if (!where.empty()) s += " (" + where + ")";
  return s;
}

// Scene::surface indexes normals with the position indices and Scene reads three indices per
// triangle, so every one of these would read out of bounds.
void checkMesh(const MeshDesc& m, size_t index) {
  const auto fail = [&](const std::string& what) {
    throw WireError(describe("mesh", index, m.loc) + " '" + m.source + "': " + what);
  };
  if (!m.normals.empty() && m.normals.size() != m.positions.size()) {
    fail(std::to_string(m.normals.size()) + " normals for " + std::to_string(m.positions.size()) +
         " positions");
  }
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) {
    fail(std::to_string(m.uvs.size()) + " texture coordinates for " +
         std::to_string(m.positions.size()) + " positions");
  }
  if (!m.colors.empty() && m.colors.size() != m.positions.size()) {
    fail(std::to_string(m.colors.size()) + " colours for " + std::to_string(m.positions.size()) +
         " positions");
  }
  if (m.indices.size() % 3 != 0) {
    fail(std::to_string(m.indices.size()) + " indices, not a multiple of 3");
  }
  if (!m.faceMaterials.empty() && m.faceMaterials.size() != m.triangleCount()) {
    fail(std::to_string(m.faceMaterials.size()) + " face materials for " +
         std::to_string(m.triangleCount()) + " triangles");
  }
  for (size_t i = 0; i < m.indices.size(); ++i) {
    if (m.indices[i] >= m.positions.size()) {
      fail("index " + std::to_string(i) + " is " + std::to_string(m.indices[i]) + ", past the " +
           std::to_string(m.positions.size()) + " positions");
    }
  }
}

// Scene adds a default material when the list is empty, so id 0 is always valid.
template <typename Desc>
void checkMaterials(const std::vector<Desc>& items, const char* kind, size_t materialCount) {
  const size_t limit = std::max<size_t>(materialCount, 1);
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].material >= limit) {
      throw WireError(describe(kind, i, items[i].loc) + ": material " +
                      std::to_string(items[i].material) + " but the scene has " +
                      std::to_string(materialCount) + " materials");
    }
  }
}

// width × height pixels of perPixel values each (floats' pixels: 1, bytes: 3); sizes not negative.
void checkImageSize(int width, int height, size_t values, size_t perPixel,
                    const std::string& what) {
  if (width < 0 || height < 0) {
    throw WireError(what + " has negative size " + std::to_string(width) + "x" +
                    std::to_string(height));
  }
  if (values != static_cast<size_t>(width) * static_cast<size_t>(height) * perPixel) {
    throw WireError(what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                    " but carries " + std::to_string(values) +
                    (perPixel == 1 ? " pixels" : " bytes"));
  }
}

}  // namespace

void Fields<RenderSettings>::check(const RenderSettings& render) {
  try {
    validate(render);
  } catch (const SettingError& e) {
    throw WireError(std::string("invalid render settings: ") + e.what());
  }
}

void Fields<CausticSettings>::check(const CausticSettings& caustics) {
  try {
    validate(caustics);
  } catch (const SettingError& e) {
    throw WireError(std::string("invalid caustic settings: ") + e.what());
  }
}

void Fields<CubeMapDesc>::check(const CubeMapDesc& cube) {
  const bool bytes = cube.keptAsBytes();
  for (size_t i = 0; i < cube.faces.size(); ++i) {
    const std::string what = "cube-map face " + std::to_string(i);
    const ImageRgb& linear = cube.faces[i];
    const SrgbImage& srgb = cube.srgbFaces[i];
    checkImageSize(linear.width, linear.height, linear.pixels.size(), 1, what);
    checkImageSize(srgb.width, srgb.height, srgb.rgb.size(), 3, what);
    // CubeMap reads one kind for all six faces, and clamps into [0, width - 1]: an empty face
    // would be indexed at -1.
    const bool hasLinear = !linear.pixels.empty(), hasBytes = !srgb.rgb.empty();
    if (hasLinear && hasBytes) throw WireError(what + " carries both floats and bytes");
    if (bytes ? !hasBytes : !hasLinear) {
      throw WireError(what + (hasLinear || hasBytes ? " is not of face 0's kind" : " is empty"));
    }
  }
}

void Fields<SceneDescription>::check(const SceneDescription& scene) {
  for (size_t i = 0; i < scene.meshes.size(); ++i) checkMesh(scene.meshes[i], i);
  const size_t materials = scene.materials.size();
  const size_t materialLimit = std::max<size_t>(materials, 1);
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    for (const MaterialId id : scene.meshes[i].faceMaterials) {
      if (id >= materialLimit) {
        throw WireError(describe("mesh", i, scene.meshes[i].loc) + ": a face has material " +
                        std::to_string(id) + " but the scene has " + std::to_string(materials) +
                        " materials");
      }
    }
  }
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const TextureDesc& t = scene.textures[i];
    const std::string what = "texture " + std::to_string(i) + " '" + t.path + "'";
    checkImageSize(t.linear.width, t.linear.height, t.linear.pixels.size(), 1, what);
    checkImageSize(t.srgb.width, t.srgb.height, t.srgb.rgb.size(), 3, what);
    const bool hasLinear = !t.linear.pixels.empty(), hasBytes = !t.srgb.rgb.empty();
    if (hasLinear == hasBytes) {
      throw WireError(what + (hasLinear ? " carries both floats and bytes" : " is empty"));
    }
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const std::optional<TextureMap>& map = scene.materials[i].diffuseMap;
    if (map && map->texture >= scene.textures.size()) {
      throw WireError(describe("material", i, scene.materials[i].loc) + ": texture " +
                      std::to_string(map->texture) + " but the scene has " +
                      std::to_string(scene.textures.size()) + " textures");
    }
  }
  forEachShapeList(scene, [&](const auto& shapes) {
    using Desc = typename std::decay_t<decltype(shapes)>::value_type;
    const std::string kind(Desc::kName);
    checkMaterials(shapes, kind.c_str(), materials);
    for (size_t i = 0; i < shapes.size(); ++i) {
      if (const std::optional<ShapeProblem> problem = shapeProblem(shapes[i])) {
        throw WireError(describe(kind.c_str(), i, shapes[i].loc) + ": " + problem->message);
      }
    }
  });
  checkMaterials(scene.planes, "plane", materials);
  checkMaterials(scene.meshes, "mesh", materials);
}

void writeScene(ByteWriter& w, const SceneDescription& scene) {
  writeFields(w, scene);
}

SceneDescription readScene(ByteReader& r) {
  SceneDescription scene;
  readFields(r, scene);
  return scene;
}

}  // namespace prism::wire
