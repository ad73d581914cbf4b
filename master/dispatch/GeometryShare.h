// One build per job where it pays: rank 0 either broadcasts the geometry it built (the BVH, the
// triangle packs, the primitives in BVH order: wire/GeometryCodec.h) or every rank builds its
// own from the description it already has. The build is deterministic, so the pixels are the
// same either way; only the time to the first tile differs.
//
// The rule (docs/distributed.md, "One build per job"): with W the build's work, each rank
// builds at the pace of the cores it really gets, min(its build threads, its machine's cores /
// the job's ranks on that machine), since ranks on one machine build at once and share them.
//   every rank builds:  max over ranks of W / pace
//   broadcast:          W / rank 0's pace alone (the slaves sleep meanwhile)
//                       + bytes / link rate + bytes / codec rate (encode, checksum, decode)
// The link rate is the one the job has just measured: the scene description's own broadcast
// (bytes over seconds), the same collective over the same ranks. Broadcast wins when it is the
// shorter. Between machines alike, every rank building wins (the build is not slower there than
// on rank 0); ranks sharing a machine's cores, or slaves with fewer cores, make the broadcast pay
// once the link moves the build faster than they would make it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace prism {

class SceneGeometry;
class Transport;

// How long rank 0's set-up broadcasts (the scene, the geometry) may wait for the slaves (they
// may still be starting).
inline constexpr double kSceneBroadcastTimeoutSeconds = 600.0;

// --bvh-share: auto (the rule above), broadcast, or local (every rank builds its own).
enum class GeometryShareMode { Auto, Broadcast, Local };
// "auto", "broadcast", "local"; parseGeometryShareMode throws std::invalid_argument otherwise.
const char* geometryShareModeName(GeometryShareMode mode);
GeometryShareMode parseGeometryShareMode(const std::string& text);

// Where a rank builds: its build threads (the cores it may run on), its machine's cores, and
// the job's ranks on that machine.
struct BuildPlace {
  int threads = 1;
  int cores = 1;
  int ranksOnNode = 1;
  double pace() const;  // the cores its build really gets
};

// What the rule assumes of a build, measured on the 5 M-triangle torus (docs/scaling.md):
// thread-seconds per triangle, wire bytes per triangle, and the rate of encoding plus decoding.
inline constexpr double kBuildThreadSecondsPerTriangle = 0.5e-6;
inline constexpr double kGeometryBytesPerTriangle = 68.0;
inline constexpr double kGeometryCodecBytesPerSecond = 0.5e9;
// `prism render` sends the geometry while rank 0 renders (DispatchSession::GeometrySending) only
// when the transfer is predicted to take this long: a small scene's geometry goes before the
// frame, so that the slaves have it when the frame's first jobs go out and take part.
inline constexpr double kSendWhileRenderingSeconds = 0.1;

struct GeometrySharePlan {
  GeometryShareMode requested = GeometryShareMode::Auto;
  bool broadcast = false;
  double linkBytesPerSecond = 0.0;  // measured by the description's broadcast
  double eachBuildsSeconds = 0.0;   // predicted: every rank builds its own
  double broadcastSeconds = 0.0;    // predicted: rank 0 builds, then broadcasts
  double transferSeconds = 0.0;     // predicted: of that, encoding, sending and decoding
  // What happened, once it has: the geometry's bytes and the broadcast's time.
  size_t sentBytes = 0;
  double sentSeconds = 0.0;
  bool sentWhileRendering = false;  // as the first frame began, rank 0's threads rendering it

  // For the run summary: "broadcast by rank 0 (auto: 1.20 s against 3.40 s for every rank
  // building; link 1.1 GB/s), 322.7 MiB in 0.41 s".
  std::string describe() const;
};

// The plan for a job of rank0 and slaves (one place each) over a geometry of `triangles`,
// after a description broadcast of descriptionBytes in descriptionSeconds.
GeometrySharePlan planGeometryShare(GeometryShareMode requested, size_t triangles,
                                    size_t descriptionBytes, double descriptionSeconds,
                                    const BuildPlace& rank0, const std::vector<BuildPlace>& slaves);

// Broadcasts rank 0's built geometry to the slaves and notes in plan what was sent, how long it
// took, and whether rank 0's render threads rendered meanwhile.
void broadcastGeometry(Transport& transport, const SceneGeometry& geometry, bool rank0Renders,
                       GeometrySharePlan& plan);

}  // namespace prism
