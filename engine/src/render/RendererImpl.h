// RendererImpl.h: the state behind lantern::Renderer, shared by the files that implement its
// members (Renderer.cpp, SequenceRender.cpp).
#pragma once

#include "gpu/Context.h"
#include "render/Engine.h"
#include "render/FramePlan.h"
#include "render/GpuScene.h"

#include <lantern/Renderer.h>

#include <memory>

namespace lantern {

struct Renderer::Impl {
    std::shared_ptr<gpu::Context> ctx;
    std::unique_ptr<render::Engine> engine;
    DeviceInfo info;
    FrameStats stats;
    bool presentation = false;  ///< created with RendererDesc::presentation (VK_KHR_swapchain)
};

/// Adds Lantern's metadata (version, device, time, shading, camera) to a rendered image.
void attachMetadata(Image& image, const render::FramePlan& plan, const DeviceInfo& device, double time);

} // namespace lantern
