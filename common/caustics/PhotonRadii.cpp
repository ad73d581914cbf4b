#include "caustics/PhotonRadii.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "caustics/AutomaticGather.h"
#include "util/Parallel.h"
#include "util/SelectNth.h"

namespace prism {

namespace {

// Slack on the bound from the last photon, far above float rounding.
constexpr float kBoundSlack = 1.001f;

// How many of the photons placed last bound the next: the nearest of them gives the tightest.
constexpr int kRecent = 8;
// A photon's radius seldom differs from a near one's by the whole step between them: a search
// first within this guess (radius · 1.02 + step · 0.3) holds k about as often as not and reads
// fewer photons; when it does not, the sure bound follows. 11-20 % off the radii, measured.
constexpr float kGuessRadius = 1.02f, kGuessStep = 0.3f;

}  // namespace

std::vector<float> photonRadiiShare(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                                    size_t first, size_t count, int threads,
                                    const std::atomic<bool>* cancel) {
  const std::vector<uint32_t>& order = map.spatialOrder();
  if (first % kPhotonRadiiChunk != 0 || first > order.size() || count > order.size() - first) {
    throw std::invalid_argument("photon radii share [" + std::to_string(first) + ", +" +
                                std::to_string(count) + ") of " + std::to_string(order.size()) +
                                " photons does not start at a chunk or runs past the map");
  }
  std::vector<float> radii(count, 0.0f);
  const float maxRadius2 = maxRadius * maxRadius;
  const std::vector<int> ladder = automaticGatherLadder(k);
  const size_t end = first + count;
  const size_t chunks = (count + kPhotonRadiiChunk - 1) / kPhotonRadiiChunk;
  parallelFor(chunks, threads, [&](uint64_t chunk) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    thread_local std::vector<PhotonNeighbour> found;
    thread_local std::vector<float> distance2;
    const size_t chunkFirst = first + chunk * kPhotonRadiiChunk;
    const size_t last = std::min(end, chunkFirst + kPhotonRadiiChunk);
    // The photons placed last with k within maxRadius, and their radii.
    Vec3 recentPosition[kRecent];
    float recentRadius[kRecent];
    int recent = 0, placed = 0;
    for (size_t n = chunkFirst; n < last; ++n) {
      const uint32_t i = order[n];
      const Vec3& position = map.photons()[i].position;
      // The photons placed last are near, and the k nearest of each lie within its radius plus
      // the step from it, so p's k nearest lie within the smallest such bound too (a little
      // more, for rounding). Every photon within it, in no order, costs one tree walk and no
      // sorting; the k-th smallest of their distances (nanoflann's own, the ones
      // PhotonMap::nearest compares) is then selected. Any radius holding k will do: the k-th
      // smallest below it is the k-th of all. So the guess is tried first. Below the bound there
      // were fewer than k only if rounding beat the slack: then the k-nearest search, as for a
      // chunk's first photon or where no recent photon had k within maxRadius.
      int count = -1;  // photons within maxRadius, up to k; -1 until known
      if (recent > 0) {
        float bound = std::numeric_limits<float>::infinity();
        float guess = std::numeric_limits<float>::infinity();
        for (int r = 0; r < recent; ++r) {
          const float step = glm::length(position - recentPosition[r]);
          bound = std::min(bound, step + recentRadius[r]);
          guess = std::min(guess, kGuessStep * step + kGuessRadius * recentRadius[r]);
        }
        bound *= kBoundSlack;
        const float limit2 = std::min(bound * bound, maxRadius2);
        bool holdsK = false;
        if (guess < bound && guess * guess < maxRadius2) {
          map.distancesWithin(position, guess * guess, distance2);
          holdsK = distance2.size() >= static_cast<size_t>(k);
        }
        if (!holdsK) map.distancesWithin(position, limit2, distance2);
        if (distance2.size() >= static_cast<size_t>(k)) {
          count = k;
        } else if (limit2 == maxRadius2) {
          count = static_cast<int>(distance2.size());
        }
      }
      if (count < 0) {
        map.nearest(position, k, maxRadius2, found);
        count = static_cast<int>(found.size());
        distance2.resize(found.size());
        for (size_t j = 0; j < found.size(); ++j) distance2[j] = found[j].distance2;
      }
      // Put the ranks the radius needs in place: the largest first, each later selection among
      // the nearer ones before it, which leaves the earlier ranks where they are.
      size_t end = distance2.size();
      const auto select = [&](int rank) {
        if (rank > count) return;
        selectNth(distance2.data(), end, static_cast<size_t>(rank) - 1);
        end = static_cast<size_t>(rank) - 1;
      };
      const auto ofRank = [&](int rank) { return distance2[static_cast<size_t>(rank) - 1]; };
      float radius2;
      if (automaticK) {
        for (auto r = ladder.rbegin(); r != ladder.rend(); ++r) select(*r);
        radius2 = automaticGatherRadius2(ladder, count, ofRank, maxRadius2);
      } else {
        select(k);
        radius2 = count == k ? ofRank(k) : maxRadius2;
      }
      radii[n - first] = std::sqrt(radius2);
      if (count == k) {
        recentPosition[placed % kRecent] = position;
        recentRadius[placed % kRecent] = std::sqrt(ofRank(k));
        recent = std::min(recent + 1, kRecent);
        ++placed;
      }
    }
  });
  return radii;
}

void placePhotonRadii(const PhotonMap& map, size_t first, const std::vector<float>& share,
                      std::vector<float>& radii) {
  const std::vector<uint32_t>& order = map.spatialOrder();
  for (size_t n = 0; n < share.size(); ++n) radii[order[first + n]] = share[n];
}

std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                               int threads) {
  std::vector<float> radii(map.size());
  placePhotonRadii(map, 0, photonRadiiShare(map, k, maxRadius, automaticK, 0, map.size(), threads),
                   radii);
  return radii;
}

}  // namespace prism
