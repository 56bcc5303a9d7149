// Reading a finished frame back: timestamps, the colour image and the AOV planes from the
// slot's host-visible buffers. The last line of defence: no NaN or Inf leaves the renderer.
#include "gpu/FrameRing.h"

#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace lantern::gpu {
namespace {

float bitsFloat(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// The shaders are written so that no non-finite value arises; any found is counted (tests
// assert zero) and replaced.
float finiteOr(float v, float replacement, std::uint64_t& nonFinite) {
    if (std::isfinite(v)) return v;
    ++nonFinite;
    return replacement;
}

#ifdef LANTERN_TESTING_HOOKS
// LANTERN_TEST_NONFINITE_PIXEL="X,Y[@N]" (tests only): the (N+1)th colour readback and every
// later one find NaN at pixel (X, Y), as a shader bug would leave it, so that the path from
// detection to the refusal can be tested without one.
void injectNonFinite(FrameReadback& r) {
    static std::atomic<long> readbacks{0};
    const long index = readbacks++;
    const char* env = std::getenv("LANTERN_TEST_NONFINITE_PIXEL");
    int x = -1, y = -1;
    long after = 0;
    if (!env || std::sscanf(env, "%d,%d@%ld", &x, &y, &after) < 2 || index < after) return;
    if (x < 0 || y < 0 || x >= r.image.width || y >= r.image.height) return;
    r.image.rgba[(std::size_t(y) * std::size_t(r.image.width) + std::size_t(x)) * 4] = NAN;
}
#endif

// Counts and zeroes NaN/Inf in the colour image, remembering the first pixel that held one.
void scrubColour(FrameReadback& r) {
    const std::size_t n = r.image.rgba.size() / 4;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t before = r.nonFinite;
        for (std::size_t c = 0; c < 4; ++c) r.image.rgba[i * 4 + c] = finiteOr(r.image.rgba[i * 4 + c], 0.0f, r.nonFinite);
        if (r.nonFinite != before && r.nonFiniteX < 0) {
            r.nonFiniteX = int(i % std::size_t(r.image.width));
            r.nonFiniteY = int(i / std::size_t(r.image.width));
        }
    }
}

void readAovs(const FrameRing::Slot& slot, std::size_t n, FrameReadback& r) {
    const auto* nd = static_cast<const std::uint32_t*>(slot.target.readNormalDepth.mapped);
    const AovSet& aovs = slot.desc.aovs;
    lantern::Image& img = r.image;
    if (aovs.depth) img.depth.resize(n);
    if (aovs.normal) img.normal.resize(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        if (aovs.normal)
            for (std::size_t c = 0; c < 3; ++c)
                img.normal[i * 3 + c] = finiteOr(bitsFloat(nd[i * 4 + c]), 0.0f, r.nonFinite);
        if (aovs.depth) img.depth[i] = finiteOr(bitsFloat(nd[i * 4 + 3]), FLT_MAX, r.nonFinite);
    }
    const auto* ids = static_cast<const std::uint32_t*>(slot.target.readIds.mapped);
    r.ids.assign(ids, ids + n * 2);
}

} // namespace

Result<FrameReadback> readBack(Context& ctx, const FrameRing::Slot& slot) {
    FrameReadback r;
    r.draws = slot.draws;
    r.flatTriangles = slot.flat.triangles;
    if (slot.queries) {
        std::uint64_t ts[2] = {0, 0};
        if (vkGetQueryPoolResults(ctx.device(), slot.queries, 0, 2, sizeof ts, ts, 8,
                                  VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
            r.gpuMs = double(ts[1] - ts[0]) * ctx.properties().limits.timestampPeriod * 1e-6;
    }
    if (!slot.readback) return r;
    const Target& t = slot.target;
    LANTERN_TRY(invalidate(ctx, t.readColor));
    const std::size_t n = std::size_t(t.width) * t.height;
    r.image.width = int(t.width);
    r.image.height = int(t.height);
    r.image.rgba.resize(n * 4);
    std::memcpy(r.image.rgba.data(), t.readColor.mapped, n * 16);
#ifdef LANTERN_TESTING_HOOKS
    injectNonFinite(r);
#endif
    scrubColour(r);
    if (t.aov) {
        LANTERN_TRY(invalidate(ctx, t.readNormalDepth));
        LANTERN_TRY(invalidate(ctx, t.readIds));
        readAovs(slot, n, r);
    }
    return r;
}

} // namespace lantern::gpu
