// Closed-form tests of the photon tracer: energy (an index-1 caster lets light through
// unchanged), flux (a glass slab transmits (1 − R)/(1 + R)), focus (a glass ball images the light
// where the thick-lens equation says) and progressive convergence (error falls with passes at
// the rate PPPM theory predicts).
#include "caustics/PhotonTracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ios>

#include "caustics/PhotonGather.h"
#include "shading/Optics.h"
#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

constexpr double kPiD = 3.14159265358979323846;

MaterialDesc clearMaterial(float ior) {
  MaterialDesc m;
  m.diffuse = Color(0.0f);
  m.transmittance = Color(1.0f);
  m.ior = ior;
  m.fresnel = true;
  return m;
}

MaterialDesc diffuseMaterial() {
  MaterialDesc m;
  m.diffuse = Color(0.8f);
  return m;
}

Color totalPower(const std::vector<Photon>& photons) {
  glm::dvec3 sum(0.0);
  for (const Photon& p : photons) sum += glm::dvec3(p.power);
  return Color(sum);
}

// ---- roulette -------------------------------------------------------------------------------

// Half-transmitting ball of index 1 (it absorbs the other half at each of its two surfaces, and
// deviates nothing): each photon through it lands where the same photon lands through a clear
// ball, with probability 1/4. Binned on the floor, the stored counts are then 1/4 of the clear
// ball's in every bin, give or take the roulette's spread. Decided at random, that spread is
// binomial: χ² per bin about 1 (measured 1.02; ± 0.07 over 376 bins). Decided along each cell's
// low-discrepancy sequence, the share kept is closer to 1/4 in every bin: measured 0.42 (0.61
// with the Halton point over the whole map; what is left comes from the bins' edges, which cut
// the cells and their sequences' strata).
TEST(PhotonTracerRoulette, TheShareKeptInEverySmallRegionIsTheProbabilityNotARandomDraw) {
  constexpr uint64_t kPhotons = 200000;
  constexpr int kBins = 20;  // over [−2, 2]² on the floor: about 300 clear-ball photons a bin
  const auto binCounts = [&](float transmittance, size_t& stored) {
    SceneDescription d = test::ballOverFloorScene(1.0f);
    d.materials[0].transmittance = Color(transmittance);
    const Scene scene(d);
    const PhotonTracer tracer(scene, kPhotons, 16);
    const std::vector<Photon> photons = tracePhotons(tracer, 0, 0, kPhotons, 2);
    stored = photons.size();
    std::vector<double> counts(kBins * kBins, 0.0);
    for (const Photon& p : photons) {
      const int bx = static_cast<int>(std::floor((p.position.x + 2.0f) / 4.0f * kBins));
      const int bz = static_cast<int>(std::floor((p.position.z + 2.0f) / 4.0f * kBins));
      if (bx >= 0 && bx < kBins && bz >= 0 && bz < kBins) counts[bz * kBins + bx] += 1.0;
    }
    return counts;
  };
  size_t clearStored = 0, halfStored = 0;
  const std::vector<double> clear = binCounts(1.0f, clearStored);
  const std::vector<double> half = binCounts(0.5f, halfStored);
  constexpr double kKept = 0.25;
  // Unbiased: the kept share over all photons is 1/4 (binomial σ ≈ 0.1 %; 5σ).
  const double share = static_cast<double>(halfStored) / static_cast<double>(clearStored);
  EXPECT_NEAR(share, kKept, 5.0 * std::sqrt(kKept * (1.0 - kKept) / clearStored));
  double chi2 = 0.0;
  int bins = 0;
  for (size_t b = 0; b < clear.size(); ++b) {
    if (clear[b] < 100.0) continue;
    const double expected = kKept * clear[b];
    chi2 += (half[b] - expected) * (half[b] - expected) / (expected * (1.0 - kKept));
    ++bins;
  }
  ASSERT_GT(bins, 300);
  EXPECT_LT(chi2 / bins, 0.7) << "χ² per bin over " << bins << " bins";
}

// Fewer photons than marked cells (about 9 000 for this ball): they must still spread over the
// whole cap the ball fills, not over the first cells of the map's list (its rim, in rows of
// constant latitude). Half of them land within the radius that holds half of 200 000 photons.
TEST(PhotonTracerEmission, FewerPhotonsThanCellsStillSpreadOverTheWholeCap) {
  const Scene scene(test::ballOverFloorScene(1.0f));
  const auto radiiFromAxis = [&](uint64_t count) {
    const PhotonTracer tracer(scene, count, 16);
    std::vector<float> r;
    for (const Photon& p : tracePhotons(tracer, 0, 0, count, 2))
      r.push_back(std::hypot(p.position.x, p.position.z));
    return r;
  };
  std::vector<float> many = radiiFromAxis(200000);
  std::nth_element(many.begin(), many.begin() + many.size() / 2, many.end());
  const float median = many[many.size() / 2];
  const std::vector<float> few = radiiFromAxis(2000);
  ASSERT_GT(few.size(), 1500u);
  const double inside = static_cast<double>(std::count_if(
                            few.begin(), few.end(), [median](float r) { return r < median; })) /
                        static_cast<double>(few.size());
  EXPECT_NEAR(inside, 0.5, 0.05);
}

// ---- energy ---------------------------------------------------------------------------------

// A sphere of radius 1 at (0, 2, 0) made of "glass" of index 1 (transmittance 1, Fresnel on: at
// n = 1 Fresnel reflects nothing), a point light of intensity I at (0, 4, 0), a diffuse floor
// y = 0. Light passes the sphere undeviated, so the photons under it must reproduce the direct
// irradiance E = I·cos θ / d² = I·h / d³ (h = 4, d² = h² + x² + z²).
constexpr float kEnergyIntensity = test::kBallLightIntensity;
constexpr float kLightHeight = test::kBallLightHeight;

SceneDescription indexOneScene() {
  return test::ballOverFloorScene(1.0f);
}

double directIrradiance(double x, double z) {
  return test::ballOverFloorDirectIrradiance(x, z);
}

TEST(PhotonTracerEnergy, IndexOneCasterPassesExactlyItsConeOfFlux) {
  const Scene scene(indexOneScene());
  constexpr uint64_t kPhotons = 200000;
  const PhotonTracer tracer(scene, kPhotons, 16);
  ASSERT_TRUE(tracer.hasWork());
  ASSERT_EQ(tracer.photonsPerPass(), kPhotons);
  PhotonTraceStats stats;
  const std::vector<Photon> photons = tracePhotons(tracer, 0, 0, kPhotons, 0, &stats);
  EXPECT_EQ(stats.emitted, kPhotons);
  EXPECT_EQ(stats.stored, photons.size());
  // Every photon ends once, as missed (nothing needed it) or absorbed (its path ended after a
  // bounce — a stored photon ends on its receiver, so it counts there too).
  EXPECT_EQ(stats.emitted, stats.missed + stats.absorbed);
  EXPECT_EQ(stats.absorbed, stats.stored);  // here every photon that hit the sphere landed
  // Every photon that hit the sphere went through and landed on the floor, with its power
  // unchanged: the stored power is the flux into the sphere's cone, I·2π(1 − cos β), sin β = 1/2.
  // Each photon hits with probability p = cap / covered (binomial): σ_rel = √((1 − p)/(N p)),
  // ≈ 0.1 % here; 5σ.
  const double cap = 2.0 * kPiD * (1.0 - std::cos(std::asin(0.5)));
  const double p = cap / tracer.plans()[0].map.coveredSolidAngle();
  const double sigma = std::sqrt((1.0 - p) / (kPhotons * p));
  const Color stored = totalPower(photons);
  EXPECT_NEAR(stored.x / (kEnergyIntensity * cap), 1.0, 5.0 * sigma);
  EXPECT_EQ(stored.x, stored.z);  // colourless glass keeps the light white
  RecordProperty("stored_over_expected", std::to_string(stored.x / (kEnergyIntensity * cap)));
  for (const Photon& ph : photons) {
    ASSERT_NEAR(ph.position.y, 0.0f, 1e-4f);
    // Undeviated: the photon lands where the straight line from the light meets the floor,
    // inside the sphere's shadow of radius 4·tan 30°.
    ASSERT_LE(std::hypot(ph.position.x, ph.position.z), 4.0f * std::tan(kPi / 6.0f) + 1e-3f);
  }
}

// Irradiance from the photons at points well inside the shadow (radius 2.31; the farthest point
// is 1.6 + the gather radius 0.1 from the axis), fixed-radius box gather. The box estimate is
// Φ·n / (π r²) with n ~ Poisson: σ_rel = 1/√n; the test takes 4/√n with n as found (≈ 900–1900).
// The irradiance's curvature over the disc biases the box average by ~ r²/h² ≈ 0.06 %, far
// below that.
TEST(PhotonTracerEnergy, PhotonIrradianceUnderAnIndexOneCasterIsTheDirectLight) {
  const Scene scene(indexOneScene());
  constexpr uint64_t kPhotons = 400000;
  const PhotonTracer tracer(scene, kPhotons, 16);
  auto map = std::make_shared<const PhotonMap>(tracePhotons(tracer, 0, 0, kPhotons, 0));
  const float radius = 0.1f;
  const PhotonGather gather(map, {true, 1, radius, PhotonFilter::Box});
  std::vector<PhotonNeighbour> found;
  double worst = 0.0;
  for (const Vec3 p : {Vec3(0, 0, 0), Vec3(0.5f, 0, 0), Vec3(-0.7f, 0, 0.7f), Vec3(0, 0, -1.2f),
                       Vec3(1.1f, 0, 1.1f), Vec3(-1.6f, 0, 0)}) {
    map->within(p, radius * radius, found);
    const double n = static_cast<double>(found.size());
    const double expected = directIrradiance(p.x, p.z);
    const double measured = gather.irradiance(p, Vec3(0, 1, 0)).y;
    EXPECT_NEAR(measured / expected, 1.0, 4.0 / std::sqrt(n)) << p.x << ", " << p.z << ": " << n;
    worst = std::max(worst, std::abs(measured / expected - 1.0));
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

// ---- flux through a slab ------------------------------------------------------------------

// Glass of index 1.5 between the planes y = 2 (normal +y) and y = 1 (normal −y), a diffuse floor
// y = 0 and a point light at (0, 4, 0). A photon reaching the slab at incidence θ is reflected
// with the unpolarised Fresnel reflectance R(θ) at the top; inside, it meets the bottom at the
// refracted angle, where the reflectance is the same R (Stokes), and so on. Summing the
// incoherent multiple reflections of a non-absorbing slab, the fraction that leaves downward is
//   T = (1 − R)² Σ R^{2k} = (1 − R)² / (1 − R²) = (1 − R) / (1 + R).
// Those photons all land on the floor and are stored; those reflected upwards escape. Over the
// lower hemisphere of directions (dω = 2π dμ, μ = cos θ) the expected stored power is
//   P = I · 2π ∫₀¹ T(θ(μ)) dμ.
TEST(PhotonTracerFlux, StoredPowerUnderASlabIsTheFresnelTransmittedFlux) {
  SceneDescription d;
  d.materials = {clearMaterial(1.5f), diffuseMaterial()};
  d.planes.push_back({{0, 2, 0}, {0, 1, 0}, 0, {}});
  d.planes.push_back({{0, 1, 0}, {0, -1, 0}, 0, {}});
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 1, {}});
  PointLightDesc light;
  light.position = {0, 4, 0};
  light.intensity = Color(10.0f);
  d.lights.push_back(light);
  const Scene scene(d);

  // A ray at θ needs 2k + 1 bounces for k internal round trips; R^{2k} after 64 bounces is
  // < 1e-6 for every θ below 89.5°, where T·dμ is already negligible.
  constexpr int kMaxBounces = 64;
  constexpr uint64_t kPhotons = 300000;
  const PhotonTracer tracer(scene, kPhotons, kMaxBounces);
  PhotonTraceStats stats;
  const std::vector<Photon> photons = tracePhotons(tracer, 0, 0, kPhotons, 0, &stats);

  // The expectation, by the midpoint rule in μ (T is smooth; 10⁵ steps: error ≪ 1e-6).
  constexpr int kSteps = 100000;
  double integral = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const float mu = static_cast<float>((i + 0.5) / kSteps);
    const double r = fresnelDielectric(mu, 1.0f / 1.5f);
    integral += (1.0 - r) / (1.0 + r);
  }
  const double expected = 10.0 * 2.0 * kPiD * integral / kSteps;

  // Russian roulette with colourless glass leaves every photon's power at Φ = I·Ω/N, so the
  // stored power is Φ times a binomial count with p = stored/emitted: σ_rel = √((1 − p)/(N p)),
  // about 0.3 %. 5σ; the truncation at 64 bounces adds < 1e-5.
  const double p = static_cast<double>(stats.stored) / static_cast<double>(stats.emitted);
  const double sigma = std::sqrt((1.0 - p) / (kPhotons * p));
  const double stored = totalPower(photons).x;
  EXPECT_NEAR(stored / expected, 1.0, 5.0 * sigma)
      << "stored " << stored << " W, expected " << expected << " W";
  RecordProperty("stored_over_expected", std::to_string(stored / expected));
  // Sanity of the expectation: at normal incidence R = ((n − 1)/(n + 1))² = 0.04, T = 0.96/1.04;
  // T falls towards grazing incidence, so the slab passes between half and T(0) of I·2π.
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  EXPECT_LT(expected, 0.96 / 1.04 * 10.0 * 2.0 * kPiD);
  EXPECT_GT(expected, 0.5 * 10.0 * 2.0 * kPiD);
  for (const Photon& ph : photons) ASSERT_NEAR(ph.position.y, 0.0f, 1e-4f);
}

// ---- focus --------------------------------------------------------------------------------

// A glass ball (radius R = 1, n = 1.5, centre at the origin) under a point light on its axis at
// distance s = 20. A ball lens's principal planes both pass through its centre and its focal
// length is f = nR / (2(n − 1)) = 1.5, so the thick-lens equation 1/s + 1/s' = 1/f, with both
// distances measured from the centre, puts the paraxial image of the light at
//   s' = 1 / (1/f − 1/s) = 1 / (2/3 − 1/20) = 60/37 ≈ 1.6216 below the centre.
// Spherical aberration brings marginal rays to the axis sooner: a ray entering at height h
// crosses it ≈ 0.52 h² earlier (traced exactly in 2D: 0.005 at h = 0.1, 0.13 at h = 0.5), and
// with the whole ball lit the brightest on-axis point lies well above s' (measured: see below).
// The paraxial image is the cusp of the caustic; to see it as a peak the test stops the ball
// down: an opaque screen (caustic role off: photons meeting it first are dropped) with a square
// hole of half-width 0.06 at y = 2.5 lets through only rays entering at h ≤ 0.092, whose
// aberration is ≤ 0.0045.
//
// Receivers: thin index-1 sheets (diffuse, transmittance 1, so they store the photon and pass
// it on unchanged) at depths s' + δ: one trace stores the beam's cross-section at every depth.
// The on-axis irradiance is gathered from the 40 nearest photons (at most 0.004 away, under half
// the sheets' spacing), so the estimate follows the beam as it narrows instead of saturating
// at a fixed radius.
constexpr double kBallIor = 1.5, kLightDistance = 20.0;
const double kFocal = kBallIor * 1.0 / (2.0 * (kBallIor - 1.0));
const double kImage = 1.0 / (1.0 / kFocal - 1.0 / kLightDistance);

SceneDescription ballScene(const std::vector<double>& depths, float hole) {
  SceneDescription d;
  MaterialDesc screen;
  screen.diffuse = Color(0.0f);
  MaterialDesc sheet = clearMaterial(1.0f);
  sheet.diffuse = Color(0.5f);
  d.materials = {clearMaterial(static_cast<float>(kBallIor)), screen, sheet};
  d.spheres.push_back({{0, 0, 0}, 1.0f, 0, {}});
  if (hole > 0.0f) {
    // A 3 × 3 square at y = 2.5 with a hole of half-width `hole`: four trapezoids, 8 triangles.
    MeshDesc m;
    const float o = 1.5f, y = 2.5f;
    m.positions = {{-o, y, -o},       {o, y, -o},       {o, y, o},       {-o, y, o},
                   {-hole, y, -hole}, {hole, y, -hole}, {hole, y, hole}, {-hole, y, hole}};
    for (uint32_t i = 0; i < 4; ++i) {
      const uint32_t j = (i + 1) % 4;
      m.indices.insert(m.indices.end(), {i, j, 4 + j, i, 4 + j, 4 + i});
    }
    m.material = 1;
    m.caustic = CausticRole::Off;
    d.meshes.push_back(m);
  }
  for (double depth : depths) {
    MeshDesc m;
    const float w = 0.4f, y = static_cast<float>(-depth);
    m.positions = {{-w, y, -w}, {w, y, -w}, {w, y, w}, {-w, y, w}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.material = 2;
    d.meshes.push_back(m);
  }
  PointLightDesc light;
  light.position = {0, static_cast<float>(kLightDistance), 0};
  light.intensity = Color(1.0f);
  d.lights.push_back(light);
  return d;
}

// On-axis irradiance on each sheet, by k-NN.
std::vector<double> axialIrradiance(const std::vector<double>& depths, float hole, uint64_t photons,
                                    int k, float maxRadius) {
  const Scene scene(ballScene(depths, hole));
  const PhotonTracer tracer(scene, photons, 2 + static_cast<int>(depths.size()) + 4);
  const auto map = std::make_shared<const PhotonMap>(tracePhotons(tracer, 0, 0, photons, 0));
  const PhotonGather gather(map, {false, k, maxRadius, PhotonFilter::Cone});
  std::vector<double> e;
  for (double depth : depths) {
    e.push_back(gather.irradiance(Vec3(0, static_cast<float>(-depth), 0), Vec3(0, 1, 0)).x);
  }
  return e;
}

// The sheets sit at s' + δ for δ = 0, ±0.01, ±0.02, ...: the brightest must be δ = 0, so the
// peak lies within ±0.01 (0.6 % of s') of the prediction; the aperture's own aberration, 0.0045,
// is inside that. Measured (1.5 M photons, about 5 k through the hole): E(s') ≈ 8·10⁶ against
// ≈ 65 at ±0.01 — the stopped-down beam comes to a point at s' and spreads symmetrically.
TEST(PhotonTracerFocus, StoppedDownBallFocusesWhereTheThickLensEquationSays) {
  EXPECT_NEAR(kImage, 60.0 / 37.0, 1e-12);
  const std::vector<double> offsets = {-0.1, -0.06, -0.03, -0.02, -0.01, 0.0,
                                       0.01, 0.02,  0.03,  0.06,  0.1};
  std::vector<double> depths;
  for (double o : offsets) depths.push_back(kImage + o);
  const std::vector<double> e = axialIrradiance(depths, 0.06f, 1500000, 40, 0.004f);
  const size_t peak = static_cast<size_t>(std::max_element(e.begin(), e.end()) - e.begin());
  EXPECT_EQ(offsets[peak], 0.0) << "the caustic peaks at s' " << std::showpos << offsets[peak];
  // Symmetric about the focus: equal offsets before and after give the same irradiance within
  // the k-NN noise (1/√40 ≈ 16 % each; a factor 2 is > 4σ).
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_GT(e[i] / e[10 - i], 0.5) << offsets[i];
    EXPECT_LT(e[i] / e[10 - i], 2.0) << offsets[i];
  }
  RecordProperty("irradiance_at_s_prime", std::to_string(e[5]));
}

// With the whole ball lit, marginal rays cross the axis up to ~0.5 before s' (h → 1), so the
// axis before s' is a line caustic, bright all along, while after s' no ray crosses it. The
// k-NN estimate (k = 40) resolves the densest part — the paraxial rays meeting at the cusp —
// and still peaks at s' (measured: E(s') ≈ 1.4·10⁶, E(s' − 0.025) ≈ 2·10⁴, E(s' + 0.025) ≈ 13).
// A fixed-radius estimate, by contrast, would average the cusp with the line caustic: what
// finite radius sees as "brightest" shifts towards the circle of least confusion. The test
// checks the cusp at s' and the asymmetry: far brighter before s' than after.
TEST(PhotonTracerFocus, FullyLitBallHasItsCuspAtTheParaxialImageAndALineCausticBefore) {
  const std::vector<double> offsets = {-0.3, -0.1, -0.05, -0.01, 0.0, 0.01, 0.05, 0.1};
  std::vector<double> depths;
  for (double o : offsets) depths.push_back(kImage + o);
  const std::vector<double> e = axialIrradiance(depths, 0.0f, 200000, 40, 0.004f);
  const size_t peak = static_cast<size_t>(std::max_element(e.begin(), e.end()) - e.begin());
  EXPECT_EQ(offsets[peak], 0.0) << "the cusp is at s' " << std::showpos << offsets[peak];
  EXPECT_GT(e[2], 100.0 * e[6]) << "s' ∓ 0.05: " << e[2] << " vs " << e[6];
  EXPECT_GT(e[1], 100.0 * e[7]) << "s' ∓ 0.1: " << e[1] << " vs " << e[7];
}

}  // namespace
}  // namespace prism
