// The reader behind parseYamlScene (parse/YamlSceneParser.h): Prism's scene schema, written in
// the checked reader's vocabulary (number, mapping, choice, ...; parse/CheckedYaml.h). The
// sections are read in YamlSceneParser.cpp, the objects section (shapes, planes, cylinders,
// triangles, meshes and their materials) in YamlSceneObjects.cpp. Only those two include it.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parse/CheckedYaml.h"
#include "scene/ModelDesc.h"
#include "scene/SceneDescription.h"
#include "util/MemoryBudget.h"
#include "util/MemorySize.h"

namespace prism {

class YamlSceneReader : private yaml::CheckedYaml {
 public:
  YamlSceneReader(const std::string& path, const MemoryLimit& limit);

  SceneDescription read(const std::string& text);

 private:
  using Entry = yaml::Entry;
  using Mapping = yaml::Mapping;

  std::string path_;
  std::filesystem::path baseDir_;
  MemoryBudget meshBudget_;  // each mesh is read against the limit less the meshes before it
  SceneDescription scene_;
  std::map<std::string, MaterialId, std::less<>> materialIds_;
  std::optional<MaterialId> defaultMaterial_;

  // ---- sections (YamlSceneParser.cpp) -----------------------------------------------------

  // A file the scene names: relative paths start at the scene file's folder.
  std::filesystem::path resolve(const std::string& file) const;
  // Every section, materials first so objects can refer to them wherever they appear.
  SceneDescription readScene(const YAML::Node& root);
  void readCamera(const Entry& section);
  void readRender(const Entry& section);
  void readCaustics(const Entry& section);
  void readEnvironment(const Entry& section);
  void readMaterials(const Entry& section);
  CheckerDesc checker(const Entry& section) const;
  void readLights(const Entry& section);

  // ---- objects (YamlSceneObjects.cpp) ----------------------------------------------------

  void readObjects(const Entry& section);
  // An object's 'caustic' key, or Auto without one.
  CausticRole causticRole(const Mapping& m) const;
  // The material an object's 'material' key names, or the default material without one.
  MaterialId material(const Mapping& m);
  // The built-in material of objects that name none; added to the list only once it is used,
  // so a scene that names every material keeps exactly the materials it wrote.
  MaterialId defaultMaterial();
  // Any shape of geometry/ShapeKinds.h, by the keys it declares (geometry/ShapeKeys.h).
  template <class Desc>
  void readShape(const Entry& object, std::vector<Desc>& shapes);
  void readPlane(const Entry& object);
  // A cylinder is written as one but read as a cone of equal radii.
  void readCylinder(const Entry& object);
  // Three points (or normals) written as [[x,y,z], [x,y,z], [x,y,z]].
  std::array<Vec3, 3> threeVectors(const Entry& e, std::string_view what) const;
  void readTriangle(const Entry& object);
  void readMesh(const Entry& object);
  // Bakes scale, then rotation about X, Y and Z (in that order), then translation into the
  // model's meshes, camera and lights. Normals take the inverse transpose of the linear part,
  // R·S⁻¹, and are renormalised.
  void applyTransform(const Entry& section, ModelDesc& model) const;
};

// Every key of the objects section, by section as yamlSceneKeys() lists them: "objects" (the
// kinds), each kind, and "transform".
void addObjectKeys(std::map<std::string, std::vector<std::string>>& keys);

}  // namespace prism
