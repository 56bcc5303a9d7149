// Shadow maps planned for a frame: which lights cast shadows, and for each the Vulkan clip
// space (reversed Z) of its map(s), fitted to the bounds of what the frame draws. The maps are
// rendered by gpu/Shadows.cpp and read by the lighting (shaders/include/shadows.glsl).
#include "frame/Frame.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::frame {
namespace {

// A unit vector not parallel to `d`, for lookAt's up.
glm::dvec3 upFor(const glm::dvec3& d) {
    return std::abs(d.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
}

// A perspective map from `eye` along `dir` with the given full field of view (radians), near
// a thousandth of the bounds' size in front of the light and no far plane (reversed Z keeps
// the precision: depth = near / distance).
ShadowMap perspectiveMap(std::size_t light, const glm::dvec3& eye, const glm::dvec3& dir,
                         const glm::dvec3& up, double fov, double radius, int resolution) {
    ShadowMap m;
    m.light = light;
    m.perspective = true;
    const Projection p = Projection::makePerspective(fov, 1.0, 1e-3 * radius, kInfinity);
    m.clipFromWorld = vulkanClipFromView(p, 1.0, DepthMode::ReversedZ) * lookAt(eye, eye + dir, up);
    m.texel = 2.0 * std::tan(0.5 * fov) / resolution;
    return m;
}

// A directional light's orthographic box around the bounds' sphere, looking along the light.
ShadowMap directionalMap(std::size_t light, const glm::dvec3& towardsLight, const Bounds& b,
                         int resolution) {
    ShadowMap m;
    m.light = light;
    const double r = std::max(b.radius(), 1e-30);
    const glm::dvec3 centre = b.center(), eye = centre + 2.0 * r * towardsLight;
    const Projection p = Projection::makeOrtho(-r, r, -r, r, r, 3.0 * r);
    m.clipFromWorld = vulkanClipFromView(p, 1.0, DepthMode::ReversedZ) *
                      lookAt(eye, centre, upFor(towardsLight));
    m.texel = 2.0 * r / resolution;
    return m;
}

} // namespace

Shadows planShadows(const Scene& scene, const Frame& frame, const RenderOptions& o) {
    Shadows s;
    if (frame.views.empty()) return s;
    const View& view = frame.views[0];
    s.firstMap.assign(view.lights.size(), -1);
    const bool all = o.shadows.all;
    bool any = false;
    for (const EyeLight& l : view.lights) any |= all || l.castShadows;
    if (!any) return s;
    const Bounds bounds = computeBounds(scene, frame.pose);
    if (bounds.empty()) return s;
    const double radius = std::max(bounds.radius(), 1e-30);
    // Lights are placed in the first view's eye space: back to world space through it.
    const glm::dmat4 worldFromView = glm::inverse(view.camera.viewFromWorld);
    const glm::dmat3 rotate(worldFromView);
    const int res = o.shadows.resolution;
    for (std::size_t i = 0; i < view.lights.size(); ++i) {
        const EyeLight& l = view.lights[i];
        if (!(all || l.castShadows)) continue;
        s.firstMap[i] = int(s.maps.size());
        const glm::dvec3 position(worldFromView * glm::dvec4(l.position, 1.0));
        if (l.type == LightType::Directional) {
            s.maps.push_back(directionalMap(i, glm::normalize(rotate * l.toLight), bounds, res));
        } else if (l.type == LightType::Spot) {
            const glm::dvec3 axis = glm::normalize(rotate * l.spotAxis);
            const double fov = std::min(2.0 * l.coneAngle + 0.02, 3.1);
            s.maps.push_back(perspectiveMap(i, position, axis, upFor(axis), fov, radius, res));
        } else {
            // Six 90-degree faces along the world axes (+X, -X, +Y, -Y, +Z, -Z); the lookup
            // takes the face whose square holds the point (shaders/include/shadows.glsl).
            for (int face = 0; face < 6; ++face) {
                glm::dvec3 axis(0.0);
                axis[face / 2] = face % 2 ? -1.0 : 1.0;
                const glm::dvec3 up = face / 2 == 1 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
                s.maps.push_back(perspectiveMap(i, position, axis, up, 1.5707963267948966, radius, res));
            }
        }
    }
    return s;
}

} // namespace lantern::frame
