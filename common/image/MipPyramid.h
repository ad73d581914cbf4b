// A mip pyramid (Williams 1983, "Pyramidal parametrics"): an image and its copies halved again
// and again down to 1x1, for filtered lookups that read the level whose texels match the
// footprint's size.
//
// Each texel of a level is the exact area average of the texels of the level below that it
// covers: a box filter. It keeps the mean of every level equal to the image's (a footprint
// covering the whole image reads its mean), never rings or goes negative about a bright spot (a
// sun in an HDR sky), and is separable and cheap to build; its softness against a wider kernel
// hardly shows once lookups blend two levels (trilinear). A side of odd length n halves to
// floor(n/2) texels, each covering n/floor(n/2) texels below, the ones it cuts weighted by the
// part covered.
#pragma once

#include <cstdint>
#include <vector>

#include "image/ImageRgb.h"
#include "image/SrgbImage.h"

namespace prism {

// The level above image: each side halved (rounded down, at least 1), box filtered.
ImageRgb halved(const ImageRgb& image);

// image (level 0) and every level above it, the last 1x1.
std::vector<ImageRgb> mipLevels(ImageRgb image);

// The same for an 8-bit sRGB image: level 0 its bytes, each level above averaged over the
// radiance of the one below and kept as the nearest sRGB bytes (packedTexels).
std::vector<SrgbTexels> srgbMipLevels(const SrgbImage& image);

// The texels of mipLevels() of a width × height image, all levels (about 4/3 of the image's).
uint64_t mipLevelsTexels(int width, int height);

}  // namespace prism
