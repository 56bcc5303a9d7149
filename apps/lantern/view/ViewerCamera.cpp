// The viewer's free camera: turntable orbit, pan, zoom, fly, framing, and its exact
// `lantern render` equivalent.
#include "view/ViewerCamera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace lantern::cli {
namespace {

// The same constant CameraOptions uses to turn --perspective's degrees into radians, so that
// the printed command line rebuilds the very same projection.
constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxPitch = 89.5 * kPi / 180.0;
constexpr double kOrbitRadiansPerPixel = 0.005;
constexpr double kLookRadiansPerPixel = 0.003;
const glm::dvec3 kUp{0.0, 1.0, 0.0};

std::string number(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

std::string numbers(std::initializer_list<double> values) {
    std::string s;
    for (double v : values)
        s += (s.empty() ? "" : ",") + number(v);
    return s;
}

} // namespace

void ViewerCamera::setBounds(const Bounds& b) {
    if (b.empty()) {
        m_center = glm::dvec3(0.0);
        m_radius = 1.0;
        return;
    }
    m_center = b.center();
    m_radius = b.radius() > 0.0 ? b.radius() : std::max(1e-6, glm::length(m_center) * 1e-6);
}

glm::dvec3 ViewerCamera::forward() const {
    return {std::sin(m_yaw) * std::cos(m_pitch), std::sin(m_pitch),
            -std::cos(m_yaw) * std::cos(m_pitch)};
}

void ViewerCamera::takeOver(const CameraPlacement& placement) {
    const glm::dmat4 worldFromView = glm::inverse(placement.viewFromWorld);
    const glm::dvec3 eyeNow(worldFromView[3]);
    glm::dvec3 f = -glm::dvec3(worldFromView[2]);
    f = glm::length(f) > 0.0 ? glm::normalize(f) : glm::dvec3(0, 0, -1);
    m_pitch = std::clamp(std::asin(std::clamp(f.y, -1.0, 1.0)), -kMaxPitch, kMaxPitch);
    m_yaw = std::atan2(f.x, -f.z);
    f = forward();
    const Projection& p = placement.projection;
    const double along = glm::dot(m_center - eyeNow, f);
    m_orthographic = p.kind == ProjectionKind::Orthographic;
    if (p.kind == ProjectionKind::Perspective) m_yfovDeg = p.yfov * 180.0 / kPi;
    if (p.kind == ProjectionKind::Frustum)
        m_yfovDeg = (std::atan(p.top / p.znear) - std::atan(p.bottom / p.znear)) * 180.0 / kPi;
    if (m_orthographic) {
        // The eye's place along the axis does not change an orthographic picture: pivot about
        // the bounds' centre as seen along the axis, with the eye well outside the bounds.
        m_halfHeight = (p.top - p.bottom) / 2.0;
        m_target = eyeNow + f * along;
        m_distance = 3.0 * m_radius;
    } else {
        m_distance = along > 0.05 * m_radius ? along : m_radius;
        m_target = eyeNow + f * m_distance;
    }
    m_free = true;
}

void ViewerCamera::orbit(double dx, double dy) {
    m_yaw += dx * kOrbitRadiansPerPixel;
    m_pitch = std::clamp(m_pitch - dy * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void ViewerCamera::look(double dx, double dy) {
    const glm::dvec3 e = eye();
    m_yaw += dx * kLookRadiansPerPixel;
    m_pitch = std::clamp(m_pitch - dy * kLookRadiansPerPixel, -kMaxPitch, kMaxPitch);
    m_target = e + forward() * m_distance;
}

void ViewerCamera::pan(double dx, double dy, double viewHeight) {
    const double height =
        m_orthographic ? 2.0 * m_halfHeight : 2.0 * m_distance * std::tan(m_yfovDeg * kPi / 360.0);
    const double perPixel = height / std::max(viewHeight, 1.0);
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, kUp));
    const glm::dvec3 up = glm::cross(right, f);
    // The scene follows the mouse: the pivot moves the other way.
    m_target += (-right * dx + up * dy) * perPixel;
}

void ViewerCamera::zoom(double steps) {
    const double k = std::pow(0.9, steps);
    if (m_orthographic)
        m_halfHeight = std::max(m_halfHeight * k, m_radius * 1e-6);
    else
        m_distance = std::max(m_distance * k, m_radius * 1e-3);
}

void ViewerCamera::move(const glm::dvec3& v) {
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, kUp));
    m_target += (right * v.x + kUp * v.y + f * v.z) * m_radius;
}

void ViewerCamera::frameAll(double aspect) {
    m_target = m_center;
    const double margin = 1.08;
    if (m_orthographic) {
        m_halfHeight = m_radius * margin / std::min(aspect, 1.0);
        m_distance = 3.0 * m_radius;
    } else {
        const double yfov = m_yfovDeg * kPi / 180.0;
        const double xfov = 2.0 * std::atan(std::tan(yfov / 2.0) * aspect);
        m_distance = m_radius * margin / std::sin(std::min(yfov, xfov) / 2.0);
    }
}

void ViewerCamera::lookFrom(ViewDirection view, double aspect) {
    const glm::dvec3 f = glm::normalize(framingDirection(view));
    m_pitch = std::clamp(std::asin(std::clamp(f.y, -1.0, 1.0)), -kMaxPitch, kMaxPitch);
    // Straight down or up: keep -Z up on screen (yaw 0), as the top view of `--view` does.
    const bool vertical = std::abs(f.x) < 1e-12 && std::abs(f.z) < 1e-12;
    m_yaw = vertical ? 0.0 : std::atan2(f.x, -f.z);
    frameAll(aspect);
}

void ViewerCamera::setOrthographic(bool orthographic) {
    const double t = std::tan(m_yfovDeg * kPi / 360.0);
    if (orthographic && !m_orthographic) m_halfHeight = m_distance * t;
    if (!orthographic && m_orthographic) m_distance = std::max(m_halfHeight / t, m_radius * 1e-3);
    m_orthographic = orthographic;
}

Projection ViewerCamera::projection(double aspect) const {
    const double along = glm::dot(m_center - eye(), forward());
    if (m_orthographic) {
        const double h = m_halfHeight, w = h * aspect;
        return Projection::makeOrtho(-w, w, -h, h, along - 2.0 * m_radius, along + 2.0 * m_radius);
    }
    // Reversed-Z float depth with an infinite far plane keeps its precision however small
    // the near plane is; near stays a small fraction of the scene so nothing is clipped.
    return Projection::makePerspective(m_yfovDeg * kPi / 180.0, aspect, m_radius * 1e-3, kInfinity);
}

CameraSpec ViewerCamera::spec(double aspect) const {
    if (!m_free) return m_base;
    CameraSpec s;
    s.source = CameraSpec::Source::GlDefault; // both parts are overridden below
    s.lookAt = LookAt{eye(), m_target, kUp};
    s.projection = projection(aspect);
    return s;
}

std::string ViewerCamera::commandLine(double aspect) const {
    std::string s;
    const CameraSpec spec = this->spec(aspect);
    if (!m_free) {
        if (spec.source == CameraSpec::Source::SceneCamera)
            s += " --camera " + std::to_string(spec.sceneCamera);
        if (spec.source == CameraSpec::Source::GlDefault) s += " --default-camera";
    }
    if (spec.lookAt) {
        const LookAt& l = *spec.lookAt;
        s += " --look-at " + numbers({l.eye.x, l.eye.y, l.eye.z, l.target.x, l.target.y, l.target.z,
                                      l.up.x, l.up.y, l.up.z});
    }
    if (spec.projection) {
        const Projection& p = *spec.projection;
        switch (p.kind) {
        case ProjectionKind::Perspective:
            // The free camera keeps its field of view in degrees, as --perspective takes it.
            s += " --perspective " +
                 numbers({m_free ? m_yfovDeg : p.yfov * 180.0 / kPi, p.aspect, p.znear}) + "," +
                 (std::isinf(p.zfar) ? std::string("inf") : number(p.zfar));
            break;
        case ProjectionKind::Frustum:
            s += " --frustum " + numbers({p.left, p.right, p.bottom, p.top, p.znear}) + "," +
                 (std::isinf(p.zfar) ? std::string("inf") : number(p.zfar));
            break;
        case ProjectionKind::Orthographic:
            s += " --ortho " + numbers({p.left, p.right, p.bottom, p.top, p.znear, p.zfar});
            break;
        }
    }
    return s;
}

} // namespace lantern::cli
