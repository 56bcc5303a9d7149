// DrawLists.h: a frame::Frame packed for the GPU: uniform blocks in the shaders' layouts
// (gpu/GpuLayouts.h), one DrawCommand per draw with its pipeline variant, opaque draws grouped
// by variant (fewer binds), blended ones kept far to near. Pure: testable without a device.
#pragma once

#include "frame/Frame.h"
#include "gpu/DrawList.h"

#include <lantern/Options.h>

namespace lantern::render {

/// The render target `options` ask for.
gpu::TargetDesc targetFor(const RenderOptions& options);

/// The display overlays `options` ask for; a normal length of 0 becomes 3% of the radius of
/// the frame's drawn bounds.
gpu::Overlays overlaysFor(const Scene& scene, const frame::Frame& frame,
                          const RenderOptions& options);

gpu::DrawList buildDrawList(const Scene& scene, const frame::Frame& frame,
                            const RenderOptions& options);

/// The GPU packings, field by field (floats from doubles).
gpu::LightData packLight(const frame::EyeLight& light);
gpu::MaterialData packMaterial(const Material& material);

} // namespace lantern::render
