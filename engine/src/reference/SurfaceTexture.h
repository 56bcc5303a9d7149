// reference/SurfaceTexture.h: the base-colour texture on the reference's analytic surfaces:
// the texture coordinates tessellate() gives a sphere's or a plane's vertices, evaluated
// exactly at a model-space point, and nearest-texel sampling as the device does it.
#pragma once

#include <lantern/Reference.h>
#include <lantern/Scene.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace lantern::ref {

/// The texture coordinates of model point p on `shape`: a plane's (x / size + 1/2,
/// 1/2 - y / size), a sphere's (longitude / 2 pi, colatitude / pi) as makeSphere() lays them.
glm::dvec2 analyticUv(const AnalyticShape& shape, const glm::dvec3& p);

/// The texel nearest to uv (Vulkan's rule: floor(uv * size), wrapped by the texture's modes),
/// as linear RGBA: sRGB colour decoded, alpha linear.
glm::dvec4 sampleNearest(const Texture& texture, const glm::dvec2& uv);

} // namespace lantern::ref
