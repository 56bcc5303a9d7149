// A texture's mip chain, made on the host: each level the area-weighted average of the level
// before it, sRGB colour averaged in linear light (as a Vulkan linear blit of an sRGB image
// filters). No Vulkan here; gpu/SceneTextures.cpp uploads the levels.
//
// Why on the host: a device's blit is not free everywhere. On lavapipe vkCmdBlitImage runs
// Mesa's internal blit shaders, which its shader cache does not keep, so every process paid
// their compilation (about 0.2 s for a textured model, docs/performance.md). The host's chain
// is the same on every device, so a textured picture does not depend on the driver's filter.
#pragma once

#include <cstdint>

namespace lantern::gpu {

/// Levels in a full chain for a width x height image: floor(log2(max(width, height))) + 1
/// (1 for 1x1). Width and height are at least 1.
std::uint32_t mipLevelCount(int width, int height);

/// The size of level `level` of a width x height image: each side halved, rounded down, at
/// least 1 (Vulkan's rule).
int mipExtent(int extent, std::uint32_t level);

/// One level from the one before it (RGBA8, rows packed): `dst` is dstWidth x dstHeight with
/// dstWidth = max(srcWidth / 2, 1) and the same for the height. Each destination texel covers
/// srcWidth / dstWidth by srcHeight / dstHeight source texels (2 x 2 for even sides, 1 for a
/// side of 1, and about 2 + 1/dst, three texels partly, for an odd side) and is their average
/// weighted by how much of each it covers. With `srgb` the colour channels are decoded to
/// linear light before averaging and encoded after (rounded to the nearest code); alpha is
/// always linear.
void downsampleRgba8(const std::uint8_t* src, int srcWidth, int srcHeight, std::uint8_t* dst,
                     int dstWidth, int dstHeight, bool srgb);

} // namespace lantern::gpu
