// Targets.h: a frame slot's render targets: the float colour image (and its multisampled
// twin), depth, the AOV attachments (eye normal + depth bits, draw + primitive ids and, when
// asked for, the surface plane: texture coordinates and range), the
// single-sampled AOV pass that multisampling needs, and the host-visible readback buffers.
// The planes the host reads (colour, the AOVs) are read in place where the device allows it:
// linear images in host-visible memory, with no readback buffer (gpu/ReadbackPath.h).
// Made for a TargetDesc, kept while the next frame asks for the same size and kind.
#pragma once

#include "gpu/Context.h"
#include "gpu/DrawList.h"
#include "gpu/Resources.h"

#include <vector>

namespace lantern::gpu {

inline constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kNormalDepthFormat = VK_FORMAT_R32G32B32A32_UINT;
inline constexpr VkFormat kIdFormat = VK_FORMAT_R32G32_UINT;
inline constexpr VkFormat kSurfaceFormat = VK_FORMAT_R32G32B32A32_UINT;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
/// Weighted transparency's sums and revealage (float, not the paper's half floats: no sum of
/// weights overflows them; formats every device can also read as storage images).
inline constexpr VkFormat kWeightedAccumFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kWeightedRevealFormat = VK_FORMAT_R32_SFLOAT;

struct Target {
    std::uint32_t width = 0, height = 0, samples = 0;
    bool aov = false;
    bool surface = false;  ///< the surface plane (uv, range) exists: only when asked for
    Image color, colorMsaa, depth, normalDepth, ids, surfaceUvRange;
    Image aovColor, aovDepth;  ///< the single-sampled AOV pass, with MSAA
    /// The staging buffers of the planes read back through a copy (empty for a plane read in
    /// place, whose image is mapped: Image::mapped).
    Buffer readColor, readNormalDepth, readIds, readSurface;

    bool multisampled() const { return samples > 1; }
    /// With MSAA the AOVs are drawn in a second, single-sampled pass: integer attachments
    /// cannot be multisampled on every device (lavapipe), and an AOV is one value per pixel.
    bool separateAovPass() const { return aov && samples > 1; }
};

/// (Re)makes `target` for `desc` unless it already matches. `inPlace`: planes may be read in
/// place where the device allows it (false: every plane staged, as tests compare).
Result<void> ensureTarget(Context& ctx, Target& target, const TargetDesc& desc,
                          bool inPlace = true);

/// Refuses what a device cannot make, before anything is allocated: an empty or too large
/// image, an unsupported sample count, AOVs without primitive ids, more memory than the
/// device has for `slots` frame slots.
Result<void> checkTarget(const Context& ctx, const TargetDesc& desc, std::uint32_t slots);

/// The colour attachment formats of a pass with `attachments` of them, in the order of the
/// fragment outputs: the colour alone (1), or with the AOV planes, the surface plane last (3
/// or LANTERN_OUT_COUNT_AOV).
std::vector<VkFormat> passColorFormats(std::uint32_t attachments);

} // namespace lantern::gpu
