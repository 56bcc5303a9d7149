// GL/GLU camera matrices in double precision and their exact conversion to Vulkan clip space.
#include <lantern/Camera.h>

#include "math/Robust.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace lantern {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The unit vector along v, computed after dividing by the largest component so that neither
// the squares of tiny components (1e-200) underflow nor those of huge ones (1e200) overflow.
glm::dvec3 direction(const glm::dvec3& v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return glm::normalize(v / m);
}

// Sets row `r` of a column-major matrix.
void setRow(glm::dmat4& m, int r, double a, double b, double c, double d) {
    m[0][r] = a;
    m[1][r] = b;
    m[2][r] = c;
    m[3][r] = d;
}

} // namespace

glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up) {
    // GLU: forward f, side s = f x up, u = s x f; rows s, u, -f; then translate by -eye.
    const glm::dvec3 f = direction(target - eye);
    const glm::dvec3 s = direction(glm::cross(f, direction(up)));
    const glm::dvec3 u = glm::cross(s, f);
    glm::dmat4 m(1.0);
    setRow(m, 0, s.x, s.y, s.z, -glm::dot(s, eye));
    setRow(m, 1, u.x, u.y, u.z, -glm::dot(u, eye));
    setRow(m, 2, -f.x, -f.y, -f.z, glm::dot(f, eye));
    setRow(m, 3, 0, 0, 0, 1);
    return m;
}

glm::dmat4 ortho(double l, double r, double b, double t, double n, double f) {
    glm::dmat4 m(0.0);
    setRow(m, 0, 2.0 / (r - l), 0, 0, -(r + l) / (r - l));
    setRow(m, 1, 0, 2.0 / (t - b), 0, -(t + b) / (t - b));
    setRow(m, 2, 0, 0, -2.0 / (f - n), -(f + n) / (f - n));
    setRow(m, 3, 0, 0, 0, 1);
    return m;
}

glm::dmat4 frustum(double l, double r, double b, double t, double n, double f) {
    glm::dmat4 m(0.0);
    // For f = +inf, C -> -1 and D -> -2n (the limit of GL's formulas).
    const double ratio = n / f;  // 0 for an infinite far plane
    const double c = std::isinf(f) ? -1.0 : -(f + n) / (f - n);
    const double d = std::isinf(f) ? -2.0 * n : -2.0 * n / (1.0 - ratio);
    setRow(m, 0, 2.0 * n / (r - l), 0, (r + l) / (r - l), 0);
    setRow(m, 1, 0, 2.0 * n / (t - b), (t + b) / (t - b), 0);
    setRow(m, 2, 0, 0, c, d);
    setRow(m, 3, 0, 0, -1, 0);
    return m;
}

glm::dmat4 perspective(double fovyDegrees, double aspect, double n, double f) {
    const double cot = 1.0 / std::tan(fovyDegrees * kPi / 360.0);
    glm::dmat4 m(0.0);
    const double c = std::isinf(f) ? -1.0 : (f + n) / (n - f);
    const double d = std::isinf(f) ? -2.0 * n : 2.0 * f * n / (n - f);
    setRow(m, 0, cot / aspect, 0, 0, 0);
    setRow(m, 1, 0, cot, 0, 0);
    setRow(m, 2, 0, 0, c, d);
    setRow(m, 3, 0, 0, -1, 0);
    return m;
}

glm::dmat4 viewport(double x, double y, double w, double h, double depthNear, double depthFar) {
    glm::dmat4 m(0.0);
    setRow(m, 0, w / 2.0, 0, 0, x + w / 2.0);
    setRow(m, 1, 0, h / 2.0, 0, y + h / 2.0);
    setRow(m, 2, 0, 0, (depthFar - depthNear) / 2.0, (depthNear + depthFar) / 2.0);
    setRow(m, 3, 0, 0, 0, 1);
    return m;
}

double fovyFromLens(double focalLengthMm, double filmHeightMm) {
    return 2.0 * std::atan(filmHeightMm / (2.0 * focalLengthMm)) * 180.0 / kPi;
}

std::optional<glm::dvec3> project(const glm::dvec3& object, const glm::dmat4& viewFromModel,
                                  const glm::dmat4& clipFromView, const glm::dvec4& vp) {
    const glm::dvec4 clip = clipFromView * (viewFromModel * glm::dvec4(object, 1.0));
    if (clip.w == 0.0) return std::nullopt;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return glm::dvec3(vp.x + vp.z * (ndc.x + 1.0) / 2.0, vp.y + vp.w * (ndc.y + 1.0) / 2.0,
                      (ndc.z + 1.0) / 2.0);
}

std::optional<glm::dvec3> unProject(const glm::dvec3& window, const glm::dmat4& viewFromModel,
                                    const glm::dmat4& clipFromView, const glm::dvec4& vp) {
    const glm::dmat4 clipFromModel = clipFromView * viewFromModel;
    if (glm::determinant(clipFromModel) == 0.0 || vp.z == 0.0 || vp.w == 0.0)
        return std::nullopt;
    const glm::dvec4 ndc(2.0 * (window.x - vp.x) / vp.z - 1.0,
                         2.0 * (window.y - vp.y) / vp.w - 1.0, 2.0 * window.z - 1.0, 1.0);
    const glm::dvec4 object = glm::inverse(clipFromModel) * ndc;
    if (object.w == 0.0 || !std::isfinite(object.w)) return std::nullopt;
    return glm::dvec3(object) / object.w;
}

const char* toString(DepthMode mode) noexcept {
    return mode == DepthMode::ReversedZ ? "reversed" : "standard";
}

std::optional<DepthMode> parseDepthMode(std::string_view text) noexcept {
    if (text == "reversed") return DepthMode::ReversedZ;
    if (text == "standard") return DepthMode::Standard;
    return std::nullopt;
}

glm::dmat4 vulkanFromGlClip(DepthMode mode) {
    glm::dmat4 m(0.0);
    const double zs = mode == DepthMode::ReversedZ ? -0.5 : 0.5;
    setRow(m, 0, 1, 0, 0, 0);
    setRow(m, 1, 0, -1, 0, 0);
    setRow(m, 2, 0, 0, zs, 0.5);
    setRow(m, 3, 0, 0, 0, 1);
    return m;
}

Projection Projection::makePerspective(double yfovRadians, double aspect, double znear,
                                       double zfar) {
    Projection p;
    p.kind = ProjectionKind::Perspective;
    p.yfov = yfovRadians;
    p.aspect = aspect;
    p.znear = znear;
    p.zfar = zfar;
    return p;
}

Projection Projection::makeFrustum(double l, double r, double b, double t, double n, double f) {
    Projection p;
    p.kind = ProjectionKind::Frustum;
    p.left = l, p.right = r, p.bottom = b, p.top = t, p.znear = n, p.zfar = f;
    return p;
}

Projection Projection::makeOrtho(double l, double r, double b, double t, double n, double f) {
    Projection p;
    p.kind = ProjectionKind::Orthographic;
    p.left = l, p.right = r, p.bottom = b, p.top = t, p.znear = n, p.zfar = f;
    return p;
}

Projection Projection::makeLens(double focalLength, double filmWidth, double filmHeight,
                                double znear, double zfar) {
    const double aspect = filmWidth > 0.0 ? filmWidth / filmHeight : 0.0;
    return makePerspective(fovyFromLens(focalLength, filmHeight) * kPi / 180.0, aspect, znear,
                           zfar);
}

Projection fittedProjection(const Projection& projection, double viewportAspect) {
    Projection p = projection;
    if (!p.fitViewportAspect || p.kind == ProjectionKind::Perspective || !(viewportAspect > 0.0))
        return p;
    const double w = p.right - p.left, h = p.top - p.bottom;
    if (!(w != 0.0 && h != 0.0)) return p;
    const double cx = 0.5 * (p.left + p.right), cy = 0.5 * (p.bottom + p.top);
    if (std::abs(w / h) < viewportAspect) {
        const double half = 0.5 * std::abs(h) * viewportAspect * (w < 0 ? -1.0 : 1.0);
        p.left = cx - half, p.right = cx + half;
    } else {
        const double half = 0.5 * std::abs(w) / viewportAspect * (h < 0 ? -1.0 : 1.0);
        p.bottom = cy - half, p.top = cy + half;
    }
    return p;
}

glm::dmat4 glClipFromView(const Projection& projection, double viewportAspect) {
    const Projection p = fittedProjection(projection, viewportAspect);
    switch (p.kind) {
    case ProjectionKind::Perspective:
        return perspective(p.yfov * 180.0 / kPi, p.aspect > 0 ? p.aspect : viewportAspect,
                           p.znear, p.zfar);
    case ProjectionKind::Frustum:
        return frustum(p.left, p.right, p.bottom, p.top, p.znear, p.zfar);
    case ProjectionKind::Orthographic:
        return ortho(p.left, p.right, p.bottom, p.top, p.znear, p.zfar);
    }
    return glm::dmat4(1.0);
}

glm::dmat4 vulkanClipFromView(const Projection& p, double viewportAspect, DepthMode mode) {
    // Rows 0, 1 and 3 are GL's with row 1 negated; row 2 is vulkanFromGlClip's depth row
    // applied symbolically, with n/f kept as a ratio so an infinite far plane is exact.
    glm::dmat4 gl = glClipFromView(p, viewportAspect);  // fits the box to the viewport when asked
    glm::dmat4 m = gl;
    for (int c = 0; c < 4; ++c) m[c][1] = -gl[c][1];
    const double n = p.znear, f = p.zfar;
    if (p.kind == ProjectionKind::Orthographic) {
        const double span = f - n;
        if (mode == DepthMode::ReversedZ)
            setRow(m, 2, 0, 0, 1.0 / span, f / span);
        else
            setRow(m, 2, 0, 0, -1.0 / span, -n / span);
    } else {
        const double ratio = std::isinf(f) ? 0.0 : n / f;  // n/f in [0, 1)
        if (mode == DepthMode::ReversedZ)
            setRow(m, 2, 0, 0, ratio / (1.0 - ratio), n / (1.0 - ratio));
        else
            setRow(m, 2, 0, 0, -1.0 / (1.0 - ratio), -n / (1.0 - ratio));
    }
    return m;
}

Camera glDefaultCamera() {
    Camera c;
    c.name = "GL default";
    c.projection = Projection::makeOrtho(-1, 1, -1, 1, -1, 1);
    c.lookAt = LookAt{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    return c;
}

Result<void> checkLookAt(const LookAt& la, const std::string& object) {
    if (!finite(la.eye) || !finite(la.target) || !finite(la.up))
        return makeError(ErrorCode::InvalidInput, "lookAt has a non-finite value", object);
    const glm::dvec3 f = la.target - la.eye;
    if (f == glm::dvec3(0.0))
        return makeError(ErrorCode::InvalidInput,
                         "eye and target are the same point (no view direction)", object);
    if (!finite(f))
        return makeError(ErrorCode::InvalidInput,
                         "eye and target are too far apart (their difference overflows)", object);
    if (la.up == glm::dvec3(0.0))
        return makeError(ErrorCode::InvalidInput, "up vector has zero length", object);
    // Judged by direction only: up = (0, 1e-200, 0) is as good as (0, 1, 0).
    // Parallel when the sine of the angle between f and up is below ~1e-12.
    const double s = glm::length(glm::cross(direction(f), direction(la.up)));
    if (!(s > 1e-12))
        return makeError(ErrorCode::InvalidInput,
                         "up vector is parallel to the view direction", object);
    return {};
}

Result<void> checkProjection(const Projection& p, const std::string& object) {
    auto bad = [&](const std::string& what) {
        return makeError(ErrorCode::InvalidInput, what, object);
    };
    const bool perspectiveKind = p.kind != ProjectionKind::Orthographic;
    if (!std::isfinite(p.znear)) return bad("near is not a finite number");
    if (std::isnan(p.zfar) || (std::isinf(p.zfar) && !(perspectiveKind && p.zfar > 0)))
        return bad("far must be a finite number (or +inf for a perspective projection)");
    if (p.kind == ProjectionKind::Perspective) {
        const double deg = p.yfov * 180.0 / kPi;
        if (!std::isfinite(p.yfov) || !(deg > 0.0 && deg < 180.0))
            return bad("fovy must be in (0, 180) degrees, got " + std::to_string(deg));
        // aspect 0 stands for "the viewport's aspect".
        if (!std::isfinite(p.aspect) || p.aspect < 0.0)
            return bad("aspect must be a positive finite number");
    } else {
        for (double v : {p.left, p.right, p.bottom, p.top})
            if (!std::isfinite(v)) return bad("left/right/bottom/top must be finite");
        if (p.left == p.right) return bad("left == right (zero-width view volume)");
        if (p.bottom == p.top) return bad("bottom == top (zero-height view volume)");
    }
    if (perspectiveKind) {
        if (!(p.znear > 0.0)) return bad("near must be > 0 for a perspective projection");
        if (!(p.zfar > p.znear)) return bad("far must be greater than near");
    } else if (p.zfar == p.znear) {
        return bad("far == near (zero-depth view volume)");
    }
    if (p.kind != ProjectionKind::Perspective &&
        (!std::isfinite(p.right - p.left) || !std::isfinite(p.top - p.bottom)))
        return bad("the view volume is too large (right - left or top - bottom overflows)");
    if (p.kind == ProjectionKind::Orthographic && !std::isfinite(p.zfar - p.znear))
        return bad("the view volume is too deep (far - near overflows)");
    // The GPU receives the matrix in single precision: an entry beyond float's range would be
    // infinite there (NaN in the image), and a scale or near term below float's smallest
    // normal number flushes to zero (an empty image). Refuse both rather than render either.
    const double aspect = p.aspect > 0.0 ? p.aspect : 1.0;
    for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
        const glm::dmat4 m = vulkanClipFromView(p, aspect, mode);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!(std::abs(m[c][r]) <= double(std::numeric_limits<float>::max())))
                    return bad("the projection matrix overflows single precision (the view "
                               "volume is too narrow: fovy, right - left, top - bottom or "
                               "far - near is too small)");
        const double essential[] = {m[0][0], m[1][1],
                                    p.kind == ProjectionKind::Orthographic ? m[2][2] : m[3][2]};
        for (double v : essential)
            if (std::abs(v) < double(std::numeric_limits<float>::min()))
                return bad("the projection matrix underflows single precision (the view "
                           "volume is too wide, or near is too small: nothing would render)");
    }
    return {};
}

TransformStack::TransformStack() : m_stack{glm::dmat4(1.0)} {}

void TransformStack::push() { m_stack.push_back(m_stack.back()); }

bool TransformStack::pop() {
    if (m_stack.size() <= 1) return false;
    m_stack.pop_back();
    return true;
}

void TransformStack::loadIdentity() { m_stack.back() = glm::dmat4(1.0); }
void TransformStack::load(const glm::dmat4& m) { m_stack.back() = m; }
void TransformStack::multiply(const glm::dmat4& m) { m_stack.back() = m_stack.back() * m; }

void TransformStack::translate(const glm::dvec3& t) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(t, 1.0);
    multiply(m);
}

void TransformStack::rotate(double degrees, const glm::dvec3& axis) {
    // glRotate's matrix (reference page), axis normalised.
    const glm::dvec3 a = glm::normalize(axis);
    const double c = std::cos(degrees * kPi / 180.0), s = std::sin(degrees * kPi / 180.0);
    const double x = a.x, y = a.y, z = a.z, k = 1.0 - c;
    glm::dmat4 m(1.0);
    setRow(m, 0, x * x * k + c, x * y * k - z * s, x * z * k + y * s, 0);
    setRow(m, 1, y * x * k + z * s, y * y * k + c, y * z * k - x * s, 0);
    setRow(m, 2, x * z * k - y * s, y * z * k + x * s, z * z * k + c, 0);
    multiply(m);
}

void TransformStack::scale(const glm::dvec3& s) {
    glm::dmat4 m(1.0);
    m[0][0] = s.x, m[1][1] = s.y, m[2][2] = s.z;
    multiply(m);
}

void TransformStack::lookAt(const glm::dvec3& eye, const glm::dvec3& target,
                            const glm::dvec3& up) {
    multiply(lantern::lookAt(eye, target, up));
}

glm::dmat3 normalMatrix(const glm::dmat4& viewFromModel) {
    glm::dmat3 m(viewFromModel);
    double largest = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(m[c][r]));
    if (!(largest > 0.0) || !std::isfinite(largest)) return glm::dmat3(0.0);
    // The cofactor is homogeneous of degree 2: pre-scaling keeps it in double range.
    m /= largest;
    // Accurate cross products and determinant: with scales 1e-6 and 1e6 under a rotation the
    // textbook formulas cancel to noise, and the determinant's sign comes out wrong.
    glm::dmat3 cof(math::accurateCross(m[1], m[2]), math::accurateCross(m[2], m[0]),
                   math::accurateCross(m[0], m[1]));
    // cof = det * inverse-transpose; a mirroring transform (det < 0) would flip normals inward.
    if (math::accurateDot(m[0], cof[0]) < 0.0) cof = -cof;
    double big = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) big = std::max(big, std::abs(cof[c][r]));
    if (!(big > 0.0)) return glm::dmat3(0.0);
    return cof / big;
}

} // namespace lantern
