// AovPlanes.h: the id planes and the world-space normal of a frame, made on the CPU from what
// the GPU wrote per pixel (the draw index + 1 and the eye-space normal): each draw is one
// node's primitive seen from one view, so a table per draw turns the draw index into the node,
// mesh, primitive, material and semantic ids, and the view's rotation turns the eye normal into
// the world's. The GPU pays for one small integer plane, whatever ids are asked for.
#pragma once

#include "frame/Frame.h"
#include "gpu/Device.h"

#include <lantern/Image.h>
#include <lantern/Scene.h>

#include <cstdint>
#include <vector>

namespace lantern::render {

/// Each node's semantic id: its own "semantic_id", else its parent's, 0 at a root without one.
std::vector<std::uint32_t> nodeSemantics(const Scene& scene);

/// Fills readback.image's id planes and world normal as `aovs` asks (a no-op when it asks for
/// none). Needs readback.ids (the frame's TargetDesc::readIds()) and, for the world normal,
/// the eye normal plane.
void resolveAovPlanes(const Scene& scene, const frame::Frame& frame, const AovSet& aovs,
                      gpu::FrameReadback& readback);

} // namespace lantern::render
