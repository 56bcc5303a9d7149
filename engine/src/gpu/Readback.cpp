// Reading a finished frame back: timestamps, the colour image and the AOV planes, from the
// mapped render targets themselves (read in place) or from the slot's staging buffers. The
// last line of defence: no NaN or Inf leaves the renderer.
#include "gpu/FrameRing.h"
#include "gpu/ReadbackPath.h"

#include "core/Bands.h"

#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

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

// Where the host reads one plane: the mapped image (in place, at its row pitch) or the staging
// buffer its copy filled (rows packed).
struct HostPlane {
    const char* data = nullptr;
    std::size_t rowPitch = 0;

    template <typename T> const T* row(std::uint32_t y) const {
        return reinterpret_cast<const T*>(data + std::size_t(y) * rowPitch);
    }
};

Result<HostPlane> hostPlane(Context& ctx, const Image& image, const Buffer& staging,
                            std::size_t rowBytes) {
    if (image.mapped) {
        LANTERN_TRY(invalidate(ctx, image));
        return HostPlane{static_cast<const char*>(image.mapped), std::size_t(image.rowPitch)};
    }
    LANTERN_TRY(invalidate(ctx, staging));
    return HostPlane{static_cast<const char*>(staging.mapped), rowBytes};
}

// The pixel a test poisons, or (-1, -1).
struct Poison {
    long x = -1, y = -1;
};

#ifdef LANTERN_TESTING_HOOKS
// LANTERN_TEST_NONFINITE_PIXEL="X,Y[@N]" (tests only): the (N+1)th colour readback and every
// later one find NaN at pixel (X, Y), as a shader bug would leave it, so that the path from
// detection to the refusal can be tested without one.
Poison injectedNonFinite(std::uint32_t width, std::uint32_t height) {
    static std::atomic<long> readbacks{0};
    const long index = readbacks++;
    const char* env = std::getenv("LANTERN_TEST_NONFINITE_PIXEL");
    int x = -1, y = -1;
    long after = 0;
    if (!env || std::sscanf(env, "%d,%d@%ld", &x, &y, &after) < 2 || index < after) return {};
    if (x < 0 || y < 0 || std::uint32_t(x) >= width || std::uint32_t(y) >= height) return {};
    return {x, y};
}
#endif

// The pixel a test poisons in this readback (tests only), or none.
Poison colourPoison([[maybe_unused]] std::uint32_t width, [[maybe_unused]] std::uint32_t height) {
#ifdef LANTERN_TESTING_HOOKS
    return injectedNonFinite(width, height);
#else
    return {};
#endif
}

// What a pass over rows of the colour plane found: NaN/Inf values and the first pixel.
struct Findings {
    std::uint64_t count = 0;
    int x = -1, y = -1;
};

// Counts the NaN/Inf values of row `y` of `src` (the poisoned pixel as one), remembering the
// first pixel that held one; when `row` (a copy of `src`, or `src` itself) is given, replaces
// them there by 0.
void scanRow(float* row, const float* src, std::uint32_t width, std::uint32_t y, Poison poison,
             Findings& f) {
    for (std::uint32_t x = 0; x < width; ++x) {
        std::uint64_t found = long(y) == poison.y && long(x) == poison.x ? 1 : 0;
        for (std::size_t c = 0; c < 4; ++c) {
            if (std::isfinite(src[x * 4 + c])) continue;
            ++found;
            if (row) row[x * 4 + c] = 0.0f;
        }
        if (found == 0) continue;
        if (f.x < 0) f.x = int(x), f.y = int(y);
        f.count += found;
    }
}

// Runs band(y0, y1) over the rows of a picture of `bytes`: in two halves on two threads when
// it is large and the host has the cores (the pass is bound by memory bandwidth: about 5 ms
// for a 1080p float picture on one core of the 2-core test machine, and the device has
// finished with the frame, so the cores wait), else at once. The halves' findings are merged,
// the top half's first pixel first.
template <typename Band>
Findings inBands(std::uint32_t height, std::size_t bytes, Band&& band) {
    constexpr std::size_t kSplitBytes = std::size_t(4) << 20;
    Findings top, bottom;
    inTwoBands(int(height), bytes >= kSplitBytes, [&](int y0, int y1) {
        (y0 == 0 ? top : bottom) = band(std::uint32_t(y0), std::uint32_t(y1));
    });
    top.count += bottom.count;
    if (top.x < 0) top.x = bottom.x, top.y = bottom.y;
    return top;
}

void addFindings(const Findings& f, FrameReadback& r) {
    r.nonFinite += f.count;
    if (f.count > 0 && r.nonFiniteX < 0) r.nonFiniteX = f.x, r.nonFiniteY = f.y;
}

// Whether the host must look for NaN/Inf in the colour plane: yes unless every colour of the
// frame came from a guarded draw or the clear colour and nothing tripped the guard
// (shaders/include/guard.glsl), or when a test poisons a pixel (as a shader bug that trips
// the guard would leave it).
Result<bool> hostCheckNeeded(Context& ctx, const FrameRing::Slot& slot, Poison poison) {
    if (!slot.guarded || poison.x >= 0) return true;
    LANTERN_TRY(invalidate(ctx, slot.arena));
    std::uint32_t tripped = 0;
    std::memcpy(&tripped, static_cast<const char*>(slot.arena.mapped) + slot.guardOffset, 4);
    return tripped != 0;
}

// The colour plane into r.image.rgba, each row checked while it is still in the cache (when
// `check`) and scrubbed only when it holds a NaN or Inf. An Image kept from a frame of the same
// size (Renderer::render into an Image) is overwritten in place, in two bands for a large
// picture; otherwise each row is appended (the vector is never zero-filled first).
void readColour(const HostPlane& src, std::uint32_t width, std::uint32_t height, Poison poison,
                bool check, FrameReadback& r) {
    std::vector<float>& rgba = r.image.rgba;
    const std::size_t rowFloats = std::size_t(width) * 4;
    auto copyRow = [&](float* dst, std::uint32_t y, Findings& f) {
        const float* row = src.row<float>(y);
        std::memcpy(dst, row, rowFloats * sizeof(float));
        if (check && (long(y) == poison.y || anyNonFinite(dst, rowFloats)))
            scanRow(dst, dst, width, y, poison, f);
    };
    if (rgba.size() == rowFloats * height) {
        addFindings(inBands(height, rgba.size() * sizeof(float),
                            [&](std::uint32_t y0, std::uint32_t y1) {
                                Findings f;
                                for (std::uint32_t y = y0; y < y1; ++y)
                                    copyRow(rgba.data() + std::size_t(y) * rowFloats, y, f);
                                return f;
                            }),
                    r);
        return;
    }
    rgba.clear();
    rgba.reserve(rowFloats * height);
    Findings f;
    for (std::uint32_t y = 0; y < height; ++y) {
        const float* row = src.row<float>(y);
        rgba.insert(rgba.end(), row, row + rowFloats);
        float* dst = rgba.data() + std::size_t(y) * rowFloats;
        if (check && (long(y) == poison.y || anyNonFinite(dst, rowFloats)))
            scanRow(dst, dst, width, y, poison, f);
    }
    addFindings(f, r);
}

// The colour plane where it lies (collect in place): each row checked, nothing copied or
// scrubbed (the renderer refuses such a frame, render/FrameRender.h); the first pixel that
// holds a NaN or Inf is remembered for the refusal's message.
void checkColourInPlace(const HostPlane& src, std::uint32_t width, std::uint32_t height,
                        Poison poison, FrameReadback& r) {
    const std::size_t rowFloats = std::size_t(width) * 4;
    addFindings(inBands(height, rowFloats * height * sizeof(float),
                        [&](std::uint32_t y0, std::uint32_t y1) {
                            Findings f;
                            for (std::uint32_t y = y0; y < y1; ++y) {
                                const float* row = src.row<float>(y);
                                if (long(y) == poison.y || anyNonFinite(row, rowFloats))
                                    scanRow(nullptr, row, width, y, poison, f);
                            }
                            return f;
                        }),
                r);
}

// The depth and normal planes asked for, and the ids when the frame wants them (the probe).
void readAovs(const HostPlane& nd, const HostPlane* ids, const TargetDesc& desc,
              FrameReadback& r) {
    const AovSet& aovs = desc.aovs;
    lantern::Image& img = r.image;
    const std::size_t w = desc.width;
    if (aovs.depth) img.depth.resize(w * desc.height);
    // The world normal is made from the eye normal (render/AovPlanes.h), which drops it after.
    const bool normal = aovs.normal || aovs.worldNormal;
    if (normal) img.normal.resize(w * desc.height * 3);
    for (std::uint32_t y = 0; y < desc.height; ++y) {
        const std::uint32_t* row = nd.row<std::uint32_t>(y);
        const std::size_t base = std::size_t(y) * w;
        for (std::size_t x = 0; x < w; ++x) {
            if (normal)
                for (std::size_t c = 0; c < 3; ++c)
                    img.normal[(base + x) * 3 + c] =
                        finiteOr(bitsFloat(row[x * 4 + c]), 0.0f, r.nonFinite);
            if (aovs.depth)
                img.depth[base + x] = finiteOr(bitsFloat(row[x * 4 + 3]), FLT_MAX, r.nonFinite);
        }
    }
    if (!ids) return;
    r.ids.reserve(w * desc.height * 2);
    for (std::uint32_t y = 0; y < desc.height; ++y) {
        const std::uint32_t* row = ids->row<std::uint32_t>(y);
        r.ids.insert(r.ids.end(), row, row + w * 2);
    }
}

// The surface plane: texture coordinates and range, as the frame asked for them.
void readSurface(const HostPlane& s, const TargetDesc& desc, FrameReadback& r) {
    lantern::Image& img = r.image;
    const std::size_t w = desc.width;
    if (desc.aovs.uv) img.uv.resize(w * desc.height * 2);
    if (desc.aovs.range) img.range.resize(w * desc.height);
    for (std::uint32_t y = 0; y < desc.height; ++y) {
        const std::uint32_t* row = s.row<std::uint32_t>(y);
        const std::size_t base = std::size_t(y) * w;
        for (std::size_t x = 0; x < w; ++x) {
            if (desc.aovs.uv)
                for (std::size_t c = 0; c < 2; ++c)
                    img.uv[(base + x) * 2 + c] =
                        finiteOr(bitsFloat(row[x * 4 + c]), 0.0f, r.nonFinite);
            if (desc.aovs.range)
                img.range[base + x] = finiteOr(bitsFloat(row[x * 4 + 2]), FLT_MAX, r.nonFinite);
        }
    }
}

} // namespace

Result<FrameReadback> readBack(Context& ctx, const FrameRing::Slot& slot, lantern::Image storage,
                               const HostView* view) {
    FrameReadback r;
    if (slot.readback && !view) {
        // The caller's vectors keep their capacity (Renderer::render into an Image): no
        // allocation, and for large pictures no fresh pages to fault in.
        r.image = std::move(storage);  // rgba: overwritten or cleared by readColour
        r.image.depth.clear();
        r.image.normal.clear();
        r.image.metadata.clear();
        r.image.camera.reset();
        r.image.framesPerSecond = 0.0;
    }
    r.draws = slot.draws;
    r.flatTriangles = slot.flat.triangles;
    if (slot.cull.any()) {
        LANTERN_TRY(invalidate(ctx, slot.cull.counts));
        r.clusterTriangles = slot.cull.triangles;
        std::memcpy(&r.clusterTrianglesDrawn, slot.cull.counts.mapped, sizeof(std::uint32_t));
    }
    if (slot.queries) {
        std::uint64_t ts[2] = {0, 0};
        if (vkGetQueryPoolResults(ctx.device(), slot.queries, 0, 2, sizeof ts, ts, 8,
                                  VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
            r.gpuMs = double(ts[1] - ts[0]) * ctx.properties().limits.timestampPeriod * 1e-6;
    }
    if (!slot.readback) return r;
    const Target& t = slot.target;
    auto colour = hostPlane(ctx, t.color, t.readColor, std::size_t(t.width) * 16);
    if (!colour) return std::move(colour).error();
    r.image.width = int(t.width);
    r.image.height = int(t.height);
    const Poison poison = colourPoison(t.width, t.height);
    auto check = hostCheckNeeded(ctx, slot, poison);
    if (!check) return std::move(check).error();
    r.hostChecked = *check;
    if (view) {
        r.view = *view;
        r.view.data = colour->data;
        r.view.rowPitch = colour->rowPitch;
        if (*check) checkColourInPlace(*colour, t.width, t.height, poison, r);
        return r;
    }
    readColour(*colour, t.width, t.height, poison, *check, r);
    if (t.aov) {
        auto nd = hostPlane(ctx, t.normalDepth, t.readNormalDepth, std::size_t(t.width) * 16);
        if (!nd) return std::move(nd).error();
        std::optional<HostPlane> ids, surface;
        if (slot.desc.readIds()) {
            auto plane = hostPlane(ctx, t.ids, t.readIds, std::size_t(t.width) * 8);
            if (!plane) return std::move(plane).error();
            ids = *plane;
        }
        if (t.surface) {
            auto plane = hostPlane(ctx, t.surfaceUvRange, t.readSurface, std::size_t(t.width) * 16);
            if (!plane) return std::move(plane).error();
            surface = *plane;
        }
        readAovs(*nd, ids ? &*ids : nullptr, slot.desc, r);
        if (surface) readSurface(*surface, slot.desc, r);
    }
    return r;
}

} // namespace lantern::gpu
