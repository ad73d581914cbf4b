// Texture images as scenes and model files bring them: read once per file into a TextureDesc
// (scene/SceneDescription.h) that travels with the scene, so a slave reads no file.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Reads the image at path: an 8-bit PNG or JPEG stays sRGB bytes, anything else (16-bit PNG,
// EXR, HDR, TIFF, ...: through OpenImageIO) becomes linear radiance. A file whose pixels would
// pass the memory limit is refused before they are decoded. Throws SceneError at referencedFrom
// naming the file and what is wrong (missing, not an image, corrupt).
TextureDesc loadTextureFile(const std::string& path, const FileLoc& referencedFrom,
                            const MemoryLimit& limit = {});

// The same from an encoded PNG or JPEG already in memory (a glTF's data URI or buffer view);
// name stands for it in the texture's path and in errors. Any other format is refused.
TextureDesc decodeTexture(std::span<const uint8_t> bytes, const std::string& name,
                          const FileLoc& referencedFrom, const MemoryLimit& limit = {});

// Whether bytes start like a PNG or a JPEG file (their signatures).
bool looksLikePng(std::span<const uint8_t> bytes);
bool looksLikeJpeg(std::span<const uint8_t> bytes);

}  // namespace prism
