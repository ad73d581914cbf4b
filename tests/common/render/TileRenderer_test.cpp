#include "render/TileRenderer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

#include "caustics/CausticMapEstimator.h"
#include "parse/SceneLoader.h"

namespace prism {
namespace {

// Whether two tiles have the same pixels bit for bit and counted the same rays.
void expectSameTile(const TileResult& a, const TileResult& b, const std::string& what) {
  ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
  int differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(Color)) != 0;
  }
  EXPECT_EQ(differing, 0) << what;
  EXPECT_EQ(a.rays.primary, b.rays.primary) << what;
  EXPECT_EQ(a.rays.shadow, b.rays.shadow) << what;
  EXPECT_EQ(a.rays.secondary, b.rays.secondary) << what;
}

TileResult renderTile(const TileRenderer& renderer, const TileRect& rect) {
  return renderer.render(0, rect);
}

// Camera rays traced as packets of eight (4 × 2 pixel blocks), with their shadow rays (a packet
// per light) and first reflection and refraction rays as packets, give every pixel the value and
// the ray counts tracing them one by one gives, bit for bit: every scene in scenes/ (caustic maps
// included) and the SPD files in tests/data, whole frames and a tile whose width and height are not
// multiples of the block, one sample per pixel and several.
TEST(TileRenderer, CameraRayPacketsGiveTheSameImageAsSingleRays) {
  const std::string root = PRISM_SOURCE_DIR;
  const char* scenes[] = {
      "/scenes/default.yaml",
      "/scenes/caustic-glass-knot.yaml",
      "/scenes/caustic-glass-sphere.yaml",
      "/scenes/caustic-map-grazing.yaml",
      "/scenes/caustic-map-hidden-receiver.yaml",
      "/scenes/caustic-map-mirror-view.yaml",
      "/scenes/caustic-mirror.yaml",
      "/scenes/caustic-ring.yaml",
      "/scenes/lambert-plane.yaml",
      "/scenes/textured-still-life.yaml",
      "/scenes/globe.glb",
      "/tests/data/nff/balls-s2.nff",
      "/tests/data/nff/gears-s2.nff",
      "/tests/data/nff/jacks-s1.nff",
      "/tests/data/nff/mount-s4.nff",
      "/tests/data/nff/rings-s3.nff",
      "/tests/data/nff/sample-s1.nff",
      "/tests/data/nff/teapot-s3.nff",
      "/tests/data/nff/tetra-s4.nff",
      "/tests/data/nff/tree-s7.nff",
  };
  for (const char* path : scenes) {
    SceneDescription d = loadScene(root + path);
    d.render.width = 72;
    d.render.height = 54;
    d.render.samplesPerPixel = std::string(path) == "/scenes/default.yaml" ? 3 : 1;
    const Scene scene(d);
    // Caustic maps are looked up per pixel like the rest of the shading: include them. Photon
    // maps gather over the pixel's footprint and so always trace one ray at a time.
    std::unique_ptr<CausticMapEstimator> maps;
    LightTerms terms;
    if (d.caustics.method == CausticMethod::CausticMap) {
      maps = std::make_unique<CausticMapEstimator>(scene, 1);
      terms.caustics = maps.get();
    }
    TileRenderer packets(scene, terms), single(scene, terms);
    single.setCameraRays(CameraRays::OneByOne);
    for (const TileRect& rect : {TileRect{0, 0, 72, 54}, TileRect{5, 3, 13, 7}}) {
      expectSameTile(renderTile(packets, rect), renderTile(single, rect),
                     std::string(path) + " tile at " + std::to_string(rect.x));
    }
  }
}

// Records where each footprint the caustic estimate is asked for lies: the hit plus the
// footprint's offset to its cell's centre, and the cell's size.
class FootprintCells : public CausticEstimator {
 public:
  Color irradiance(const Vec3&, const Vec3&) const override { return Color(0.0f); }
  Color irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint) const override {
    centres.push_back(s.position + footprint.offset());
    samples.push_back(s.position);
    cells.push_back(footprint.cell);
    return Color(0.0f);
  }
  bool usesFootprint() const override { return true; }
  mutable std::vector<Vec3> centres, samples;
  mutable std::vector<Vec2> cells;
};

// With several jittered samples a pixel, each sample's cell is its stratum, about the stratum's
// centre: an orthographic view straight down at a plane, 8 × 8 pixels of 0.25, 4 spp (2 × 2
// strata of 0.125); sample i of pixel (x, y) has its cell's centre at (-1 + 0.25 x + 0.125
// (i % 2 + 0.5), 0, -1 + 0.25 y + 0.125 (i / 2 + 0.5)).
TEST(TileRenderer, EverySamplesCellIsItsStratumAboutItsCentre) {
  SceneDescription d;
  d.camera.projection = Projection::Orthographic;
  d.camera.position = {0.0f, 1.0f, 0.0f};
  d.camera.lookAt = {0.0f, 0.0f, 0.0f};
  d.camera.up = {0.0f, 0.0f, -1.0f};
  d.camera.width = 2.0f;
  d.render.width = d.render.height = 8;
  d.render.samplesPerPixel = 4;
  MaterialDesc floor;
  floor.diffuse = Color(0.5f);
  d.materials.push_back(floor);
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  const Scene scene(d);
  FootprintCells probe;
  const TileRenderer renderer(scene, {true, &probe});
  renderTile(renderer, {0, 0, 8, 8});
  ASSERT_EQ(probe.centres.size(), 8u * 8u * 4u);
  float jitter = 0.0f;
  for (size_t n = 0; n < probe.centres.size(); ++n) {
    const int i = static_cast<int>(n % 4), pixel = static_cast<int>(n / 4);
    const int x = pixel % 8, y = pixel / 8;
    const Vec3 centre(-1.0f + 0.25f * x + 0.125f * (i % 2 + 0.5f), 0.0f,
                      -1.0f + 0.25f * y + 0.125f * (i / 2 + 0.5f));
    EXPECT_NEAR(glm::length(probe.centres[n] - centre), 0.0f, 1e-5f) << "sample " << n;
    EXPECT_EQ(probe.cells[n], Vec2(0.5f)) << "sample " << n;
    jitter = std::max(jitter, glm::length(probe.samples[n] - centre));
  }
  EXPECT_GT(jitter, 0.02f);  // the samples themselves lie off the centres
}

// The viewer's passes: its own camera and size, one jittered sample per pixel.
TEST(TileRenderer, CameraRayPacketsGiveTheSameViewerPass) {
  const SceneDescription d = loadScene(std::string(PRISM_SOURCE_DIR) + "/scenes/default.yaml");
  const Scene scene(d);
  RenderView view;
  view.camera = d.camera;
  view.camera.position += Vec3(0.3f, -0.2f, 0.5f);
  view.width = 90;
  view.height = 50;
  view.seed = 17;
  view.jitterSingleSample = true;
  TileRenderer packets(scene, view), single(scene, view);
  single.setCameraRays(CameraRays::OneByOne);
  expectSameTile(renderTile(packets, {0, 0, 90, 50}), renderTile(single, {0, 0, 90, 50}),
                 "viewer pass");
}

}  // namespace
}  // namespace prism
