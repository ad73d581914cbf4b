// The field lists of the SceneDescription structs (wire/Fields.h says how a list reads): every
// field of the description travels, meshes and cube-map images included, so the master can
// broadcast the parsed scene and each slave builds the same Scene without reading a file.
#pragma once

#include "scene/SceneDescription.h"
#include "wire/ByteBuffer.h"
#include "wire/Fields.h"

namespace prism::wire {

template <>
struct Fields<FileLoc> {
  PRISM_WIRE_FIELDS(file, line, column)
};

template <>
struct Fields<CameraDesc> {
  PRISM_WIRE_FIELDS(projection, position, lookAt, up, fovDegrees, width, nearClip, loc)
};

template <>
struct Fields<RenderSettings> {
  PRISM_WIRE_FIELDS(width, height, samplesPerPixel, maxDepth, minContribution, seed, exposure,
                    triangleTest, instructionSet)
  static void check(const RenderSettings& render);  // validate(): what the parser refuses
};

template <>
struct Fields<CausticSettings> {
  PRISM_WIRE_FIELDS(method, photons, gather, automaticGather, gatherNoise, maxRadius, filter,
                    maxBounces, progressive, passes, alpha, radius, timeBudgetSeconds,
                    mapResolution, mapSteps, mapBlurSigma, mapBlurRadius, mapPaths)
  static void check(const CausticSettings& caustics);  // validate()
};

template <>
struct Fields<ImageRgb> {
  PRISM_WIRE_FIELDS(width, height, pixels)
};

template <>
struct Fields<SrgbImage> {
  PRISM_WIRE_FIELDS(width, height, rgb)
};

template <>
struct Fields<CubeMapDesc> {
  PRISM_WIRE_FIELDS(faces, srgbFaces, paths, scale)
  // Each face non-empty (CubeMap::texel would index -1) with width × height pixels, all six of
  // one kind (floats or bytes).
  static void check(const CubeMapDesc& cube);
};

template <>
struct Fields<CheckerDesc> {
  PRISM_WIRE_FIELDS(colorA, colorB, scale)
};

template <>
struct Fields<TextureDesc> {
  PRISM_WIRE_FIELDS(path, srgb, linear)
};

template <>
struct Fields<TextureMap> {
  PRISM_WIRE_FIELDS(texture, scale, offset, rotation)
};

template <>
struct Fields<MaterialDesc> {
  PRISM_WIRE_FIELDS(name, ambient, diffuse, specular, shininess, reflectance, transmittance, ior,
                    fresnel, checker, diffuseMap, loc)
};

template <>
struct Fields<Attenuation> {
  PRISM_WIRE_FIELDS(constant, linear, quadratic)
};

template <>
struct Fields<PointLightDesc> {
  PRISM_WIRE_FIELDS(position, intensity, attenuation, loc)
};

// The plane and the mesh send their caustic role before their location.
template <>
struct Fields<PlaneDesc> {
  static void fields(auto& self, auto&& visit) {
    auto& [point, normal, material, loc, caustic] = self;
    visit(point, normal, material, caustic, loc);
  }
};

template <>
struct Fields<MeshDesc> {
  static void fields(auto& self, auto&& visit) {
    auto& [source, positions, normals, indices, material, loc, caustic, uvs, colors,
           faceMaterials] = self;
    visit(source, positions, normals, indices, material, caustic, loc, uvs, colors, faceMaterials);
  }
};

template <>
struct Fields<SceneDescription> {
  PRISM_WIRE_FIELDS(sourcePath, camera, render, caustics, background, ambientLight, environment,
                    materials, textures, lights, PRISM_SHAPE_KINDS(PRISM_SHAPE_PLURAL_COMMA) planes,
                    meshes, warnings, notes)
  // What would crash the renderer later: mesh indices past the positions, normals, uvs or
  // colours not parallel to positions, index counts not a multiple of three, material ids past
  // the material list (a face's too), texture maps past the texture list, textures without
  // pixels or with both kinds.
  static void check(const SceneDescription& scene);
};

// The payload of a Scene message (Messages.h: encodeScene, decodeScene). readScene checks every
// field (enumerators, sizes, the settings' validate(), the checks above) but not that nothing is
// left over; both throw WireError.
void writeScene(ByteWriter& w, const SceneDescription& scene);
SceneDescription readScene(ByteReader& r);

}  // namespace prism::wire
