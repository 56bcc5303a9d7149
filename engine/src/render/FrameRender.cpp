// Rendering a frame synchronously on a gpu::Device, and the explain and probe services built
// on it.
#include "render/FrameRender.h"

#include "reference/PixelReference.h"
#include "render/AovPlanes.h"
#include "render/Cryptomatte.h"
#include "render/DrawLists.h"
#include "render/Variants.h"

#include "lantern_shared.h"

#include <chrono>
#include <set>
#include <sstream>

namespace lantern::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

Result<void> checkShadowOptions(const ShadowOptions& s) {
    if (s.resolution < 16 || s.resolution > 16384)
        return makeError(ErrorCode::InvalidInput,
                         "shadow map resolution " + std::to_string(s.resolution) +
                             " is not in [16, 16384]",
                         "--shadow-resolution");
    if (s.kernel < 1 || s.kernel > 9 || s.kernel % 2 == 0)
        return makeError(ErrorCode::InvalidInput,
                         "PCF kernel " + std::to_string(s.kernel) + " is not odd in [1, 9]",
                         "--shadow-kernel");
    if (!(s.slopeBias >= 0.0 && s.slopeBias <= 1e3))
        return makeError(ErrorCode::InvalidInput, "the shadow slope bias is not in [0, 1000]",
                         "--shadow-bias");
    if (!(s.normalOffset >= 0.0 && s.normalOffset <= 1e3))
        return makeError(ErrorCode::InvalidInput, "the shadow normal offset is not in [0, 1000]",
                         "--shadow-normal-offset");
    if (s.cascades < 1 || s.cascades > LANTERN_MAX_CASCADES)
        return makeError(ErrorCode::InvalidInput,
                         std::to_string(s.cascades) + " shadow cascades is not in [1, " +
                             std::to_string(LANTERN_MAX_CASCADES) + "]",
                         "--shadow-cascades");
    if (!(s.lightRadius >= 0.0 && s.lightRadius <= 1e30))
        return makeError(ErrorCode::InvalidInput, "the light radius is not in [0, 1e30]",
                         "--shadow-light-radius");
    if (!(s.sunRadius >= 0.0 && s.sunRadius <= 45.0))
        return makeError(ErrorCode::InvalidInput, "the sun's angular radius is not in [0, 45] degrees",
                         "--shadow-sun-radius");
    return {};
}

} // namespace

Result<void> checkOptions(const gpu::Device& device, const RenderOptions& o) {
    LANTERN_TRY(checkShadowOptions(o.shadows));
    if (o.normals && !(o.normalLength >= 0.0 && o.normalLength < 1e300))
        return makeError(ErrorCode::InvalidInput, "the normal length must be finite and >= 0",
                         "options.normalLength");
    if (!(o.pointSize >= 1.0 && o.pointSize <= 255.0))
        return makeError(ErrorCode::InvalidInput,
                         "point size " + std::to_string(o.pointSize) + " is not in [1, 255]",
                         "--point-size");
    if (!(o.lineWidth >= 1.0 && o.lineWidth <= 255.0))
        return makeError(ErrorCode::InvalidInput,
                         "line width " + std::to_string(o.lineWidth) + " is not in [1, 255]",
                         "--line-width");
    if (!(o.lodError >= 0.0 && o.lodError <= 1e6))
        return makeError(ErrorCode::InvalidInput,
                         "level-of-detail error " + std::to_string(o.lodError) +
                             " pixels is not in [0, 1e6]",
                         "--lod-error");
    // Signed values first: the device's check reads sizes and sample counts as unsigned.
    if (o.width < 1 || o.height < 1)
        return makeError(ErrorCode::InvalidInput,
                         "image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " is empty",
                         "--width/--height");
    if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8)
        return makeError(ErrorCode::InvalidInput,
                         "sample count " + std::to_string(o.msaa) + " is not 1, 2, 4 or 8", "--msaa");
    if (o.unlitExact && o.msaa != 1)
        return makeError(ErrorCode::InvalidInput,
                         "exact colours need one sample per pixel (anti-aliasing blends them): "
                         "use --msaa 1 with --unlit-exact",
                         "--unlit-exact");
    gpu::Overlays overlays;
    overlays.wireframe = o.wireframe;
    overlays.normals = o.normals;
    return device.checkTarget(targetFor(o), overlays);
}

Result<PlannedFrame> planFrame(const Scene& scene, const RenderOptions& options, double time) {
    auto f = frame::buildFrame(scene, options, time);
    if (!f) return std::move(f).error();
    PlannedFrame p;
    p.list = buildDrawList(scene, *f, options);
    p.frame = std::move(*f);
    return p;
}

Result<RenderedFrame> renderFrame(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                                  const Scene& sceneData, const RenderOptions& options, double time,
                                  FrameStats& stats, const FrameEdits& edits, Image storage,
                                  bool inPlace) {
    const auto t0 = Clock::now();
    auto f = frame::buildFrame(sceneData, options, time);
    if (!f) return std::move(f).error();
    if (edits.frame) edits.frame(*f);
    gpu::DrawList list = buildDrawList(sceneData, *f, options);
    if (edits.list) edits.list(list);
    const std::size_t pipelinesBefore = device.pipelineCount();
    // Drain any slot still in flight from a sequence before reusing it.
    if (device.busy(device.nextSlot())) {
        auto drained = device.collect(device.nextSlot());
        if (!drained) return std::move(drained).error();
    }
    auto slot = device.submit(list, scene);
    if (!slot) return std::move(slot).error();
    stats = FrameStats{};
    stats.cpuMs = msSince(t0);
    const auto t1 = Clock::now();
    auto readback = device.collect(*slot, std::move(storage), inPlace);
    if (!readback) return std::move(readback).error();
    // Exact transparency's lists held fewer fragments than the frame made: the device now
    // sizes them for it (gpu/Transparency.h), and the frame is rendered again, once. (A device
    // that cannot hold more logged a warning instead.)
    if (readback->listFragments > readback->listCapacity && readback->listsGrow) {
        auto again = device.submit(list, scene);
        if (!again) return std::move(again).error();
        auto retried = device.collect(*again, std::move(readback->image), inPlace);
        if (!retried) return std::move(retried).error();
        readback = std::move(retried);
    }
    resolveAovPlanes(sceneData, *f, options.aovs, *readback);
    stats.waitMs = msSince(t1);
    stats.gpuMs = readback->gpuMs;
    stats.draws = readback->draws;
    stats.clusterTriangles = readback->clusterTriangles;
    stats.clusterTrianglesDrawn = readback->clusterTrianglesDrawn;
    stats.nonFinite = readback->nonFinite;
    stats.pipelinesCreated = device.pipelineCount() - pipelinesBefore;
    return RenderedFrame{std::move(*f), std::move(*readback)};
}

Result<std::vector<CryptomatteLayer>> renderCryptomatte(
    gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene, const Scene& sceneData,
    const RenderOptions& options, double time) {
    const RenderOptions fineOptions = cryptomatteRenderOptions(options);
    auto failed = [&](Error e) {
        e.message = "the Cryptomatte id render (" +
                    std::to_string(options.aovs.cryptomatteSamples) + "x the size) failed: " +
                    e.message;
        return e;
    };
    if (auto ok = checkOptions(device, fineOptions); !ok) return failed(ok.error());
    FrameStats stats;
    auto fine = renderFrame(device, scene, sceneData, fineOptions, time, stats);
    if (!fine) return failed(fine.error());
    if (fine->readback.nonFinite > 0)
        return failed(nonFiniteFrame(device, scene, sceneData, fineOptions, time, fine->readback));
    return cryptomatteLayers(sceneData, options.aovs, options.width, options.height,
                             fine->readback.image);
}

Result<FeatureReport> explain(const Scene& scene, const RenderOptions& options, double time) {
    LANTERN_TRY(scene.validate());
    auto f = frame::buildFrame(scene, options, time);
    if (!f) return std::move(f).error();
    FeatureReport report;
    report.features = frame::describeFeatures(*f, options);
    std::set<std::string> seen;
    const gpu::DrawList list = buildDrawList(scene, *f, options);
    for (const gpu::ViewCommands& v : list.views)
        for (const gpu::DrawCommand& d : v.draws) {
            const std::string line = describe(d.pipeline);
            if (seen.insert(line).second) report.variants.push_back(line);
        }
    // What the shadow passes draw: each map's casters, of those every map would draw unculled.
    if (list.shadows.any()) {
        std::size_t drawn = 0, casters = 0;
        for (const gpu::DrawCommand& d : list.views[0].draws)
            casters += !d.pipeline.blend && d.pipeline.topology == Topology::Triangles;
        for (const std::vector<std::uint32_t>& p : list.shadows.passDraws) drawn += p.size();
        report.features.push_back("shadow-maps:" + std::to_string(list.shadows.passes.size()) +
                                  " (caster draws " + std::to_string(drawn) + " of " +
                                  std::to_string(casters * list.shadows.passes.size()) + ")");
    }
    return report;
}

Result<ProbeReport> probe(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                          const Scene& sceneData, const RenderOptions& options, double time, int x,
                          int y, FrameStats& stats) {
    if (x < 0 || y < 0 || x >= options.width || y >= options.height)
        return makeError(ErrorCode::InvalidInput,
                         "pixel " + std::to_string(x) + "," + std::to_string(y) +
                             " is outside the " + std::to_string(options.width) + "x" +
                             std::to_string(options.height) + " image",
                         "--probe");
    // One sample per pixel: the probe explains the surface at the pixel centre.
    RenderOptions single = options;
    single.msaa = 1;
    // The primitive plane reads the draw ids back, so every instance is drawn on its own
    // (render/DrawLists.cpp) and its id names its node.
    single.aovs.depth = single.aovs.normal = single.aovs.primitive = true;
    LANTERN_TRY(checkOptions(device, single));
    auto f = renderFrame(device, scene, sceneData, single, time, stats);
    if (!f) return std::move(f).error();
    return ref::probePixel(sceneData, f->frame, f->readback.image, f->readback.ids, x, y);
}

Error nonFiniteFrame(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                     const Scene& sceneData, const RenderOptions& options, double time,
                     const gpu::FrameReadback& readback, int frameNumber) {
    std::ostringstream m;
    if (frameNumber >= 0) m << "frame " << frameNumber << " (time " << time << " s)";
    else m << "the frame at time " << time << " s";
    m << " holds " << readback.nonFinite
      << " non-finite values (NaN or Inf), the first at pixel (" << readback.nonFiniteX << ", "
      << readback.nonFiniteY << ")";
    FrameStats stats;
    auto p = readback.nonFiniteX < 0 ? Result<ProbeReport>(ProbeReport{})
                                     : probe(device, scene, sceneData, options, time,
                                             readback.nonFiniteX, readback.nonFiniteY, stats);
    if (p && p->hit) {
        m << " on nodes[" << p->node << "]";
        if (!p->nodeName.empty()) m << " \"" << p->nodeName << "\"";
        m << " (meshes[" << p->mesh << "].primitives[" << p->primitive << "])";
    } else if (p) {
        m << " where no object is drawn";
    }
    m << "; nothing was written for it (a renderer bug: please report it with the scene)";
    return makeError(ErrorCode::Internal, m.str());
}

} // namespace lantern::render
