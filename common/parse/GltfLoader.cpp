#include "parse/GltfLoader.h"

#include <array>
#include <deque>
#include <filesystem>
#include <sstream>

#include "parse/GltfGlb.h"
#include "parse/GltfMaterial.h"
#include "parse/GltfMesh.h"
#include "parse/GltfScene.h"
#include "parse/GltfUri.h"
#include "parse/MeshFileBytes.h"

namespace prism {

namespace {

constexpr std::array<std::string_view, 5> kSupportedExtensions = {
    "KHR_texture_transform", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_lights_punctual", "KHR_mesh_quantization"};

void checkAsset(const GltfJson& root) {
  const GltfJson version = root.required("asset").required("version");
  // glTF 1.0 files sometimes wrote the version as a number.
  std::string v;
  if (version.isString()) {
    v = version.string();
  } else {
    std::ostringstream number;
    number << version.number();
    v = number.str();
  }
  if (!v.starts_with("2.")) {
    version.fail("glTF " + v +
                 " is not read (only glTF 2.0; convert older files, e.g. with Blender)");
  }
}

void checkExtensions(GltfDocument& doc) {
  if (const std::optional<GltfJson> required = doc.root.member("extensionsRequired")) {
    for (const GltfJson& name : required->items()) {
      if (!gltfExtensionSupported(name.string())) {
        name.fail("the file requires " + std::string(name.string()) +
                  ", which Prism cannot read (supported: KHR_texture_transform, "
                  "KHR_materials_transmission, KHR_materials_ior, KHR_lights_punctual, "
                  "KHR_mesh_quantization)");
      }
    }
  }
  std::string ignored;
  if (const std::optional<GltfJson> used = doc.root.member("extensionsUsed")) {
    for (const GltfJson& name : used->items()) {
      if (gltfExtensionSupported(name.string())) continue;
      ignored += (ignored.empty() ? "" : ", ") + std::string(name.string());
    }
  }
  if (!ignored.empty()) {
    doc.warn("extensions", "extensionsUsed: " + ignored +
                               " not read: what they add is ignored, the rest of the file is used");
  }
}

void listTopLevel(GltfDocument& doc) {
  doc.accessors = doc.root.objectsOf("accessors");
  doc.bufferViews = doc.root.objectsOf("bufferViews");
  doc.buffers = doc.root.objectsOf("buffers");
  doc.meshes = doc.root.objectsOf("meshes");
  doc.nodes = doc.root.objectsOf("nodes");
  doc.materials = doc.root.objectsOf("materials");
  doc.textures = doc.root.objectsOf("textures");
  doc.images = doc.root.objectsOf("images");
  doc.cameras = doc.root.objectsOf("cameras");
  if (const std::optional<GltfJson> ext = doc.root.member("extensions")) {
    if (const std::optional<GltfJson> punctual = ext->member("KHR_lights_punctual")) {
      doc.lights = punctual->objectsOf("lights");
    }
  }
  if (doc.root.member("animations")) {
    doc.warn("animations", "animations: not played: the nodes' own transforms are used");
  }
}

// Every buffer's bytes: the GLB's binary chunk (a buffer without a URI), a data URI or a file.
void resolveBuffers(GltfDocument& doc, const GlbChunks* glb) {
  for (const GltfJson& buffer : doc.buffers) {
    const uint64_t length = buffer.required("byteLength").index();
    std::span<const uint8_t> bytes;
    std::string from;
    if (const std::optional<GltfJson> uriJson = buffer.member("uri")) {
      const std::string_view uri = uriJson->string();
      try {
        if (const std::optional<DataUri> data = splitDataUri(uri)) {
          doc.charge(base64DecodedSize(data->payload), buffer.path() + "'s data URI");
          doc.decoded.push_back(
              std::make_unique<std::vector<uint8_t>>(decodeBase64(data->payload)));
          bytes = *doc.decoded.back();
          from = "its data URI";
        } else {
          const std::string relative = uriToRelativePath(uri);
          from.append("'").append(relative).append("'");  // not "'" + ...: GCC 12 -Wrestrict
          const std::optional<std::string_view> file = doc.readFile(relative);
          if (!file) uriJson->fail("the buffer file " + from + " is missing");
          doc.charge(file->size(), buffer.path() + "'s file " + from);  // its pages, once read
          bytes = {reinterpret_cast<const uint8_t*>(file->data()), file->size()};
        }
      } catch (const std::invalid_argument& e) {
        uriJson->fail(e.what());
      }
    } else if (glb && glb->hasBin && &buffer == &doc.buffers.front()) {
      bytes = glb->bin;
      from = "the binary chunk";
    } else {
      buffer.fail("has no uri (only the first buffer of a .glb may use the binary chunk)");
    }
    if (bytes.size() < length) {
      buffer.required("byteLength")
          .fail(std::to_string(length) + " bytes, but " + from + " holds " +
                std::to_string(bytes.size()));
    }
    doc.bufferBytes.push_back(bytes.first(length));
  }
}

// The meshes the scene places, checked and counted; the memory they need is charged before
// any is read.
std::vector<std::vector<GltfPrimitivePlan>> planMeshes(GltfDocument& doc,
                                                       const GltfSceneContents& scene,
                                                       const FileLoc& referencedFrom) {
  std::vector<bool> used(doc.meshes.size());
  for (const GltfMeshInstance& instance : scene.meshes) used[instance.mesh] = true;
  std::vector<std::vector<GltfPrimitivePlan>> plans = planGltfMeshes(doc, used);
  uint64_t bytes = 0, triangles = 0, vertices = 0;
  for (const GltfMeshInstance& instance : scene.meshes) {
    for (const GltfPrimitivePlan& plan : plans[instance.mesh]) {
      bytes = saturatingAdd(bytes, gltfPrimitiveBytes(plan));
      triangles = saturatingAdd(triangles, plan.triangles);
      vertices = saturatingAdd(vertices, plan.vertices);
    }
  }
  if (triangles == 0) {
    throw SceneError(FileLoc{doc.file, 0, 0},
                     doc.warnedKinds.contains("points and lines")
                         ? "the default scene has no triangles (only points and lines, which "
                           "Prism does not render)"
                         : "the default scene has no triangles (no node places a mesh with "
                           "triangle primitives)");
  }
  const uint64_t needed = saturatingAdd(doc.committedBytes, bytes);
  if (needed > doc.limit.bytes) {
    throw SceneError(
        referencedFrom.file.empty() ? FileLoc{doc.file, 0, 0} : referencedFrom,
        memoryRefusal("glTF model '" + doc.file + "' (" + std::to_string(triangles) +
                          " triangles, " + std::to_string(vertices) + " vertices) read and built",
                      needed, doc.limit, "simplify the model or raise --memory-limit"));
  }
  return plans;
}

ModelDesc readModel(GltfDocument& doc, const GlbChunks* glb, const FileLoc& referencedFrom) {
  checkAsset(doc.root);
  checkExtensions(doc);
  listTopLevel(doc);
  resolveBuffers(doc, glb);
  GltfSceneContents scene = walkGltfScene(doc);
  const std::vector<std::vector<GltfPrimitivePlan>> plans = planMeshes(doc, scene, referencedFrom);
  ModelDesc model;
  model.source = doc.file;
  model.materials = readGltfMaterials(doc, model.textures);
  const auto noMaterial = static_cast<uint32_t>(model.materials.size());
  bool defaultUsed = false;
  for (const GltfMeshInstance& instance : scene.meshes) {
    for (const GltfPrimitivePlan& plan : plans[instance.mesh]) {
      if (plan.triangles == 0) continue;
      model.meshes.push_back(readGltfPrimitive(doc, plan, instance, noMaterial));
      defaultUsed = defaultUsed || !plan.material;
    }
  }
  if (defaultUsed) model.materials.push_back(defaultGltfMaterial(doc.file));
  model.camera = scene.camera;
  model.lights = std::move(scene.lights);
  model.warnings = std::move(doc.warnings);
  return model;
}

}  // namespace

void GltfDocument::charge(uint64_t bytes, const std::string& what) {
  const uint64_t needed = saturatingAdd(committedBytes, bytes);
  if (needed > limit.bytes) {
    throw SceneError(referencedFrom.file.empty() ? FileLoc{file, 0, 0} : referencedFrom,
                     memoryRefusal("glTF model '" + file + "' with " + what, needed, limit,
                                   "simplify the model or raise --memory-limit"));
  }
  committedBytes = needed;
}

bool gltfExtensionSupported(std::string_view name) {
  for (const std::string_view supported : kSupportedExtensions) {
    if (name == supported) return true;
  }
  return false;
}

ModelDesc parseGltfModel(std::string_view bytes, const std::string& path,
                         const GltfFileReader& readFile, const FileLoc& referencedFrom,
                         const MemoryLimit& limit) {
  const bool binary = looksLikeGlb(bytes) || std::filesystem::path(path).extension() == ".glb";
  GlbChunks glb;
  if (binary) glb = splitGlb(bytes, path);
  const std::string_view json = binary ? glb.json : bytes;
  const uint64_t jsonBytes = saturatingAdd(bytes.size(), gltfJsonParseBytes(json.size()));
  if (jsonBytes > limit.bytes) {
    throw SceneError(referencedFrom.file.empty() ? FileLoc{path, 0, 0} : referencedFrom,
                     memoryRefusal("glTF file '" + path + "' read and its JSON parsed", jsonBytes,
                                   limit, "simplify the model or raise --memory-limit"));
  }
  const GltfJsonDocument parsed(json, path);
  GltfDocument doc(path, parsed.root());
  doc.readFile = readFile;
  doc.limit = limit;
  doc.referencedFrom = referencedFrom;
  doc.committedBytes = jsonBytes;
  return readModel(doc, binary ? &glb : nullptr, referencedFrom);
}

ModelDesc loadGltfModel(const std::string& path, const FileLoc& referencedFrom,
                        const MemoryLimit& limit) {
  MeshFileBytes file(path, referencedFrom, limit);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::deque<std::unique_ptr<MeshFileBytes>> opened;  // the buffer and image files, until the end
  const GltfFileReader reader =
      [&](const std::string& relative) -> std::optional<std::string_view> {
    const std::filesystem::path full = folder / relative;
    std::error_code error;
    if (!std::filesystem::is_regular_file(full, error)) return std::nullopt;
    opened.push_back(std::make_unique<MeshFileBytes>(full.string(), FileLoc{path, 0, 0}, limit));
    return opened.back()->bytes();
  };
  return parseGltfModel(file.bytes(), path, reader, referencedFrom, limit);
}

}  // namespace prism
