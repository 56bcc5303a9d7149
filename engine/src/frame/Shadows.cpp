// Shadow maps planned for a frame: which lights cast shadows, and for each the Vulkan clip
// space (reversed Z) of its map(s): a perspective map per spot light, six cube faces per point
// light, and per directional light orthographic cascades fitted to consecutive depth ranges of
// the first view. The maps are rendered by gpu/Shadows.cpp and read by the lighting
// (shaders/include/shadows.glsl).
#include "frame/Frame.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace lantern::frame {
namespace {

// A unit vector not parallel to `d`, for lookAt's up.
glm::dvec3 upFor(const glm::dvec3& d) {
    return std::abs(d.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
}

// How far (texels) a lookup reads from its point, plus one: the margin a cascade keeps.
int filterReach(const ShadowOptions& o) {
    switch (o.filter) {
    case ShadowFilter::Hardware: return 2;
    case ShadowFilter::Pcf: return o.kernel / 2 + 2;
    case ShadowFilter::Pcss: return 33;  // LANTERN_PCSS_MAX_TEXELS + 1 (shadows.glsl)
    }
    return 2;
}

// A perspective map from `eye` along `dir` with the given full field of view (radians), near
// a thousandth of the bounds' size in front of the light and no far plane (reversed Z keeps
// the precision: depth = near / distance).
ShadowMap perspectiveMap(std::size_t light, const glm::dvec3& eye, const glm::dvec3& dir,
                         const glm::dvec3& up, double fov, double radius, const ShadowOptions& o) {
    ShadowMap m;
    m.light = light;
    m.perspective = true;
    const double near = 1e-3 * radius;
    const Projection p = Projection::makePerspective(fov, 1.0, near, kInfinity);
    m.clipFromWorld = vulkanClipFromView(p, 1.0, DepthMode::ReversedZ) * lookAt(eye, eye + dir, up);
    m.texel = 2.0 * std::tan(0.5 * fov) / o.resolution;
    m.depthScale = near;
    if (o.filter == ShadowFilter::Pcss) m.lightSize = o.lightRadius;
    return m;
}

// The eye-space corners of the first view's frustum at depth d (distance in front of the eye):
// the rays through the four corners of its clip square, from two depths unprojected.
struct FrustumRays {
    std::array<glm::dvec3, 4> at{}, dir{};  // corner(d) = at + (d + at.z) * dir, dir.z = -1
    double near = 0.0;                      // the near plane's distance
    glm::dvec3 corner(int k, double d) const { return at[k] + (d + at[k].z) * dir[k]; }
};

FrustumRays frustumRays(const ViewCamera& camera) {
    const glm::dmat4 viewFromClip = glm::inverse(camera.clipFromView);
    const double nearDepth = camera.depth == DepthMode::ReversedZ ? 1.0 : 0.0;
    auto unproject = [&](double x, double y, double z) {
        const glm::dvec4 p = viewFromClip * glm::dvec4(x, y, z, 1.0);
        return glm::dvec3(p) / p.w;
    };
    FrustumRays r;
    for (int k = 0; k < 4; ++k) {
        const double x = k & 1 ? 1.0 : -1.0, y = k & 2 ? 1.0 : -1.0;
        const glm::dvec3 a = unproject(x, y, nearDepth), b = unproject(x, y, 0.5);
        r.at[k] = a;
        r.dir[k] = (b - a) / std::max(a.z - b.z, 1e-300);
    }
    r.near = -r.at[0].z;
    return r;
}

// The depths that split [d0, d1] into n cascades: the practical split scheme (Zhang et al.
// 2006), three quarters logarithmic (even texel density in depth) and a quarter uniform.
std::vector<double> cascadeSplits(double d0, double d1, int n) {
    std::vector<double> s(std::size_t(n) + 1);
    const double lo = std::max(d0, 1e-4 * d1);
    for (int i = 0; i <= n; ++i) {
        const double t = double(i) / n;
        const double uniform = d0 + (d1 - d0) * t;
        const double logarithmic = d0 > 0.0 ? lo * std::pow(d1 / lo, t) : uniform;
        s[std::size_t(i)] = 0.75 * logarithmic + 0.25 * uniform;
    }
    s.front() = d0;
    s.back() = d1;
    return s;
}

// One orthographic map along the light around the sphere (centre, r), as deep as the whole
// scene (every caster between the light and the sphere is in it), its square enlarged by the
// filter's reach and moved in whole texels so the map does not shimmer as the view moves.
ShadowMap orthoMap(std::size_t light, const glm::dvec3& towardsLight, const glm::dvec3& centre,
                   double r, const Bounds& scene, const ShadowOptions& o) {
    ShadowMap m;
    m.light = light;
    const int res = o.resolution;
    const int reach = std::min(filterReach(o), res / 4);
    const double half = r * res / (res - 2.0 * reach);
    const double texel = 2.0 * half / res;
    const glm::dmat4 rotate = lookAt(glm::dvec3(0.0), -towardsLight, upFor(towardsLight));
    glm::dvec3 c(rotate * glm::dvec4(centre, 1.0));
    c.x = std::floor(c.x / texel) * texel;
    c.y = std::floor(c.y / texel) * texel;
    const double R = std::max(scene.radius(), 1e-30);
    const double sceneDepth = -glm::dvec3(rotate * glm::dvec4(scene.center(), 1.0)).z;
    const Projection p = Projection::makeOrtho(c.x - half, c.x + half, c.y - half, c.y + half,
                                               sceneDepth - 2.0 * R, sceneDepth + 2.0 * R);
    const glm::dmat4 clip = vulkanClipFromView(p, 1.0, DepthMode::ReversedZ);
    m.clipFromWorld = clip * rotate;
    m.texel = texel;
    m.depthScale = -clip[2][2];  // depth = -clip[2][2] * distance + clip[3][2]
    m.depthOffset = clip[3][2];
    m.margin = 2.0 * reach / res;
    if (o.filter == ShadowFilter::Pcss) m.lightSize = std::tan(o.sunRadius * 0.017453292519943295);
    return m;
}

// A directional light's cascades: the first view's depth range over the drawn bounds cut by
// cascadeSplits, each slice's bounding sphere (the scene's sphere where that is smaller)
// covered by one map, nearest first (shadows.glsl takes the first that holds the point). One
// map around the scene when asked for one, or when several views share the maps.
void directionalMaps(std::size_t light, const glm::dvec3& towardsLight, const Bounds& b,
                     const Frame& frame, const ShadowOptions& o, std::vector<ShadowMap>& out) {
    const double R = std::max(b.radius(), 1e-30);
    const int n = frame.views.size() == 1 ? std::clamp(o.cascades, 1, kMaxShadowCascades) : 1;
    const ViewCamera& camera = frame.views[0].camera;
    double d0 = kInfinity, d1 = -kInfinity;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                                k & 4 ? b.max.z : b.min.z);
        const double d = -glm::dvec3(camera.viewFromWorld * glm::dvec4(corner, 1.0)).z;
        d0 = std::min(d0, d);
        d1 = std::max(d1, d);
    }
    const FrustumRays rays = frustumRays(camera);
    d0 = std::max(d0, rays.near);
    if (n == 1 || !(d1 > d0) || !std::isfinite(d0) || !std::isfinite(d1)) {
        out.push_back(orthoMap(light, towardsLight, b.center(), R, b, o));
        return;
    }
    const glm::dmat4 worldFromView = glm::inverse(camera.viewFromWorld);
    const std::vector<double> splits = cascadeSplits(d0, d1, n);
    for (int i = 0; i < n; ++i) {
        std::array<glm::dvec3, 8> corners;
        glm::dvec3 centre(0.0);
        for (int k = 0; k < 8; ++k) {
            corners[std::size_t(k)] = glm::dvec3(
                worldFromView * glm::dvec4(rays.corner(k % 4, splits[std::size_t(i + k / 4)]), 1.0));
            centre += corners[std::size_t(k)] / 8.0;
        }
        double r = 0.0;
        for (const glm::dvec3& c : corners) r = std::max(r, glm::length(c - centre));
        if (!(r < R)) out.push_back(orthoMap(light, towardsLight, b.center(), R, b, o));
        else out.push_back(orthoMap(light, towardsLight, centre, r, b, o));
    }
}

} // namespace

Shadows planShadows(const Scene& scene, const Frame& frame, const RenderOptions& o) {
    Shadows s;
    s.options = o.shadows;
    if (frame.views.empty()) return s;
    const View& view = frame.views[0];
    s.firstMap.assign(view.lights.size(), -1);
    s.mapCount.assign(view.lights.size(), 0);
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
    const ShadowOptions& so = o.shadows;
    for (std::size_t i = 0; i < view.lights.size(); ++i) {
        const EyeLight& l = view.lights[i];
        if (!(all || l.castShadows)) continue;
        s.firstMap[i] = int(s.maps.size());
        const glm::dvec3 position(worldFromView * glm::dvec4(l.position, 1.0));
        if (l.type == LightType::Directional) {
            directionalMaps(i, glm::normalize(rotate * l.toLight), bounds, frame, so, s.maps);
        } else if (l.type == LightType::Spot) {
            const glm::dvec3 axis = glm::normalize(rotate * l.spotAxis);
            const double fov = std::min(2.0 * l.coneAngle + 0.02, 3.1);
            s.maps.push_back(perspectiveMap(i, position, axis, upFor(axis), fov, radius, so));
        } else {
            // Six 90-degree faces along the world axes (+X, -X, +Y, -Y, +Z, -Z); the lookup
            // takes the face whose square holds the point (shaders/include/shadows.glsl).
            for (int face = 0; face < 6; ++face) {
                glm::dvec3 axis(0.0);
                axis[face / 2] = face % 2 ? -1.0 : 1.0;
                const glm::dvec3 up = face / 2 == 1 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
                s.maps.push_back(perspectiveMap(i, position, axis, up, 1.5707963267948966, radius, so));
            }
        }
        s.mapCount[i] = int(s.maps.size()) - s.firstMap[i];
    }
    return s;
}

} // namespace lantern::frame
