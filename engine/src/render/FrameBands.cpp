// Rendering a picture in horizontal bands (render::renderBands): the same frame submitted once
// per band with the band's rows as the target, so a large picture needs only a band's
// attachments, and a band is read while the next renders.
#include "render/FrameRender.h"

#include <algorithm>
#include <chrono>
#include <deque>

namespace lantern::render {

int autoBandRows(int width, int height, double vertices) {
    const double pixels = double(width) * double(height);
    if (pixels < double(1 << 20)) return height;
    const int rows = std::max(16, int((std::size_t(4) << 20) / (std::size_t(width) * 16)));
    if (rows >= height) return height;
    const int bands = (height + rows - 1) / rows;
    return double(bands - 1) * vertices <= pixels / 4.0 ? rows : height;
}

namespace {

// The vertices the list's draws process (indices where a primitive has them).
double drawnVertices(const Scene& scene, const gpu::DrawList& list) {
    double vertices = 0.0;
    for (const gpu::ViewCommands& v : list.views)
        for (const gpu::DrawCommand& d : v.draws) {
            const Primitive& p = scene.meshes[d.mesh].primitives[d.primitive];
            vertices += double(d.instanceCount) *
                        double(p.indices.empty() ? p.positions.size() : p.indices.size());
        }
    return vertices;
}

} // namespace

Result<void> renderBands(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                         const Scene& sceneData, const RenderOptions& options, double time,
                         int rows, FrameStats& stats, const BandSink& sink) {
    const auto t0 = std::chrono::steady_clock::now();
    stats = FrameStats{};
    auto planned = planFrame(sceneData, options, time);
    if (!planned) return std::move(planned).error();
    gpu::DrawList& list = planned->list;
    stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const int height = int(list.target.height);
    if (rows <= 0) rows = autoBandRows(int(list.target.width), height, drawnVertices(sceneData, list));
    rows = std::min(rows, height);
    list.pictureHeight = std::uint32_t(height);
    const std::size_t pipelinesBefore = device.pipelineCount();
    LANTERN_TRY(device.drain());
    std::deque<std::pair<std::uint32_t, int>> inFlight;  // (slot, first row), oldest first
    auto fail = [&](Error e) -> Result<void> {
        (void)device.drain();
        return e;
    };
    for (int next = 0; next < height || !inFlight.empty();) {
        while (next < height && inFlight.size() < device.slotCount()) {
            list.bandTop = std::uint32_t(next);
            list.target.height = std::uint32_t(std::min(rows, height - next));
            auto slot = device.submit(list, scene);
            if (!slot) return fail(std::move(slot).error());
            inFlight.emplace_back(*slot, next);
            next += rows;
        }
        const auto [slot, top] = inFlight.front();
        inFlight.pop_front();
        auto band = device.collect(slot, {}, /*inPlace=*/true);
        if (!band) return fail(std::move(band).error());
        stats.draws += band->draws;
        stats.clusterTriangles += band->clusterTriangles;
        stats.clusterTrianglesDrawn += band->clusterTrianglesDrawn;
        if (band->gpuMs >= 0.0) stats.gpuMs = std::max(stats.gpuMs, 0.0) + band->gpuMs;
        if (band->nonFinite > 0) {
            LANTERN_TRY(device.drain());
            stats.nonFinite = band->nonFinite;
            band->nonFiniteY += band->nonFiniteY >= 0 ? top : 0;
            return nonFiniteFrame(device, scene, sceneData, options, time, *band);
        }
        if (auto sunk = sink(*band, top); !sunk) return fail(std::move(sunk).error());
    }
    stats.pipelinesCreated = device.pipelineCount() - pipelinesBefore;
    return {};
}

} // namespace lantern::render
