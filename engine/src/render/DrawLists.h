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

/// The frame's shadow maps into list.shadows (render/ShadowLists.cpp): each pass's frame block
/// and the draws it records (with RenderOptions::culling, only the casters that can reach the
/// map), each view's lookups, and each light's maps in its LightData.info (z: first + 1, 0 for
/// none; w: how many). Called once the views' draws are packed.
void packShadows(const Scene& scene, const frame::Frame& frame, const RenderOptions& options,
                 gpu::DrawList& list);

/// The GPU packings, field by field (floats from doubles).
gpu::Mat4 toMat4(const glm::dmat4& m);
gpu::LightData packLight(const frame::EyeLight& light);
gpu::MaterialData packMaterial(const Material& material);

} // namespace lantern::render
