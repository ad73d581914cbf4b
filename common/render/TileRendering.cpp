// A tile's pixels: camera rays in packets or one by one, through the integrator (compiled once
// per instruction set; accel/IsaVariant.h, render/RenderKernels.h).
#include <algorithm>
#include <new>
#include <optional>

#include "render/DebugShading.h"
#include "render/TileRenderer.h"
#include "util/ScratchArray.h"
#include "util/Stopwatch.h"

namespace prism {

void TileRenderer::addSample(const Color& sample, Color& sum, RayCounters& rays) {
  // One NaN or infinite sample would poison the pixel and every average it enters.
  if (isFinite(sample)) {
    sum += sample;
  } else {
    ++rays.nonFinite;
  }
}

Color TileRenderer::pixelValue(const Color& sum, RayCounters& rays) const {
  const Color pixel = sum / static_cast<float>(sampler_.count());
  if (isFinite(pixel)) return pixel;
  ++rays.nonFinite;  // finite samples that summed past the float range
  return Color(0.0f);
}

RayDifferential TileRenderer::sampleDifferential(const Ray& ray, int sample,
                                                 const Vec2& offset) const {
  RayDifferential differential = camera_.pixelDifferential(ray);
  // Each of several samples stands for its stratum (a single jittered one, the viewer's, for
  // the pixel about it: its passes move it).
  if (sampler_.count() > 1) {
    differential.cell = sampler_.stratumSize();
    differential.toCellCentre = sampler_.stratumCentre(sample) - offset;
  }
  return differential;
}

RayCone TileRenderer::sampleCone(const Ray& ray) const {
  RayCone cone = camera_.pixelCone(ray);
  // Each of several samples stands for its stratum, as its differential does.
  if (sampler_.count() > 1) {
    const Vec2 cell = sampler_.stratumSize();
    const float scale = std::max(cell.x, cell.y);
    cone.width *= scale;
    cone.spread *= scale;
  }
  return cone;
}

Color TileRenderer::renderPixel(int x, int y, RayCounters& rays) const {
  Pcg32 rng = Pcg32::forKey(seed_, static_cast<uint64_t>(x), static_cast<uint64_t>(y));
  Color sum(0.0f);
  for (int i = 0; i < sampler_.count(); ++i) {
    const Vec2 offset = sampler_.offset(i, rng);
    const Ray ray =
        camera_.generateRay(static_cast<float>(x) + offset.x, static_cast<float>(y) + offset.y);
    Color sample;
    if (debugView_ != DebugView::Image) {
      sample = debugColor(scene_, ray, debugView_, rays);
    } else {
      ++rays.primary;
      const RayDifferential differential =
          integrator_.usesDifferentials() ? sampleDifferential(ray, i, offset) : RayDifferential{};
      sample = integrator_.radiance(ray, 0, Color(1.0f), rays, differential,
                                    integrator_.usesCones() ? sampleCone(ray) : RayCone{});
    }
    addSample(sample, sum, rays);
  }
  return pixelValue(sum, rays);
}

void TileRenderer::renderBlock(int x, int y, int columns, int rows, Color* out, int outStride,
                               RayCounters& rays) const {
  constexpr int kSize = Scene::kPacketSize;
  const int count = columns * rows;
  // Each pixel keeps its own random stream, so its samples are the ones renderPixel() draws.
  std::optional<Pcg32> rng[kSize];
  Color sum[kSize];
  for (int k = 0; k < count; ++k) {
    rng[k].emplace(Pcg32::forKey(seed_, static_cast<uint64_t>(x + k % columns),
                                 static_cast<uint64_t>(y + k / columns)));
    sum[k] = Color(0.0f);
  }
  for (int i = 0; i < sampler_.count(); ++i) {
    // The image-plane points, then the rays four at a time as vector lanes, each stored whole
    // in its place (Camera::generateRays).
    alignas(16) float pointX[kSize], pointY[kSize];
    Vec2 offsets[kSize];
    for (int k = 0; k < count; ++k) {
      offsets[k] = sampler_.offset(i, *rng[k]);
      pointX[k] = static_cast<float>(x + k % columns) + offsets[k].x;
      pointY[k] = static_cast<float>(y + k / columns) + offsets[k].y;
    }
    ScratchArray<Ray, kSize> packet;
    camera_.generateRays(pointX, pointY, count, packet.data());
    rays.primary += static_cast<uint64_t>(count);
    // The cones renderPixel() gives the same samples, where the integrator uses them.
    RayCone cones[kSize];
    const bool withCones = integrator_.usesCones();
    if (withCones) {
      for (int k = 0; k < count; ++k) cones[k] = sampleCone(packet[k]);
    }
    Color samples[kSize];
    integrator_.radiance8(packet.data(), count, samples, rays, withCones ? cones : nullptr);
    for (int k = 0; k < count; ++k) addSample(samples[k], sum[k], rays);
  }
  for (int k = 0; k < count; ++k) {
    out[(k / columns) * outStride + k % columns] = pixelValue(sum[k], rays);
  }
}

TileResult TileRenderer::Kernels::render(const TileRenderer& r, uint32_t tileIndex,
                                         const TileRect& rect, const std::atomic<bool>* cancel,
                                         const std::atomic<bool>* frameEnded) {
  const auto start = SteadyClock::now();
  const auto stopped = [cancel, frameEnded] {
    return (cancel && cancel->load(std::memory_order_relaxed)) ||
           (frameEnded && frameEnded->load(std::memory_order_relaxed));
  };
  TileResult result;
  result.tileIndex = tileIndex;
  result.rect = rect;
  result.pixels.resize(static_cast<size_t>(rect.pixelCount()));
  const bool packets = r.cameraRays_ == CameraRays::Packets && r.debugView_ == DebugView::Image &&
                       !r.integrator_.causticsUseFootprint();
  if (packets) {
    // 4 × 2 pixel blocks, so a packet's directions stay close (RayPacket8); a tile's last
    // columns or row take narrower or shorter blocks.
    constexpr int kBlockWidth = 4, kBlockHeight = Scene::kPacketSize / kBlockWidth;
    for (int y = rect.y; y < rect.y + rect.height; y += kBlockHeight) {
      if (stopped()) break;
      const int rows = std::min(kBlockHeight, rect.y + rect.height - y);
      for (int x = rect.x; x < rect.x + rect.width; x += kBlockWidth) {
        const int columns = std::min(kBlockWidth, rect.x + rect.width - x);
        Color* out = &result.pixels[static_cast<size_t>(y - rect.y) * rect.width + (x - rect.x)];
        r.renderBlock(x, y, columns, rows, out, rect.width, result.rays);
      }
    }
  } else {
    size_t i = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
      if (stopped()) break;
      for (int x = rect.x; x < rect.x + rect.width; ++x) {
        result.pixels[i++] = r.renderPixel(x, y, result.rays);
      }
    }
  }
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace prism
