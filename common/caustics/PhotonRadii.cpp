#include "caustics/PhotonRadii.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "caustics/AutomaticGather.h"
#include "util/Parallel.h"
#include "util/SelectNth.h"

namespace prism {

namespace {

// Photons placed one after another by one thread, in the tree's leaf order: each bounds the next.
constexpr size_t kChunkSize = 64;
// Slack on the bound from the last photon, far above float rounding.
constexpr float kBoundSlack = 1.001f;

// How many of the photons placed last bound the next: the nearest of them gives the tightest.
constexpr int kRecent = 8;
// A photon's radius seldom differs from a near one's by the whole step between them: a search
// first within this guess (radius · 1.02 + step · 0.3) holds k about as often as not and reads
// fewer photons; when it does not, the sure bound follows. 11-20 % off the radii, measured.
constexpr float kGuessRadius = 1.02f, kGuessStep = 0.3f;

}  // namespace

std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                               int threads) {
  std::vector<float> radii(map.size());
  const float maxRadius2 = maxRadius * maxRadius;
  const std::vector<uint32_t> order = map.spatialOrder();
  const std::vector<int> ladder = automaticGatherLadder(k);
  const size_t chunks = (order.size() + kChunkSize - 1) / kChunkSize;
  parallelFor(chunks, threads, [&](uint64_t chunk) {
    thread_local std::vector<PhotonNeighbour> found;
    thread_local std::vector<float> distance2;
    const size_t first = chunk * kChunkSize, last = std::min(order.size(), first + kChunkSize);
    // The photons placed last with k within maxRadius, and their radii.
    Vec3 recentPosition[kRecent];
    float recentRadius[kRecent];
    int recent = 0, placed = 0;
    for (size_t n = first; n < last; ++n) {
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
      radii[i] = std::sqrt(radius2);
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

}  // namespace prism
