// CameraTestSupport.h: measuring where things land on screen to a small fraction of a pixel.
// A "ramp quad" is unlit and its colour is its own surface coordinate (u, v) plus an id in
// blue; perspective-correct interpolation evaluates it exactly at each pixel centre, so a
// least-squares fit over the pixels around (u, v) tells where the point (u, v) projects, far
// more precisely than coverage can (coverage moves in whole pixels). Coordinates in images are
// pixels from the top-left corner, pixel (i, j) centred at (i + 0.5, j + 0.5).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <lantern/Lantern.h>
#include <optional>
#include <string>

namespace lantern::test {

/// A rectangle of pixels in an image (top-left origin).
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// The image rectangle of a GL viewport (bottom-left origin) in an image `imageHeight` tall.
PixelRect rectOfView(const View& view, int imageHeight);

/// A width x height quad in the XY plane centred on the origin, normal +Z, whose colour is
/// (u, v, id, 1) with u = 0..1 left to right and v = 0..1 bottom to top.
Primitive makeRampQuad(double width, double height, float id);
/// The object-space point of (u, v) on makeRampQuad(width, height, ...).
glm::dvec3 rampPoint(double width, double height, double u, double v);

/// Unlit, double-sided white: the output colour is exactly the vertex colour.
Material unlitMaterial(const std::string& name = "unlit");

/// Where (u, v) of the ramp quad with this id appears inside `rect` (image coordinates), or
/// nullopt when it is not visible there (fewer than 6 ramp pixels, or the point is more than
/// 1.5 pixels outside the pixels that show the quad).
std::optional<glm::dvec2> locateRamp(const Image& image, const PixelRect& rect, float id, double u,
                                     double v);

/// Writes `image` as <testOutputDir>/<name>.exr and returns " (image: PATH)", for failure
/// messages (gtest evaluates them only on failure).
std::string savedAs(const Image& image, const std::string& name);

/// Image coordinates of a GL window coordinate (bottom-left origin) in an image this tall.
inline glm::dvec2 imageFromWindow(const glm::dvec3& window, int imageHeight) {
    return {window.x, double(imageHeight) - window.y};
}

/// Adds a node with a ramp quad (mesh and unlit material appended) placed by worldFromQuad;
/// returns the node index. The scene's first root lists it.
int addRampQuad(Scene& scene, double width, double height, float id,
                const glm::dmat4& worldFromQuad);

/// An empty scene with one root (and no lights: GL's headlight applies, which unlit ignores).
Scene emptyScene();

/// Pixels whose colour differs by more than `tolerance` in any channel, skipping pixels within
/// `edgeMargin` pixels of a silhouette edge of `expected` (a change of coverage, or of depth by
/// more than 2 % when both images carry the depth AOV); also returns the largest difference.
struct ImageDifference {
    std::size_t differing = 0;
    std::size_t compared = 0;
    float largest = 0.0f;
};
ImageDifference compareAwayFromEdges(const Image& actual, const Image& expected, float tolerance,
                                     int edgeMargin = 1);

} // namespace lantern::test
