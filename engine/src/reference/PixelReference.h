// PixelReference.h: the CPU reference of a rendered frame's pixels. Given the draw and triangle
// the renderer wrote at a pixel (its id AOV), the ray through the pixel centre meets that
// triangle, and the lighting equation is evaluated there in double precision under the frame's
// shading rule (per fragment, per vertex interpolated, at the triangle's centroid, or at the
// provoking vertex). Which terms apply is decided from the scene's own data (materials,
// vertex colours, textures) and the frame's lighting switches; nothing is read from the
// renderer's pipeline variants, so a wrong variant shows up as a difference.
#pragma once

#include "frame/Frame.h"
#include "reference/Lighting.h"

#include <lantern/Image.h>
#include <lantern/Probe.h>

#include <cstdint>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

namespace lantern::ref {

class PixelReference {
public:
    /// Holds references to `scene` and `frame`, which must outlive it. `imageHeight`: the
    /// rendered image's height in pixels (views are placed in GL's bottom-left convention).
    PixelReference(const Scene& scene, const frame::Frame& frame, int imageHeight);

    /// Pixel (x, y) (top-left origin) given the ids the renderer wrote there: `drawId` is the
    /// draw index + 1 (0: background), `triangle` the primitive id. `perLight` false leaves
    /// ProbeEvaluation::lights empty (faster for whole images with many lights). Fills
    /// everything but ProbeReport::pixel.
    ProbeReport explain(int x, int y, std::uint32_t drawId, std::uint32_t triangle,
                        bool perLight = true) const;

private:
    /// A deformed draw's vertices in its model space (deformPrimitive()), made on first use.
    const DeformedPrimitive& deformed(const frame::Draw& d) const;

    const Scene& m_scene;
    const frame::Frame& m_frame;
    int m_imageHeight = 0;
    mutable std::mutex m_mutex;
    mutable std::map<std::pair<std::uint32_t, std::uint32_t>, DeformedPrimitive> m_deformed;
};

/// Explains pixel (x, y) of `image` (whose ids are `ids`: two per pixel), ProbeReport::pixel
/// included.
ProbeReport probePixel(const Scene& scene, const frame::Frame& frame, const Image& image,
                       const std::vector<std::uint32_t>& ids, int x, int y);

} // namespace lantern::ref
