// Probe.h: explains pixels. A frame rendered with the id AOV names, per pixel, the draw and
// triangle the renderer drew there; PixelReference re-evaluates that pixel with the
// double-precision CPU reference (reference/Lighting.h) under the same shading rule as the
// shaders (per fragment, per vertex interpolated, per triangle centroid or provoking vertex).
// Used by Renderer::probe (--probe) and by the image tests, which compare every pixel.
#pragma once

#include "reference/Lighting.h"
#include "render/Engine.h"
#include "render/FramePlan.h"

#include <cstdint>
#include <functional>
#include <lantern/Renderer.h>
#include <utility>
#include <vector>

namespace lantern::render {

/// A frame with everything needed to explain its pixels.
struct ExplainedFrame {
    RenderOptions options; ///< as rendered (AOVs on)
    FramePlan plan;
    FrameResult frame; ///< colour, depth and normal planes, and per-pixel ids
};

/// The engine-internal door into a Renderer (a friend of it).
struct RendererAccess {
    /// A Renderer on a context (Lantern's own device or the host's).
    static Result<Renderer> create(std::shared_ptr<gpu::Context> context, const RendererDesc& desc);
    /// Renders `scene` with the depth, normal and id AOVs on. `edit` may change the plan before
    /// it is submitted (tests inject what validation refuses, e.g. a NaN, to see it reported).
    static Result<ExplainedFrame> renderExplained(Renderer& renderer, const Scene& scene,
                                                  const RenderOptions& options, double time,
                                                  const std::function<void(FramePlan&)>& edit = {});
};

/// The CPU reference of a frame's pixels. Holds references to the scene and the plan.
class PixelReference {
public:
    PixelReference(const Scene& scene, const FramePlan& plan, const RenderOptions& options);

    /// Pixel (x, y) (top-left origin) given the ids the renderer wrote there: `drawId` is the
    /// draw index + 1 (0: background), `triangle` the primitive id. `perLight` false leaves
    /// ProbeEvaluation::lights empty (faster for whole images with many lights). Fills
    /// everything but ProbeReport::pixel.
    ProbeReport explain(int x, int y, std::uint32_t drawId, std::uint32_t triangle,
                        bool perLight = true) const;

    /// The draw a global draw index names: (view, index in that view's draw list).
    const DrawItem* draw(std::uint32_t drawIndex, std::size_t* view = nullptr) const;

private:
    const Scene& m_scene;
    const FramePlan& m_plan;
    int m_imageHeight = 0;
    std::vector<std::vector<ref::EyeLight>> m_lights;         ///< per view
    std::vector<std::pair<std::size_t, std::size_t>> m_draws; ///< per global draw index
};

/// Explains pixel (x, y) of an explained frame (ProbeReport::pixel included).
ProbeReport probePixel(const Scene& scene, const ExplainedFrame& frame, int x, int y);

} // namespace lantern::render
