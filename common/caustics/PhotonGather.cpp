#include "caustics/PhotonGather.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "caustics/DensityKernel.h"
#include "caustics/PhotonRadii.h"

namespace prism {

PhotonGather::PhotonGather(std::shared_ptr<const PhotonMap> map,
                           const PhotonGatherSettings& settings, int threads)
    : PhotonGather(
          map, settings,
          needsRadii(settings, map->size())
              ? photonRadii(*map, settings.k, settings.radius, settings.automaticK, threads)
              : std::vector<float>{},
          threads) {}

PhotonGather::PhotonGather(std::shared_ptr<const PhotonMap> map,
                           const PhotonGatherSettings& settings, std::vector<float> radii,
                           int threads)
    : map_(std::move(map)), settings_(settings) {
  if (!needsRadii(settings_, map_->size())) return;
  if (radii.size() != map_->size()) {
    throw std::invalid_argument(std::to_string(radii.size()) + " photon radii for a map of " +
                                std::to_string(map_->size()) + " photons");
  }
  for (float& r : radii) r *= settings_.radiusScale;
  discs_ = std::make_unique<const PhotonDiscs>(map_->photons(), radii, threads);
}

Color PhotonGather::irradiance(const Vec3& position, const Vec3& normal) const {
  return irradianceWithin(position, normal, {});
}

Color PhotonGather::irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint) const {
  return irradianceWithin(s.position, s.geometricNormal, footprint);
}

Color PhotonGather::irradianceWithin(const Vec3& position, const Vec3& normal,
                                     const PixelFootprint& pixel) const {
  // With a footprint the estimate is the average of the photons' kernels over the sample's cell
  // of its pixel (the pixel itself at 1 spp): a photon narrower than the cell (a disc of less
  // area) counts the share of its kernel the cell holds (kernelShareOfFootprint) over the cell's
  // area; one up to twice the pixel's reach wide, the mean of its kernel over the cell; a wider
  // one, its kernel at the sample, as without a footprint. Counting a narrow photon wholly in
  // the cell its centre lies in made a pixel's value jump by a photon as photons crossed its
  // edges: at the glass ball's focus seen from above, the noise of the count of photons in a
  // footprint was most of the error (docs/accuracy.md). Flipping straight from the narrow rule to
  // the last left a photon counted in no pixel or in two where pixels' footprints differ (seen
  // through a lens): the focus seen from above read 9 % high at k = 400. The cell lies about its
  // own centre, not the jittered sample, so the cells of a pixel's samples tile it and a focus
  // narrower than a pixel stays in its pixel at any spp; the wide photons' kernels are read at
  // the sample itself, whose jitter averages them over the cell.
  const PixelFootprint footprint = pixel.sampleCell();
  const float reach = footprint.valid ? footprint.reach() : 0.0f;
  const float area = footprint.valid ? footprint.area() : 0.0f;
  const float narrow2 = area * kInvPi;
  // Photons up to twice the pixel's reach, not the cell's, are averaged over the cell: kernels
  // about as wide as a pixel, read at each cell's jittered sample (the same points in every
  // progressive pass), left a frozen error at a focus (2 % at 9 spp, the closed form of
  // tests/common/caustics/ProgressiveFocus_test.cpp), and a cone one or two pixels wide read at
  // a point missed the pixel's average where the caustic curves within a pixel (the rings about
  // the focus seen from above: 4 % low two pixels out, 5 % high three out).
  const float pixelReach = pixel.valid ? pixel.reach() : 0.0f;
  const float averaged2 =
      footprint.valid ? std::max(narrow2, 4.0f * pixelReach * pixelReach) : 0.0f;
  const PixelFootprint::Test inFootprint =
      footprint.valid ? footprint.test(normal) : PixelFootprint::Test{};
  // A narrow photon counts where its disc meets the footprint: its centre lies at most its
  // radius outside.
  const PixelFootprint::Test nearFootprint = inFootprint.grownBy(std::sqrt(narrow2));
  const bool hasArea = inFootprint.slab >= 0.0f;
  const float dualALength = glm::length(inFootprint.dualA);
  const float dualBLength = glm::length(inFootprint.dualB);
  const Vec3 centre = footprint.valid ? position + pixel.offset() : position;
  // p: a Photon, or a PhotonDiscs::Disc (the same photon, in tree order).
  const auto overFootprint = [&](const auto& p, float radius2) {
    const Vec3 q = p.position - centre;
    if (radius2 <= narrow2 && !nearFootprint.contains(q)) return 0.0f;
    // Wider photons, and any on a footprint without area (a grazing sliver, no dual basis): the
    // mean of the kernel over 4 × 4 points. (Their shares between the edges, as for the narrow
    // ones, stand for a square kernel whose corners reach √2 of the radius out: light leaked
    // past the caustic's edges, and after 4 progressive passes the focus view's MRSE was 1.6
    // times the midpoint rule's.)
    if (!hasArea || radius2 > narrow2)
      return footprintMeanKernel(settings_.filter, q, footprint.a, footprint.b, radius2);
    return kernelShareOfFootprint(settings_.filter, glm::dot(q, inFootprint.dualA),
                                  glm::dot(q, inFootprint.dualB), dualALength, dualBLength,
                                  std::sqrt(radius2)) /
           area;
  };
  // Photons that arrived from behind the surface (through a thin wall) are left out.
  const auto fromFront = [&](const auto& p) {
    return glm::dot(p.directionVector(), normal) < 0.0f;
  };
  Color sum(0.0f);
  if (!settings_.fixedRadius) {
    if (!discs_) return sum;
    discs_->covering(position, [&](const PhotonDiscs::Disc& p, float distance2, float radius2) {
      if (radius2 > averaged2 && fromFront(p))
        sum += p.power * densityKernel(settings_.filter, distance2, radius2);
    });
    if (footprint.valid) {
      // Narrow photons whose discs miss the footprint add nothing (overFootprint's 0): not
      // visited.
      discs_->reaching(centre, reach, averaged2, narrow2, nearFootprint,
                       [&](const PhotonDiscs::Disc& p, float, float radius2) {
                         if (fromFront(p)) sum += p.power * overFootprint(p, radius2);
                       });
    }
    return sum;
  }
  thread_local std::vector<PhotonNeighbour> neighbours;
  const std::vector<Photon>& photons = map_->photons();
  const float radius2 = settings_.radius * settings_.radius;
  const bool averaged = radius2 <= averaged2;
  const float gatherRadius = averaged ? settings_.radius + reach : settings_.radius;
  map_->within(averaged ? centre : position, gatherRadius * gatherRadius, neighbours);
  for (const PhotonNeighbour& n : neighbours) {
    const Photon& p = photons[n.index];
    if (!fromFront(p)) continue;
    sum += p.power * (averaged ? overFootprint(p, radius2)
                               : densityKernel(settings_.filter, n.distance2, radius2));
  }
  return sum;
}

}  // namespace prism
