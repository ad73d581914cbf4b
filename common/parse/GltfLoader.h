// glTF 2.0 models (Khronos): `.gltf` (JSON, with buffers and images in files beside it or in
// base64 data: URIs) and `.glb` (binary: the JSON chunk and a binary chunk read in place). What
// is read, the material rule, the light units and every warning and refusal are in
// docs/scene-format.md, "glTF"; the parts are GltfJson (the checked JSON walk, on simdjson),
// GltfGlb (the container), GltfUri, GltfAccessor, GltfScene (nodes, cameras, lights), GltfMesh
// (primitives) and GltfMaterial.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "scene/ModelDesc.h"
#include "util/MemorySize.h"

namespace prism {

// How a glTF reaches the files its URIs name: given the path relative to the glTF file's folder,
// the file's bytes, which must stay valid until the load returns; nothing when there is no such
// file (the loader reports it with the JSON path that names it).
using GltfFileReader = std::function<std::optional<std::string_view>(const std::string& path)>;

// Reads the model at path; external files are read relative to its folder. Errors are
// SceneErrors "file: where: what is wrong" (a byte offset in a .glb's container, the JSON path
// of the value otherwise); what the model would need beyond the memory limit is refused before
// its arrays are allocated, and reported at referencedFrom (where the scene names the file).
ModelDesc loadGltfModel(const std::string& path, const FileLoc& referencedFrom,
                        const MemoryLimit& limit = {});

// The same from the file's bytes in memory (tests and the fuzzer); readFile gives the files its
// URIs name. path names the model in messages; a .glb is recognised by its magic bytes (or a
// ".glb" path).
ModelDesc parseGltfModel(std::string_view bytes, const std::string& path,
                         const GltfFileReader& readFile, const FileLoc& referencedFrom,
                         const MemoryLimit& limit = {});

// The extensions Prism reads (a file may mark them required) and those it knows and ignores.
bool gltfExtensionSupported(std::string_view name);

}  // namespace prism
