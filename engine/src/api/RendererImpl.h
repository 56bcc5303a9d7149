// RendererImpl.h: the state behind lantern::Renderer, shared by the files of the public API
// that implement its members (Renderer.cpp, Sequence.cpp, WindowTarget.cpp).
#pragma once

#include "frame/Frame.h"
#include "gpu/Device.h"

#include <lantern/Renderer.h>

#include <memory>

namespace lantern {

struct Renderer::Impl {
    std::shared_ptr<gpu::Device> device;
    FrameStats stats;
};

/// Adds Lantern's metadata (version, device, time, shading, camera) to a rendered image.
void attachMetadata(Image& image, const frame::Frame& frame, const DeviceInfo& device, double time);

} // namespace lantern
