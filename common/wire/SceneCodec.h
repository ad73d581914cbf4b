// Encodes a SceneDescription, every field of it, so the master can broadcast the parsed scene
// and each slave builds the same Scene without reading a file.
#pragma once

#include "scene/SceneDescription.h"
#include "wire/ByteBuffer.h"

namespace prism::wire {

void writeScene(ByteWriter& w, const SceneDescription& scene);

// Reads what writeScene wrote. Besides the byte-level checks it rejects what would crash the
// renderer later: unknown enum values, non-positive image or render sizes, image pixel counts
// that disagree with width × height, mesh indices past the positions, normals not parallel to
// positions, index counts not a multiple of three, and material ids past the material list.
// Throws WireError.
SceneDescription readScene(ByteReader& r);

// The camera alone, for the viewer's View message. readCamera rejects unknown projections.
void writeCamera(ByteWriter& w, const CameraDesc& camera);
CameraDesc readCamera(ByteReader& r);

}  // namespace prism::wire
