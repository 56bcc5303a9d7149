// Variants.h: the pipeline variant of each draw: the frame's shading rule and the features the
// draw and the frame's lights need, mapped to specialisation constants (lantern_shared.h's
// LANTERN_SC_*) and fixed-function state. A scene pays only for the features it uses;
// FeatureMode::AllFeatures compiles every cost feature in, for measuring what that saves.
#pragma once

#include "frame/Frame.h"
#include "gpu/DrawList.h"

#include <lantern/Options.h>

#include <string>

namespace lantern::render {

gpu::PipelineKey pipelineKey(const frame::Frame& frame, const frame::Draw& draw,
                             const RenderOptions& options);

/// How the options composite blended surfaces: as asked, else exact (sorted under GL
/// compatibility, as GL programs draw).
TransparencyMethod effectiveTransparency(const RenderOptions& options);

/// One line, e.g. "phong: lights=directional specular=blinn vertex-color opaque".
std::string describe(const gpu::PipelineKey& key);

} // namespace lantern::render
