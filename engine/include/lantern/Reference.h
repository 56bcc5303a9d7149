// Reference: ground truth for the lighting model. A CPU ray caster in double precision renders
// scenes whose meshes stand for analytic spheres and planes, with the exact surface and its
// exact normal, the same camera, lights and materials as the renderer, and the lighting
// equation of the scene contract (spec section 1) evaluated per sample; and the error metrics
// that compare a render with it (the accuracy benchmark, `lantern bench accuracy`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Options.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <vector>

namespace lantern {

/// The analytic surfaces the reference can ray-cast.
enum class AnalyticKind {
    Sphere, ///< centred at the mesh's origin, as makeSphere() builds it
    Plane,  ///< the square |x|, |y| <= size / 2 in the mesh's XY plane, normal +Z (makePlane())
    /// around the mesh's Z axis: the circle of radius `radius` in the XY plane swept by a
    /// circle of radius `size` (the tube's), so a ray can meet it four times
    Torus,
};

/// Declares that Scene::meshes[mesh] stands for an exact surface in its own (object) space.
/// The node transforms that place the mesh place the surface too (any affine transform: a
/// scaled sphere is an ellipsoid, with the normals the inverse transpose gives).
struct LANTERN_API AnalyticShape {
    int mesh = -1;
    AnalyticKind kind = AnalyticKind::Sphere;
    double radius = 1.0; ///< Sphere; Torus: the ring's radius
    double size = 2.0;   ///< Plane: side length; Torus: the tube's radius

    static AnalyticShape sphere(int mesh, double radius);
    static AnalyticShape plane(int mesh, double size);
    static AnalyticShape torus(int mesh, double ringRadius, double tubeRadius);
};

/// The triangle mesh a rasteriser draws for `shape` at a tessellation level: a sphere with
/// `segments` around and max(2, segments / 2) rings (2 segments (rings - 1) triangles), a
/// plane split into segments x segments quads, a torus with `segments` around the ring and
/// max(3, segments / 2) around the tube. `segments` is clamped to at least 3 (sphere)
/// or 1 (plane).
LANTERN_API Primitive tessellate(const AnalyticShape& shape, int segments);

struct ReferenceOptions {
    /// Which meshes are which analytic surfaces. Every mesh drawn by the scene must be listed.
    std::vector<AnalyticShape> shapes;
    /// The box image averages boxSamples x boxSamples stratified rays per pixel (>= 1).
    int boxSamples = 8;
    /// A pixel is interior when edgeProbes x edgeProbes rays spread over its whole square,
    /// corners included, all meet the same surface (>= 2).
    int edgeProbes = 4;
    int threads = 0; ///< worker threads; 0: one per core
    /// Every light casts exact shadows (as RenderOptions::shadows.all asks; a light whose
    /// Light::castShadows is set casts them either way): a shadow ray from each shaded point to each light
    /// (unbounded towards a directional light); every surface it crosses, both faces, lets
    /// through what its material lets through (an opaque one nothing, a blended one 1 - alpha,
    /// a masked one all where the mask cuts it away). A shadow scales the light's diffuse and
    /// specular terms; its ambient term is not shadowed.
    bool shadows = false;
};

/// The reference pictures of one frame. Both images are premultiplied linear RGBA like a
/// render (alpha: the covered fraction of the pixel; background pixels hold
/// RenderOptions::background), top row first.
struct ReferenceImage {
    Image centre; ///< one ray through each pixel centre: what a one-sample rasteriser samples
    Image box;    ///< the pixel's area average: the ideal anti-aliased picture
    /// One per pixel: 1 where the same surfaces, in the same order, cover the whole pixel (a
    /// single surface, or blended layers over one: the shading-only comparison), 0 on
    /// silhouettes, on edges between surfaces (a blended layer's included) and on the
    /// background.
    std::vector<std::uint8_t> interior;
    std::size_t rays = 0; ///< rays cast, all kinds
};

/// Ray-casts the scene at `timeSeconds` as the renderer would frame it under `options`: the
/// same camera (RenderOptions::camera, resolved as the renderer resolves it), the lights and
/// the lighting model (shading switches that change the equation: specular model, local
/// viewer, two-sided, clamp), the materials and back-face culling. The shading mode is ignored:
/// the reference is exact everywhere. Blended materials are composited exactly: every layer
/// along the ray in front of the nearest opaque surface, in depth order, as if each pixel's
/// fragments were sorted (the picture an order-independent method converges to). With
/// ReferenceOptions::shadows every light casts exact shadows. Refused: InvalidInput for a
/// drawn mesh without an AnalyticShape, a bad shape or bad options; Unsupported for what the
/// reference does not model (several views, GL compatibility, a base-colour texture that is
/// not nearest-filtered or lies on a torus). A nearest-filtered base-colour texture is sampled
/// at the surface's exact texture coordinates (those tessellate() gives its vertices): its
/// colour multiplies the diffuse term and its alpha the material's, as the shaders do.
LANTERN_API Result<ReferenceImage> raycastReference(const Scene& scene,
                                                    const RenderOptions& options,
                                                    double timeSeconds,
                                                    const ReferenceOptions& reference);

/// Error statistics of one channel population (absolute errors of linear RGB values; max and
/// 99th percentile are per pixel, over the worst of its three channels).
struct ErrorStats {
    std::size_t pixels = 0;
    double rmse = 0.0; ///< over pixels and RGB channels
    double max = 0.0;
    double p99 = 0.0;
};

/// How far a render is from the reference (scene contract colours, linear HDR, before any
/// tone mapping). Alpha is not compared: colour is premultiplied, so coverage errors show in
/// RGB.
struct ErrorMetrics {
    ErrorStats whole;    ///< every pixel against the box image (shading and aliasing)
    double psnr = 0.0;   ///< dB: 20 log10(largest box reference value / whole.rmse); +inf if exact
    ErrorStats interior; ///< reference-interior pixels the render covers fully, against the
                         ///< centre image: shading alone
    ErrorStats silhouette; ///< every other pixel that either picture covers, against the box
                           ///< image: geometry and aliasing
    /// Highlight peak ratio: the render's largest value over the reference's largest value,
    /// both over the reference's interior pixels (1: the highlight keeps its height).
    double peakRatio = 0.0;
    std::size_t nonFinite = 0; ///< NaN/Inf values in the render's colour
};

/// Compares a render (same size, same options) with its reference.
LANTERN_API Result<ErrorMetrics> measureError(const Image& rendered,
                                              const ReferenceImage& reference);

} // namespace lantern
