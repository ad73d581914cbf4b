#include "wire/SceneCodec.h"

#include <algorithm>

#include "scene/SceneValidation.h"

// Every struct is written and read through a structured binding that names all its fields: a
// field added to SceneDescription.h makes this file fail to compile until the codec (and
// tests/common/wire/SceneCodec_test.cpp) is updated, instead of silently not travelling.

namespace prism::wire {
namespace {

// No default case: -Wswitch points here when an enumerator is added, so the decoder learns it.
bool isKnown(Projection p) {
  switch (p) {
    case Projection::Perspective:
    case Projection::Orthographic:
      return true;
  }
  return false;
}

bool isKnown(TriangleTest t) {
  switch (t) {
    case TriangleTest::MollerTrumbore:
    case TriangleTest::PlaneThenInside:
    case TriangleTest::Watertight:
      return true;
  }
  return false;
}

bool isKnown(CausticMethod m) {
  switch (m) {
    case CausticMethod::None:
    case CausticMethod::PhotonMap:
    case CausticMethod::CausticMap:
      return true;
  }
  return false;
}

bool isKnown(CausticMapPaths p) {
  return p == CausticMapPaths::FrontFace || p == CausticMapPaths::Traced;
}

bool isKnown(PhotonFilter f) {
  switch (f) {
    case PhotonFilter::Box:
    case PhotonFilter::Cone:
    case PhotonFilter::Epanechnikov:
      return true;
  }
  return false;
}

bool isKnown(CausticRole role) {
  switch (role) {
    case CausticRole::Auto:
    case CausticRole::Cast:
    case CausticRole::Receive:
    case CausticRole::Both:
    case CausticRole::Off:
      return true;
  }
  return false;
}

template <typename Enum>
void writeEnum(ByteWriter& w, Enum value) {
  w.writeU32(static_cast<uint32_t>(value));
}

// Any value but a known enumerator would fall through every switch in the renderer.
template <typename Enum>
Enum readEnum(ByteReader& r, const char* what) {
  const size_t at = r.offset();
  const uint32_t raw = r.readU32();
  const auto value = static_cast<Enum>(raw);  // scoped enums have a fixed type: well defined
  // The cast keeps only the low bits for a narrower enum (CausticRole is a byte), so 256 would
  // otherwise read as 0 (found by the wire fuzzer).
  if (static_cast<uint32_t>(value) != raw || !isKnown(value)) {
    throw WireError("invalid " + std::string(what) + " " + std::to_string(raw) + " at offset " +
                    std::to_string(at));
  }
  return value;
}

// "sphere 3 (scene.yaml:12:5)", so a bad entity can be found in the file it came from.
std::string describe(const char* kind, size_t index, const FileLoc& loc) {
  std::string s = std::string(kind) + " " + std::to_string(index);
  const std::string where = loc.toString();
  if (!where.empty()) s += " (" + where + ")";
  return s;
}

void writeLoc(ByteWriter& w, const FileLoc& loc) {
  const auto& [file, line, column] = loc;
  w.writeString(file);
  w.writeI32(line);
  w.writeI32(column);
}

FileLoc readLoc(ByteReader& r) {
  FileLoc loc;
  auto& [file, line, column] = loc;
  file = r.readString();
  line = r.readI32();
  column = r.readI32();
  return loc;
}

}  // namespace

void writeCamera(ByteWriter& w, const CameraDesc& c) {
  const auto& [projection, position, lookAt, up, fovDegrees, width, nearClip, loc] = c;
  writeEnum(w, projection);
  w.writeVec3(position);
  w.writeVec3(lookAt);
  w.writeVec3(up);
  w.writeF32(fovDegrees);
  w.writeF32(width);
  w.writeF32(nearClip);
  writeLoc(w, loc);
}

CameraDesc readCamera(ByteReader& r) {
  CameraDesc c;
  auto& [projection, position, lookAt, up, fovDegrees, width, nearClip, loc] = c;
  projection = readEnum<Projection>(r, "camera projection");
  position = r.readVec3();
  lookAt = r.readVec3();
  up = r.readVec3();
  fovDegrees = r.readF32();
  width = r.readF32();
  nearClip = r.readF32();
  loc = readLoc(r);
  return c;
}

namespace {

void writeRender(ByteWriter& w, const RenderSettings& s) {
  const auto& [width, height, samplesPerPixel, maxDepth, minContribution, seed, exposure,
               triangleTest] = s;
  w.writeI32(width);
  w.writeI32(height);
  w.writeI32(samplesPerPixel);
  w.writeI32(maxDepth);
  w.writeF32(minContribution);
  w.writeU64(seed);
  w.writeF32(exposure);
  writeEnum(w, triangleTest);
}

RenderSettings readRender(ByteReader& r) {
  RenderSettings s;
  auto& [width, height, samplesPerPixel, maxDepth, minContribution, seed, exposure, triangleTest] =
      s;
  width = r.readI32();
  height = r.readI32();
  samplesPerPixel = r.readI32();
  maxDepth = r.readI32();
  minContribution = r.readF32();
  seed = r.readU64();
  exposure = r.readF32();
  triangleTest = readEnum<TriangleTest>(r, "triangle test");
  try {
    validate(s);
  } catch (const SettingError& e) {
    throw WireError(std::string("invalid render settings: ") + e.what());
  }
  return s;
}

void writeCaustics(ByteWriter& w, const CausticSettings& c) {
  const auto& [method, photons, gather, automaticGather, gatherNoise, maxRadius, filter, maxBounces,
               progressive, passes, alpha, radius, timeBudgetSeconds, mapResolution, mapSteps,
               mapBlurSigma, mapBlurRadius, mapPaths] = c;
  writeEnum(w, method);
  w.writeU64(photons);
  w.writeI32(gather);
  w.writeBool(automaticGather);
  w.writeF32(gatherNoise);
  w.writeF32(maxRadius);
  writeEnum(w, filter);
  w.writeI32(maxBounces);
  w.writeBool(progressive);
  w.writeI32(passes);
  w.writeF32(alpha);
  w.writeF32(radius);
  w.writeF64(timeBudgetSeconds);
  w.writeI32(mapResolution);
  w.writeI32(mapSteps);
  w.writeF32(mapBlurSigma);
  w.writeI32(mapBlurRadius);
  writeEnum(w, mapPaths);
}

CausticSettings readCaustics(ByteReader& r) {
  CausticSettings c;
  auto& [method, photons, gather, automaticGather, gatherNoise, maxRadius, filter, maxBounces,
         progressive, passes, alpha, radius, timeBudgetSeconds, mapResolution, mapSteps,
         mapBlurSigma, mapBlurRadius, mapPaths] = c;
  method = readEnum<CausticMethod>(r, "caustic method");
  photons = r.readU64();
  gather = r.readI32();
  automaticGather = r.readBool();
  gatherNoise = r.readF32();
  maxRadius = r.readF32();
  filter = readEnum<PhotonFilter>(r, "photon filter");
  maxBounces = r.readI32();
  progressive = r.readBool();
  passes = r.readI32();
  alpha = r.readF32();
  radius = r.readF32();
  timeBudgetSeconds = r.readF64();
  mapResolution = r.readI32();
  mapSteps = r.readI32();
  mapBlurSigma = r.readF32();
  mapBlurRadius = r.readI32();
  mapPaths = readEnum<CausticMapPaths>(r, "caustic map paths");
  try {
    validate(c);
  } catch (const SettingError& e) {
    throw WireError(std::string("invalid caustic settings: ") + e.what());
  }
  return c;
}

void writeImage(ByteWriter& w, const ImageRgb& image) {
  const auto& [width, height, pixels] = image;
  w.writeI32(width);
  w.writeI32(height);
  w.writeVec3s(pixels);
}

ImageRgb readImage(ByteReader& r, const std::string& what) {
  ImageRgb image;
  auto& [width, height, pixels] = image;
  width = r.readI32();
  height = r.readI32();
  if (width < 0 || height < 0) {
    throw WireError(what + " has negative size " + std::to_string(width) + "x" +
                    std::to_string(height));
  }
  pixels = r.readVec3s();
  if (pixels.size() != static_cast<size_t>(width) * static_cast<size_t>(height)) {
    throw WireError(what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                    " but carries " + std::to_string(pixels.size()) + " pixels");
  }
  return image;
}

void writeCubeMap(ByteWriter& w, const CubeMapDesc& cube) {
  const auto& [faces, paths, scale] = cube;
  for (const ImageRgb& face : faces) writeImage(w, face);
  for (const std::string& path : paths) w.writeString(path);
  w.writeF32(scale);
}

CubeMapDesc readCubeMap(ByteReader& r) {
  CubeMapDesc cube;
  auto& [faces, paths, scale] = cube;
  for (size_t i = 0; i < faces.size(); ++i) {
    const std::string what = "cube-map face " + std::to_string(i);
    faces[i] = readImage(r, what);
    // CubeMap::texel clamps into [0, width - 1]: an empty face would be indexed at -1.
    if (faces[i].width == 0 || faces[i].height == 0) throw WireError(what + " is empty");
  }
  for (std::string& path : paths) path = r.readString();
  scale = r.readF32();
  return cube;
}

void writeMaterial(ByteWriter& w, const MaterialDesc& m) {
  const auto& [name, ambient, diffuse, specular, shininess, reflectance, transmittance, ior,
               fresnel, checker, loc] = m;
  w.writeString(name);
  w.writeVec3(ambient);
  w.writeVec3(diffuse);
  w.writeVec3(specular);
  w.writeF32(shininess);
  w.writeVec3(reflectance);
  w.writeVec3(transmittance);
  w.writeF32(ior);
  w.writeBool(fresnel);
  w.writeBool(checker.has_value());
  if (checker) {
    const auto& [colorA, colorB, scale] = *checker;
    w.writeVec3(colorA);
    w.writeVec3(colorB);
    w.writeF32(scale);
  }
  writeLoc(w, loc);
}

MaterialDesc readMaterial(ByteReader& r) {
  MaterialDesc m;
  auto& [name, ambient, diffuse, specular, shininess, reflectance, transmittance, ior, fresnel,
         checker, loc] = m;
  name = r.readString();
  ambient = r.readVec3();
  diffuse = r.readVec3();
  specular = r.readVec3();
  shininess = r.readF32();
  reflectance = r.readVec3();
  transmittance = r.readVec3();
  ior = r.readF32();
  fresnel = r.readBool();
  if (r.readBool()) {
    auto& [colorA, colorB, scale] = checker.emplace();
    colorA = r.readVec3();
    colorB = r.readVec3();
    scale = r.readF32();
  }
  loc = readLoc(r);
  return m;
}

void writeLight(ByteWriter& w, const PointLightDesc& l) {
  const auto& [position, intensity, attenuation, loc] = l;
  const auto& [constant, linear, quadratic] = attenuation;
  w.writeVec3(position);
  w.writeVec3(intensity);
  w.writeF32(constant);
  w.writeF32(linear);
  w.writeF32(quadratic);
  writeLoc(w, loc);
}

PointLightDesc readLight(ByteReader& r) {
  PointLightDesc l;
  auto& [position, intensity, attenuation, loc] = l;
  auto& [constant, linear, quadratic] = attenuation;
  position = r.readVec3();
  intensity = r.readVec3();
  constant = r.readF32();
  linear = r.readF32();
  quadratic = r.readF32();
  loc = readLoc(r);
  return l;
}

void writeSphere(ByteWriter& w, const SphereDesc& s) {
  const auto& [center, radius, material, loc, caustic] = s;
  w.writeVec3(center);
  w.writeF32(radius);
  w.writeU32(material);
  writeEnum(w, caustic);
  writeLoc(w, loc);
}

SphereDesc readSphere(ByteReader& r) {
  SphereDesc s;
  auto& [center, radius, material, loc, caustic] = s;
  center = r.readVec3();
  radius = r.readF32();
  material = r.readU32();
  caustic = readEnum<CausticRole>(r, "caustic role");
  loc = readLoc(r);
  return s;
}

void writePlane(ByteWriter& w, const PlaneDesc& p) {
  const auto& [point, normal, material, loc, caustic] = p;
  w.writeVec3(point);
  w.writeVec3(normal);
  w.writeU32(material);
  writeEnum(w, caustic);
  writeLoc(w, loc);
}

PlaneDesc readPlane(ByteReader& r) {
  PlaneDesc p;
  auto& [point, normal, material, loc, caustic] = p;
  point = r.readVec3();
  normal = r.readVec3();
  material = r.readU32();
  caustic = readEnum<CausticRole>(r, "caustic role");
  loc = readLoc(r);
  return p;
}

void writeCone(ByteWriter& w, const ConeDesc& c) {
  const auto& [base, baseRadius, apex, apexRadius, material, loc, caustic] = c;
  w.writeVec3(base);
  w.writeF32(baseRadius);
  w.writeVec3(apex);
  w.writeF32(apexRadius);
  w.writeU32(material);
  writeEnum(w, caustic);
  writeLoc(w, loc);
}

ConeDesc readCone(ByteReader& r) {
  ConeDesc c;
  auto& [base, baseRadius, apex, apexRadius, material, loc, caustic] = c;
  base = r.readVec3();
  baseRadius = r.readF32();
  apex = r.readVec3();
  apexRadius = r.readF32();
  material = r.readU32();
  caustic = readEnum<CausticRole>(r, "caustic role");
  loc = readLoc(r);
  return c;
}

void writeMesh(ByteWriter& w, const MeshDesc& m) {
  const auto& [source, positions, normals, indices, material, loc, caustic] = m;
  w.writeString(source);
  w.writeVec3s(positions);
  w.writeVec3s(normals);
  w.writeU32s(indices);
  w.writeU32(material);
  writeEnum(w, caustic);
  writeLoc(w, loc);
}

MeshDesc readMesh(ByteReader& r) {
  MeshDesc m;
  auto& [source, positions, normals, indices, material, loc, caustic] = m;
  source = r.readString();
  positions = r.readVec3s();
  normals = r.readVec3s();
  indices = r.readU32s();
  material = r.readU32();
  caustic = readEnum<CausticRole>(r, "caustic role");
  loc = readLoc(r);
  return m;
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
  if (m.indices.size() % 3 != 0) {
    fail(std::to_string(m.indices.size()) + " indices, not a multiple of 3");
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

}  // namespace

void writeScene(ByteWriter& w, const SceneDescription& scene) {
  const auto& [sourcePath, camera, render, caustics, background, ambientLight, environment,
               materials, lights, spheres, planes, cones, meshes] = scene;
  w.writeString(sourcePath);
  writeCamera(w, camera);
  writeRender(w, render);
  writeCaustics(w, caustics);
  w.writeVec3(background);
  w.writeVec3(ambientLight);
  w.writeBool(environment.has_value());
  if (environment) writeCubeMap(w, *environment);
  w.writeSequence(materials, writeMaterial);
  w.writeSequence(lights, writeLight);
  w.writeSequence(spheres, writeSphere);
  w.writeSequence(planes, writePlane);
  w.writeSequence(cones, writeCone);
  w.writeSequence(meshes, writeMesh);
}

SceneDescription readScene(ByteReader& r) {
  SceneDescription scene;
  auto& [sourcePath, camera, render, caustics, background, ambientLight, environment, materials,
         lights, spheres, planes, cones, meshes] = scene;
  sourcePath = r.readString();
  camera = readCamera(r);
  render = readRender(r);
  caustics = readCaustics(r);
  background = r.readVec3();
  ambientLight = r.readVec3();
  if (r.readBool()) environment = readCubeMap(r);
  materials = r.readSequence<MaterialDesc>(readMaterial);
  lights = r.readSequence<PointLightDesc>(readLight);
  spheres = r.readSequence<SphereDesc>(readSphere);
  planes = r.readSequence<PlaneDesc>(readPlane);
  cones = r.readSequence<ConeDesc>(readCone);
  meshes = r.readSequence<MeshDesc>(readMesh);

  for (size_t i = 0; i < meshes.size(); ++i) checkMesh(meshes[i], i);
  checkMaterials(spheres, "sphere", materials.size());
  checkMaterials(planes, "plane", materials.size());
  checkMaterials(cones, "cone", materials.size());
  checkMaterials(meshes, "mesh", materials.size());
  return scene;
}

}  // namespace prism::wire
