// The plain, self-contained description of a scene: what the parsers produce and what the
// renderer builds from. It holds data only (no pointers, no render structures) so the master can
// serialise it for the other ranks; meshes and environment images are loaded into it, so a rank
// that builds a Scene from it never reads a file.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "geometry/CausticRole.h"
#include "geometry/MaterialId.h"
#include "geometry/ShapeKinds.h"
#include "geometry/TriangleTest.h"
#include "image/ImageRgb.h"
#include "image/SrgbImage.h"
#include "math/Vec.h"
#include "scene/CausticMethods.h"
#include "scene/SettingLimits.h"
#include "util/FileLoc.h"
#include "util/InstructionSet.h"

namespace prism {

enum class Projection { Perspective, Orthographic };

struct CameraDesc {
  Projection projection = Projection::Perspective;
  Vec3 position{0.0f, 0.0f, 5.0f};
  Vec3 lookAt{0.0f, 0.0f, 0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovDegrees = 45.0f;  // perspective: full vertical field of view
  float width = 2.0f;        // orthographic: width of the view in world units
  float nearClip = 0.0f;     // primary rays start this far from the camera (NFF "hither")
  FileLoc loc;
};

// Distance falloff 1 / (constant + linear·d + quadratic·d²); (0, 0, 1) is inverse-square.
struct Attenuation {
  float constant = 0.0f;
  float linear = 0.0f;
  float quadratic = 1.0f;
};

struct PointLightDesc {
  Vec3 position{0.0f};
  Color intensity{1.0f};  // radiant intensity, W/sr per channel
  Attenuation attenuation;
  FileLoc loc;
};

// A solid (3D) checkerboard that replaces a material's diffuse colour.
struct CheckerDesc {
  Color colorA{0.9f};
  Color colorB{0.1f};
  float scale = 1.0f;  // edge length of one cell, world units
};

// An image a material reads through its surface's texture coordinates (docs/scene-format.md,
// "Textures"). 8-bit sRGB files stay bytes (srgb), as the sky's faces do; 16-bit and float files
// are linear radiance (linear). Exactly one of the two holds pixels. Rows from the top; texture
// coordinate v = 0 is the bottom row (OBJ's and OpenGL's convention; glTF's loader flips v).
struct TextureDesc {
  std::string path;  // the file it came from: one texture per file, however many materials use it
  SrgbImage srgb;
  ImageRgb linear;

  bool keptAsBytes() const { return !srgb.empty(); }
  int width() const { return keptAsBytes() ? srgb.width : linear.width; }
  int height() const { return keptAsBytes() ? srgb.height : linear.height; }
};

// A texture placed on a material: coordinates (u, v) read the texture at
// rotate(rotation) · (scale · (u, v)) + offset, wrapped by repeating (MTL's -s and -o, glTF's
// KHR_texture_transform).
struct TextureMap {
  uint32_t texture = 0;  // into SceneDescription::textures
  Vec2 scale{1.0f};
  Vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise
};

struct MaterialDesc {
  std::string name;
  Color ambient{0.0f};      // fraction of the scene's ambient radiance reflected
  Color diffuse{0.8f};      // Lambertian albedo (reflected radiance = albedo/π · irradiance)
  Color specular{0.0f};     // Phong highlight coefficient
  float shininess = 32.0f;  // Phong exponent
  Color reflectance{0.0f};  // mirror reflection weight
  Color transmittance{0.0f};
  float ior = 1.5f;
  bool fresnel = true;  // split transmittance into reflection and refraction by Fresnel
  std::optional<CheckerDesc> checker;
  // Multiplies diffuse by the texture's colour where the surface has texture coordinates.
  std::optional<TextureMap> diffuseMap;
  FileLoc loc;
};

struct PlaneDesc {
  Vec3 point{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit length after parsing
  MaterialId material = 0;
  FileLoc loc;
  CausticRole caustic = CausticRole::Auto;
};

// A triangle mesh in world space. normals is empty (flat shading) or parallel to positions
// (smooth shading, interpolated barycentrically); so are uvs (texture coordinates) and colors
// (vertex colours, which multiply the diffuse colour). faceMaterials is empty (every triangle
// has `material`) or holds one material per triangle (an OBJ's usemtl).
struct MeshDesc {
  std::string source;  // file it came from, or a description such as "triangle"
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<uint32_t> indices;  // three per triangle
  MaterialId material = 0;
  FileLoc loc;
  CausticRole caustic = CausticRole::Auto;
  std::vector<Vec2> uvs;
  std::vector<Color> colors;
  std::vector<MaterialId> faceMaterials;

  size_t triangleCount() const { return indices.size() / 3; }
  MaterialId materialOf(size_t triangle) const {
    return faceMaterials.empty() ? material : faceMaterials[triangle];
  }
};

// Six faces in the OpenGL cube-map order +X, -X, +Y, -Y, +Z, -Z. Faces read from 8-bit sRGB
// files stay bytes (srgbFaces: a quarter of floats' size on the wire and in the scene's mip
// pyramids); faces of any other kind are linear radiance (faces). Either all six srgbFaces hold
// pixels and faces are empty, or the other way round.
struct CubeMapDesc {
  std::array<ImageRgb, 6> faces;
  std::array<SrgbImage, 6> srgbFaces;
  std::array<std::string, 6> paths;
  float scale = 1.0f;  // multiplies the stored radiance

  bool keptAsBytes() const { return !srgbFaces[0].empty(); }
  int faceWidth(int face) const {
    return keptAsBytes() ? srgbFaces[face].width : faces[face].width;
  }
  int faceHeight(int face) const {
    return keptAsBytes() ? srgbFaces[face].height : faces[face].height;
  }
};

// Names and limits of these settings: SettingNames.h, SettingLimits.h; validate() checks them
// (SceneValidation.h).

struct RenderSettings {
  int width = 640;
  int height = 360;
  int samplesPerPixel = 1;
  int maxDepth = 5;               // primary ray is depth 0
  float minContribution = 1e-3f;  // secondary rays whose weight falls below this are skipped
  uint64_t seed = 0;
  float exposure = 1.0f;  // PNG/viewer only: radiance multiplied before tone mapping
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
  // The kernels' instruction set (util/InstructionSet.h): not a scene-file setting but the
  // job's choice, which rank 0 makes once for every rank (the best all of them run, or the
  // command line's --isa) and sends with the scene, so that every rank traces the same pixels.
  InstructionSet instructionSet = InstructionSet::Auto;
};

// What caustic mapping does past the first caster surface (docs/caustics.md, "Caustic mapping"):
// FrontFace refracts/reflects once at the surface the light sees, as the thesis does; Traced
// follows the light through the casters exactly and estimates only the last leg's receiver.
enum class CausticMapPaths { FrontFace, Traced };
// Density estimation kernels over the gathered disc (see caustics/DensityKernel.h).
enum class PhotonFilter { Box, Cone, Epanechnikov };

// How caustics are computed; see docs/caustics.md.
struct CausticSettings {
  CausticMethod method = CausticMethod::None;
  uint64_t photons = 200000;  // emitted per pass, over all lights
  int gather = 100;           // k: each photon's radius is the distance to its k-th nearest
  // gather: auto — k chosen per photon, up to ⌈1/noise²⌉ (caustics/AutomaticGather.h).
  bool automaticGather = false;
  float gatherNoise = 0.05f;
  float maxRadius = 0.0f;  // cap on the photon radii; 0: automatic from the casters' size
  PhotonFilter filter = PhotonFilter::Cone;
  int maxBounces = 16;  // specular bounces a photon may take before it is dropped
  // Progressive photon mapping: passes whose radii shrink by the rule of Knaus & Zwicker 2011.
  bool progressive = false;
  int passes = 16;      // under a time budget that gives no count, kPassesUntilBudget
  float alpha = 0.7f;   // radius shrink: r²(i+1) = r²(i)·(i + alpha)/(i + 1)
  float radius = 0.0f;  // one fixed first-pass radius for every photon; 0: per-photon k-NN radii
  double timeBudgetSeconds = 0;  // stop starting passes after this long; 0: no limit
  // Caustic mapping (Shah et al. 2007): light-space maps of mapResolution² texels per view.
  int mapResolution = 512;
  // Iterations of the receiver-distance estimate: 10 converges where 3 (enough far from the
  // casters) does not, at about 30 % more build time (docs/caustics.md, "Where caustic
  // mapping fails").
  int mapSteps = 10;
  float mapBlurSigma = 1.0f;  // Gaussian σ, texels
  int mapBlurRadius = 2;      // Gaussian half-width, texels; 0: no blur
  CausticMapPaths mapPaths = CausticMapPaths::Traced;
};

// The pass count of a time budget given without one: passes until the budget ends (the largest
// count `passes` takes, 2^20, far beyond any budget).
inline constexpr int kPassesUntilBudget = static_cast<int>(limits::kPasses.max);
inline bool passesUntilBudget(const CausticSettings& c) {
  return c.timeBudgetSeconds > 0.0 && c.passes == kPassesUntilBudget;
}

struct SceneDescription {
  std::string sourcePath;
  CameraDesc camera;
  RenderSettings render;
  CausticSettings caustics;
  Color background{0.0f};    // radiance of rays that escape, when there is no cube map
  Color ambientLight{0.0f};  // ambient radiance, scaled by each material's ambient colour
  std::optional<CubeMapDesc> environment;
  std::vector<MaterialDesc> materials;
  std::vector<TextureDesc> textures;  // read by the materials' texture maps
  std::vector<PointLightDesc> lights;
#define PRISM_SHAPE_LIST(Shape, plural) std::vector<Shape##Desc> plural;
  PRISM_SHAPE_KINDS(PRISM_SHAPE_LIST)  // spheres, cones, ... (geometry/ShapeKinds.h)
#undef PRISM_SHAPE_LIST
  std::vector<PlaneDesc> planes;
  std::vector<MeshDesc> meshes;
  // What the files held that Prism does not model or could not use, each once
  // ("file:line: what was skipped and what is used instead"); printed by the commands on rank 0.
  std::vector<std::string> warnings;
  // Choices made for the user that the run's summary reports (a model file rendered as a scene:
  // the camera and lights it got).
  std::vector<std::string> notes;

  size_t triangleCount() const {
    size_t n = 0;
    for (const auto& m : meshes) n += m.triangleCount();
    return n;
  }
};

// Calls f(list) with each shape kind's list of descriptions, in the order of
// geometry/ShapeKinds.h.
template <class Description, class F>
requires std::is_same_v<std::remove_const_t<Description>, SceneDescription>
void forEachShapeList(Description& d, F&& f) {
#define PRISM_SHAPE_VISIT(Shape, plural) f(d.plural);
  PRISM_SHAPE_KINDS(PRISM_SHAPE_VISIT)
#undef PRISM_SHAPE_VISIT
}

}  // namespace prism
