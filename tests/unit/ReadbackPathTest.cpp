// The choice between reading a render target in place and staging it through a buffer, on
// made-up device properties: a CPU device like lavapipe (all memory is host memory), discrete
// GPUs with and without a resizable BAR, integrated GPUs, and formats or sizes that a linear
// image cannot take (gpu/ReadbackPath.h).
#include "gpu/ReadbackPath.h"

#include <gtest/gtest.h>

#include <bit>
#include <initializer_list>
#include <limits>
#include <vector>

namespace {

using namespace lantern::gpu;

constexpr VkMemoryPropertyFlags DL = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags HV = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
constexpr VkMemoryPropertyFlags HC = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags CACHED = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

// Memory types, each on its own heap (the heaps do not enter the choice).
VkPhysicalDeviceMemoryProperties memoryOf(std::initializer_list<VkMemoryPropertyFlags> types) {
    VkPhysicalDeviceMemoryProperties m{};
    for (VkMemoryPropertyFlags f : types) {
        m.memoryTypes[m.memoryTypeCount] = {f, m.memoryTypeCount};
        m.memoryHeaps[m.memoryHeapCount++] = {VkDeviceSize(1) << 32,
                                              (f & DL) ? VkMemoryHeapFlags(VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) : 0u};
        ++m.memoryTypeCount;
    }
    return m;
}

// lavapipe's answer for R32G32B32A32_SFLOAT with linear tiling (vulkaninfo --show-formats).
LinearSupport lavapipeFloat() {
    LinearSupport s;
    s.features = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                 VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                 VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                 VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                 VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    s.imageSupported = true;
    s.maxExtent = {16384, 16384, 1};
    return s;
}

ReadbackChoice colour(const LinearSupport& s, const VkPhysicalDeviceMemoryProperties& m,
                      std::uint32_t w = 1920, std::uint32_t h = 1080) {
    return chooseReadback(s, inPlaceFeatures(true), m, ~0u, w, h);
}

TEST(ReadbackPath, ACpuDeviceReadsInPlace) {
    // lavapipe: one heap, one type that is everything.
    const auto lavapipe = memoryOf({DL | HV | HC | CACHED});
    EXPECT_EQ(inPlaceMemoryType(lavapipe, ~0u), 0);
    const ReadbackChoice c = colour(lavapipeFloat(), lavapipe);
    EXPECT_TRUE(c.inPlace) << c.why;
    EXPECT_NE(c.why.find("in place"), std::string::npos);
}

TEST(ReadbackPath, ADiscreteGpuStages) {
    // VRAM, system memory (coherent and cached), and the 256 MiB BAR window.
    const auto discrete = memoryOf({DL, HV | HC, HV | HC | CACHED, DL | HV | HC});
    EXPECT_EQ(inPlaceMemoryType(discrete, ~0u), -1);
    EXPECT_FALSE(colour(lavapipeFloat(), discrete).inPlace);
    // Even with a cached window onto VRAM, device memory the host cannot map is the faster
    // place to render: the copy is cheaper than rendering across the bus.
    const auto cachedBar = memoryOf({DL, DL | HV | HC | CACHED, HV | HC | CACHED});
    EXPECT_EQ(inPlaceMemoryType(cachedBar, ~0u), -1);
}

TEST(ReadbackPath, AResizableBarWithoutHostCacheStages) {
    // All VRAM mappable but write-combined: the host would read it at bus speed, uncached.
    const auto rebar = memoryOf({DL | HV | HC, HV | HC, HV | HC | CACHED});
    EXPECT_EQ(inPlaceMemoryType(rebar, ~0u), -1);
    const ReadbackChoice c = colour(lavapipeFloat(), rebar);
    EXPECT_FALSE(c.inPlace);
    EXPECT_NE(c.why.find("staged"), std::string::npos);
}

TEST(ReadbackPath, AnIntegratedGpuWithCachedSharedMemoryReadsInPlace) {
    // Shared memory offered both uncached and cached: the cached type is the one chosen.
    const auto integrated = memoryOf({DL | HV | HC, DL | HV | HC | CACHED});
    EXPECT_EQ(inPlaceMemoryType(integrated, ~0u), 1);
    EXPECT_TRUE(colour(lavapipeFloat(), integrated).inPlace);
    // The image's own memoryTypeBits may exclude the cached type.
    EXPECT_EQ(inPlaceMemoryType(integrated, 0b01u), -1);
    EXPECT_FALSE(chooseReadback(lavapipeFloat(), inPlaceFeatures(true), integrated, 0b01u, 64, 64)
                     .inPlace);
}

TEST(ReadbackPath, TheFormatsLinearFeaturesDecide) {
    const auto lavapipe = memoryOf({DL | HV | HC | CACHED});
    LinearSupport noBlend = lavapipeFloat();
    noBlend.features &= ~VkFormatFeatureFlags(VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT);
    // The colour blends (transparent draws); the integer AOV planes never do.
    EXPECT_FALSE(colour(noBlend, lavapipe).inPlace);
    EXPECT_TRUE(chooseReadback(noBlend, inPlaceFeatures(false), lavapipe, ~0u, 64, 64).inPlace);
    LinearSupport noAttachment = lavapipeFloat();
    noAttachment.features = VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    EXPECT_FALSE(chooseReadback(noAttachment, inPlaceFeatures(false), lavapipe, ~0u, 64, 64).inPlace);
    LinearSupport noBlit = lavapipeFloat();
    noBlit.features &= ~VkFormatFeatureFlags(VK_FORMAT_FEATURE_BLIT_SRC_BIT);
    EXPECT_FALSE(colour(noBlit, lavapipe).inPlace);  // a window frame blits the colour
}

TEST(ReadbackPath, TheLinearImageLimitsDecide) {
    const auto lavapipe = memoryOf({DL | HV | HC | CACHED});
    LinearSupport refused = lavapipeFloat();
    refused.imageSupported = false;
    EXPECT_FALSE(colour(refused, lavapipe).inPlace);
    LinearSupport small = lavapipeFloat();
    small.maxExtent = {4096, 4096, 1};
    EXPECT_TRUE(colour(small, lavapipe, 4096, 4096).inPlace);
    const ReadbackChoice wide = colour(small, lavapipe, 4097, 16);
    EXPECT_FALSE(wide.inPlace);
    EXPECT_NE(wide.why.find("4096x4096"), std::string::npos) << wide.why;
    EXPECT_FALSE(colour(small, lavapipe, 16, 4097).inPlace);
}

TEST(ReadbackPath, NoMemoryTypesMeansStaged) {
    EXPECT_EQ(inPlaceMemoryType(memoryOf({}), ~0u), -1);
    EXPECT_EQ(inPlaceMemoryType(memoryOf({HV | HC | CACHED}), ~0u), -1);  // no device-local type
}

// The vectorised check finds every kind of non-finite value at every position of a row (the
// blocks of 64 and the tail), and nothing in finite values of every exponent.
TEST(ReadbackPath, AnyNonFiniteFindsEveryNaNAndInfAndNothingElse) {
    const float bad[] = {std::numeric_limits<float>::infinity(),
                         -std::numeric_limits<float>::infinity(),
                         std::numeric_limits<float>::quiet_NaN(),
                         -std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::signaling_NaN(),
                         std::bit_cast<float>(0x7f800001u), std::bit_cast<float>(0xffffffffu)};
    std::vector<float> finite;
    for (std::uint32_t e = 0; e < 255; ++e)  // every finite exponent, both signs, some mantissas
        for (std::uint32_t m : {0u, 1u, 0x400000u, 0x7fffffu})
            for (std::uint32_t sign : {0u, 0x80000000u})
                finite.push_back(std::bit_cast<float>(sign | (e << 23) | m));
    finite.push_back(std::numeric_limits<float>::max());
    finite.push_back(std::numeric_limits<float>::denorm_min());
    EXPECT_FALSE(anyNonFinite(finite.data(), finite.size()));
    for (std::size_t n : {std::size_t(1), std::size_t(63), std::size_t(64), std::size_t(65),
                          std::size_t(200), finite.size()}) {
        EXPECT_FALSE(anyNonFinite(finite.data(), n)) << n;
        for (std::size_t at : {std::size_t(0), n / 2, n - 1})
            for (float b : bad) {
                std::vector<float> row(finite.begin(), finite.begin() + std::ptrdiff_t(n));
                row[at] = b;
                EXPECT_TRUE(anyNonFinite(row.data(), n)) << n << " " << at << " " << b;
            }
    }
    EXPECT_FALSE(anyNonFinite(nullptr, 0));
}

} // namespace
