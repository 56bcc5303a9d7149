// Render targets of a frame slot, and the checks that refuse a target before allocating it.
#include "gpu/Targets.h"

#include "gpu/ReadbackPath.h"

#include <algorithm>
#include <cmath>

namespace lantern::gpu {
namespace {

std::string sizeText(const TargetDesc& d) {
    return std::to_string(d.width) + "x" + std::to_string(d.height);
}

// Bytes one frame slot needs for `d`: colour, readback and depth, the multisampled colour, and
// the AOV attachments with their readback and the separate AOV pass.
double slotBytes(const TargetDesc& d) {
    const double pixels = double(d.width) * double(d.height);
    const double samples = double(d.samples);
    double perPixel = 16 + 16 + 4 * samples;
    if (d.samples > 1) perPixel += 16.0 * samples;
    if (d.aovs.any()) perPixel += (16 + 8) * 2.0 + (d.samples > 1 ? 16 + 4 : 0);
    if (d.aovs.anySurface()) perPixel += 16 * 2.0;
    return pixels * perPixel;
}

struct TargetMaker {
    Context& ctx;
    std::uint32_t width, height;
    bool inPlace;  ///< planes may be read in place

    Result<void> image(Image& img, VkFormat format, std::uint32_t samples, VkImageUsageFlags usage,
                       VkImageAspectFlags aspect, const char* name) const {
        ImageDesc d;
        d.format = format;
        d.width = width;
        d.height = height;
        d.samples = VkSampleCountFlagBits(samples);
        d.usage = usage;
        d.aspect = aspect;
        d.name = name;
        auto r = createImage(ctx, d);
        if (!r) return std::move(r).error();
        img = std::move(*r);
        return {};
    }
    Result<void> readback(Buffer& b, VkDeviceSize bytesPerPixel, const char* name) const {
        auto r = createBuffer(ctx, VkDeviceSize(width) * height * bytesPerPixel,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, name);
        if (!r) return std::move(r).error();
        b = std::move(*r);
        return {};
    }
    ReadbackChoice choose(VkFormat format, VkImageUsageFlags usage, bool blended) const;
    Result<void> readable(Image& img, Buffer& staging, VkFormat format, bool blended,
                          VkDeviceSize bytesPerPixel, const char* name) const;
};

// The device's answer for `format` as a linear image of this size and usage.
ReadbackChoice TargetMaker::choose(VkFormat format, VkImageUsageFlags usage, bool blended) const {
    if (!inPlace) return {false, "staged: reading in place switched off (LANTERN_TEST_READBACK=staged)"};
    VkFormatProperties fp{};
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), format, &fp);
    LinearSupport linear;
    linear.features = fp.linearTilingFeatures;
    VkImageFormatProperties ip{};
    linear.imageSupported =
        vkGetPhysicalDeviceImageFormatProperties(ctx.physicalDevice(), format, VK_IMAGE_TYPE_2D,
                                                 VK_IMAGE_TILING_LINEAR, usage, 0,
                                                 &ip) == VK_SUCCESS;
    linear.maxExtent = ip.maxExtent;
    return chooseReadback(linear, inPlaceFeatures(blended), ctx.memoryProperties(), ~0u, width,
                          height);
}

// A single-sampled plane that the host reads: rendered into a linear image it reads in place
// where the device allows it (gpu/ReadbackPath.h), else an optimal image copied into `staging`.
Result<void> TargetMaker::readable(Image& img, Buffer& staging, VkFormat format, bool blended,
                                   VkDeviceSize bytesPerPixel, const char* name) const {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ReadbackChoice choice = choose(format, usage, blended);
    if (choice.inPlace) {
        ImageDesc d;
        d.format = format;
        d.width = width;
        d.height = height;
        d.usage = usage;
        d.name = name;
        d.hostReadable = true;
        auto r = createImage(ctx, d);
        if (r) {
            img = std::move(*r);
        } else if (r.error().code == ErrorCode::Unsupported) {
            // The image's own memory types ruled out every host-readable one.
            choice = {false, "staged: " + r.error().message};
        } else {
            return std::move(r).error();
        }
    }
    ctx.log(LogLevel::Debug,
            std::string(name) + " " + std::to_string(width) + "x" + std::to_string(height) +
                " read back " + choice.why +
                (choice.inPlace ? ", rows " + std::to_string(img.rowPitch) + " bytes apart" : ""));
    if (choice.inPlace) return {};
    LANTERN_TRY(image(img, format, 1, usage, VK_IMAGE_ASPECT_COLOR_BIT, name));
    return readback(staging, bytesPerPixel, (std::string(name) + " readback").c_str());
}

// Points and lines wider than a pixel need a device feature, and the size its range.
Result<void> checkPointsAndLines(const Context& ctx, const TargetDesc& d) {
    const auto& lim = ctx.properties().limits;
    auto check = [](float value, bool feature, const float range[2], const char* what,
                    const char* featureName, const char* option) -> Result<void> {
        if (value == 1.0f) return {};
        if (!feature)
            return makeError(ErrorCode::Unsupported,
                             std::string("the device lacks the ") + featureName +
                                 " feature: " + what + " must be 1 pixel",
                             option);
        if (value < range[0] || value > range[1])
            return makeError(ErrorCode::Unsupported,
                             std::string(what) + " " + std::to_string(value) +
                                 " is outside the device's range [" + std::to_string(range[0]) +
                                 ", " + std::to_string(range[1]) + "]",
                             option);
        return {};
    };
    LANTERN_TRY(check(d.pointSize, ctx.capabilities().largePoints, lim.pointSizeRange,
                      "the point size", "largePoints", "--point-size"));
    return check(d.lineWidth, ctx.capabilities().wideLines, lim.lineWidthRange, "the line width",
                 "wideLines", "--line-width");
}

} // namespace

std::vector<VkFormat> passColorFormats(std::uint32_t attachments) {
    std::vector<VkFormat> f(attachments, kColorFormat);
    if (attachments > LANTERN_OUT_NORMAL_DEPTH) f[LANTERN_OUT_NORMAL_DEPTH] = kNormalDepthFormat;
    if (attachments > LANTERN_OUT_ID) f[LANTERN_OUT_ID] = kIdFormat;
    if (attachments > LANTERN_OUT_SURFACE) f[LANTERN_OUT_SURFACE] = kSurfaceFormat;
    return f;
}

Result<void> checkTarget(const Context& ctx, const TargetDesc& d, std::uint32_t slots) {
    const auto& lim = ctx.properties().limits;
    if (d.width < 1 || d.height < 1)
        return makeError(ErrorCode::InvalidInput, "image size " + sizeText(d) + " is empty",
                         "--width/--height");
    if (d.width > lim.maxImageDimension2D || d.height > lim.maxImageDimension2D)
        return makeError(ErrorCode::InvalidInput,
                         "image size " + sizeText(d) + " exceeds the device's maximum of " +
                             std::to_string(lim.maxImageDimension2D) + " pixels per side",
                         "--width/--height");
    if (d.samples != 1 && d.samples != 2 && d.samples != 4 && d.samples != 8)
        return makeError(ErrorCode::InvalidInput,
                         "sample count " + std::to_string(d.samples) + " is not 1, 2, 4 or 8",
                         "--msaa");
    if (!(ctx.capabilities().colorDepthSampleCounts & d.samples))
        return makeError(ErrorCode::Unsupported,
                         "the device does not support " + std::to_string(d.samples) +
                             " samples per pixel for float colour and depth",
                         "--msaa");
    if (d.aovs.any() && !ctx.capabilities().primitiveIdInFragment)
        return makeError(ErrorCode::Unsupported,
                         "the device lacks the geometryShader feature that the AOV shaders "
                         "need (gl_PrimitiveID in the fragment stage)",
                         "--aov");
    LANTERN_TRY(checkPointsAndLines(ctx, d));
    const double bytes = slotBytes(d) * double(slots);
    const VkDeviceSize heap = ctx.largestDeviceLocalHeap();
    if (heap > 0 && bytes > double(heap) * 0.9)
        return makeError(ErrorCode::OutOfMemory,
                         "a " + sizeText(d) + " image needs about " +
                             std::to_string(std::llround(bytes / 1048576.0)) +
                             " MiB of device memory; the device has " +
                             std::to_string(heap / 1048576) + " MiB",
                         "--width/--height");
    return {};
}

Result<void> ensureTarget(Context& ctx, Target& t, const TargetDesc& d, bool inPlace) {
    const bool aov = d.aovs.any(), surface = d.aovs.anySurface();
    if (t.width == d.width && t.height == d.height && t.samples == d.samples && t.aov == aov &&
        t.surface == surface)
        return {};
    t = Target{};
    const TargetMaker make{ctx, d.width, d.height, inPlace};
    const VkImageAspectFlags color = VK_IMAGE_ASPECT_COLOR_BIT;
    LANTERN_TRY(make.readable(t.color, t.readColor, kColorFormat, true, 16, "colour"));
    if (d.samples > 1)
        LANTERN_TRY(make.image(t.colorMsaa, kColorFormat, d.samples,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, color, "colour msaa"));
    LANTERN_TRY(make.image(t.depth, kDepthFormat, d.samples,
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                           "depth"));
    if (aov) {
        LANTERN_TRY(make.readable(t.normalDepth, t.readNormalDepth, kNormalDepthFormat, false, 16,
                                  "aov normal+depth"));
        LANTERN_TRY(make.readable(t.ids, t.readIds, kIdFormat, false, 8, "aov ids"));
        if (surface)
            LANTERN_TRY(make.readable(t.surfaceUvRange, t.readSurface, kSurfaceFormat, false, 16,
                                      "aov uv+range"));
        if (d.samples > 1) {
            // The single-sampled AOV pass draws into these (its colour output is discarded).
            LANTERN_TRY(make.image(t.aovColor, kColorFormat, 1,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, color, "aov pass colour"));
            LANTERN_TRY(make.image(t.aovDepth, kDepthFormat, 1,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT, "aov pass depth"));
        }
    }
    t.width = d.width;
    t.height = d.height;
    t.samples = d.samples;
    t.aov = aov;
    t.surface = surface;
    return {};
}

} // namespace lantern::gpu
