// Cameras resolved for a view in double precision: a scene camera on its node, GL's default
// camera, automatic framing of the animation's bounds, and the options' overrides.
#include "frame/Frame.h"
#include "math/Robust.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace lantern::frame {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The rigid part (rotation + translation) of a world transform: a camera node's scale must
// not distort the view.
glm::dmat4 rigid(const glm::dmat4& m) {
    glm::dvec3 x(m[0]), y(m[1]), z(m[2]);
    x = glm::length(x) > 0 ? glm::normalize(x) : glm::dvec3(1, 0, 0);
    y = y - glm::dot(y, x) * x;
    y = glm::length(y) > 0 ? glm::normalize(y) : glm::dvec3(0, 1, 0);
    z = glm::cross(x, y);
    glm::dmat4 r(1.0);
    r[0] = glm::dvec4(x, 0);
    r[1] = glm::dvec4(y, 0);
    r[2] = glm::dvec4(z, 0);
    r[3] = m[3];
    return r;
}

int findCameraNode(const Scene& scene, const Pose& pose, int camera) {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (pose.visible[i] && scene.nodes[i].camera == camera) return int(i);
    return -1;
}

// An orthographic framing fits the bounds' box as seen from this direction (a modeller's top,
// front and side views), not its bounding sphere: a flat ground seen edge-on must not shrink
// the objects standing on it. The box is centred on the view axis.
Projection framingOrtho(const Bounds& b, const glm::dmat4& viewFromWorld, double r, double d,
                        double aspect, double margin) {
    double hw = 0.0, hh = 0.0;
    for (int i = 0; i < 8 && !b.empty(); ++i) {
        const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                (i & 4) ? b.max.z : b.min.z);
        const glm::dvec4 p = viewFromWorld * glm::dvec4(corner, 1.0);
        hw = std::max(hw, std::abs(p.x));
        hh = std::max(hh, std::abs(p.y));
    }
    if (!(hw > 1e-6 * r) && !(hh > 1e-6 * r)) hw = hh = r;
    double h = std::max(hh, 1e-6 * r) * margin, w = std::max(hw, 1e-6 * r) * margin;
    if (w / h < aspect)
        w = h * aspect;
    else
        h = w / aspect;
    return Projection::makeOrtho(-w, w, -h, h, d - 1.5 * r, d + 1.5 * r);
}

// The sphere automatic framing fits: the animation's bounds (a unit sphere at the origin when
// nothing is drawn; a tiny positive radius for a single point).
struct FramingSphere {
    glm::dvec3 c{0.0};
    double r = 1.0;
    Bounds b;
};
FramingSphere framingSphere(const Scene& scene, int root) {
    FramingSphere s;
    s.b = animationBounds(scene, root);
    if (!s.b.empty()) {
        s.c = s.b.center();
        s.r = s.b.radius();
        if (!(s.r > 0.0)) s.r = std::max(1e-6, glm::length(s.c) * 1e-6);
    }
    return s;
}

ViewCamera framingCamera(const FramingSphere& sphere, const CameraSpec& spec, double aspect) {
    ViewCamera rc;
    const auto& [c, r, b] = sphere;
    const glm::dvec3 dir = glm::length(spec.framingDirection) > 0
                               ? glm::normalize(spec.framingDirection)
                               : glm::dvec3(0, 0, -1);
    glm::dvec3 up(0, 1, 0);
    if (std::abs(glm::dot(dir, up)) > 0.99)
        up = dir.y < 0 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 0, 1);
    const double margin = 1.08;
    if (spec.framingOrthographic) {
        const double d = 2.0 * r;
        rc.viewFromWorld = lookAt(c - dir * d, c, up);
        rc.projection = framingOrtho(b, rc.viewFromWorld, r, d, aspect, margin);
        rc.description = "automatic framing (orthographic)";
    } else {
        const double yfov = 45.0 * kPi / 180.0;
        const double xfov = 2.0 * std::atan(std::tan(yfov / 2.0) * aspect);
        const double d = r * margin / std::sin(std::min(yfov, xfov) / 2.0);
        rc.viewFromWorld = lookAt(c - dir * d, c, up);
        // Near and far planes fitted around the bounding sphere, with a margin.
        rc.projection = Projection::makePerspective(yfov, 0.0, std::max(d - 1.5 * r, d * 1e-3),
                                                    d + 1.5 * r);
        rc.description = "automatic framing";
    }
    return rc;
}

std::string cameraName(const Scene& scene, int i) {
    std::string s = "camera " + std::to_string(i);
    if (!scene.cameras[std::size_t(i)].name.empty())
        s += " \"" + scene.cameras[std::size_t(i)].name + "\"";
    return s;
}

Result<ViewCamera> sceneCamera(const Scene& scene, const Pose& pose, int camera,
                               const std::string& object) {
    if (camera < 0 || camera >= int(scene.cameras.size()))
        return makeError(ErrorCode::InvalidInput,
                         "camera " + std::to_string(camera) + " does not exist (the scene has " +
                             std::to_string(scene.cameras.size()) + " cameras)",
                         object);
    ViewCamera rc;
    const Camera& cam = scene.cameras[std::size_t(camera)];
    if (cam.lookAt) {
        rc.viewFromWorld = lookAt(cam.lookAt->eye, cam.lookAt->target, cam.lookAt->up);
    } else {
        const int node = findCameraNode(scene, pose, camera);
        if (node < 0)
            return makeError(ErrorCode::InvalidInput,
                             cameraName(scene, camera) + " is not placed by any node of scene " +
                                 std::to_string(pose.root),
                             object);
        rc.viewFromWorld = math::inverseRigid(rigid(pose.worldFromNode[std::size_t(node)]));
    }
    rc.projection = cam.projection;
    rc.description = cameraName(scene, camera);
    return rc;
}

// The projection of `spec.intrinsics` with automatic near (and, for orthographic, far) planes
// fitted to the sphere round the animation's bounds as seen from `viewFromWorld`: a pinhole's
// near plane 1.5 radii before the sphere's centre (at least 1e-3 radii from the eye, so a camera
// inside the scene still sees it); an orthographic box 1.5 radii either side of the centre.
Projection intrinsicProjection(const Scene& scene, int root, Intrinsics k,
                               const glm::dmat4& viewFromWorld) {
    const bool autoNear = automaticNear(k), autoFar = k.orthographic && std::isinf(k.zfar);
    if (autoNear || autoFar) {
        const auto [c, r, bounds] = framingSphere(scene, root);
        const double d = -(viewFromWorld * glm::dvec4(c, 1.0)).z;
        if (k.orthographic) {
            if (autoNear) k.znear = d - 1.5 * r;
            if (autoFar) k.zfar = d + 1.5 * r;
        } else {
            k.znear = std::max(d - 1.5 * r, 1e-3 * r);
            if (!(k.znear < k.zfar)) k.znear = k.zfar * 1e-3;
        }
    }
    return projectionFromIntrinsics(k);
}

// spec.viewFromWorld and spec.intrinsics, checked, into `rc`.
Result<void> applyPose(const Scene& scene, const Pose& pose, const CameraSpec& spec,
                       const std::string& object, ViewCamera& rc) {
    if (spec.viewFromWorld) {
        LANTERN_TRY(checkPose(*spec.viewFromWorld, object.empty() ? "viewFromWorld" : object));
        rc.viewFromWorld = *spec.viewFromWorld;
    }
    if (spec.intrinsics) {
        LANTERN_TRY(checkIntrinsics(*spec.intrinsics, object.empty() ? "intrinsics" : object));
        rc.projection = intrinsicProjection(scene, pose.root, *spec.intrinsics, rc.viewFromWorld);
        LANTERN_TRY(checkProjection(rc.projection, object.empty() ? "intrinsics" : object));
    }
    if (spec.viewFromWorld && spec.intrinsics)
        rc.description = "intrinsics and pose";
    else if (spec.viewFromWorld)
        rc.description += " with viewFromWorld";
    else if (spec.intrinsics)
        rc.description += " with intrinsics";
    return {};
}

} // namespace

Bounds animationBounds(const Scene& scene, int root) {
    // Sample every key time of every animation (and t = 0): the framing then contains the
    // whole motion (between keys, linear motion stays inside the keys' hull for translations).
    std::vector<double> times{0.0};
    for (const Animation& a : scene.animations)
        for (const AnimationSampler& s : a.samplers)
            times.insert(times.end(), s.times.begin(), s.times.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    if (times.size() > 64) {  // bound the cost for long animations
        std::vector<double> picked;
        for (std::size_t i = 0; i < 64; ++i) picked.push_back(times[i * (times.size() - 1) / 63]);
        times = picked;
    }
    Bounds b;
    for (double t : times) {
        const Bounds bt = computeBounds(scene, evaluatePose(scene, root, t));
        if (!bt.empty()) {
            b.extend(bt.min);
            b.extend(bt.max);
        }
    }
    return b;
}

Result<ViewCamera> resolveCamera(const Scene& scene, const Pose& pose, const CameraSpec& spec,
                                 double aspect, DepthMode depth, const std::string& object) {
    using Source = CameraSpec::Source;
    Source source = spec.source;
    int camera = spec.sceneCamera;
    if (source == Source::Automatic) {
        source = Source::Framing;
        for (std::size_t i = 0; i < scene.cameras.size(); ++i)
            if (scene.cameras[i].lookAt || findCameraNode(scene, pose, int(i)) >= 0) {
                source = Source::SceneCamera;
                camera = int(i);
                break;
            }
    }
    ViewCamera rc;
    std::optional<FramingSphere> framed;  // the bounds automatic framing fitted (scanned once)
    switch (source) {
    case Source::SceneCamera: {
        auto c = sceneCamera(scene, pose, camera, object);
        if (!c) return std::move(c).error();
        rc = std::move(*c);
        break;
    }
    case Source::GlDefault:
        rc.viewFromWorld = glm::dmat4(1.0);
        rc.projection = glDefaultCamera().projection;
        rc.description = "GL default camera";
        break;
    case Source::Framing:
    case Source::Automatic:
        framed = framingSphere(scene, pose.root);
        rc = framingCamera(*framed, spec, aspect);
        break;
    }
    if (spec.lookAt && spec.viewFromWorld)
        return makeError(ErrorCode::InvalidInput, "give either lookAt or viewFromWorld, not both",
                         object.empty() ? "camera" : object);
    if (spec.projection && spec.intrinsics)
        return makeError(ErrorCode::InvalidInput,
                         "give either a projection or intrinsics, not both",
                         object.empty() ? "camera" : object);
    if (spec.lookAt) {
        LANTERN_TRY(checkLookAt(*spec.lookAt, object.empty() ? "lookAt" : object));
        rc.viewFromWorld = lookAt(spec.lookAt->eye, spec.lookAt->target, spec.lookAt->up);
        rc.description += " with lookAt";
        // Framing's perspective planes were fitted from its own eye: fitted again from this
        // one, so that an eye inside the bounds (walking through a scene) sees them.
        if (framed && !spec.framingOrthographic && !spec.projection) {
            const double e = glm::length(spec.lookAt->eye - framed->c), far = e + 1.5 * framed->r;
            rc.projection.znear = std::max(e - 1.5 * framed->r, far * 1e-4);
            rc.projection.zfar = far;
        }
    }
    if (spec.projection) {
        LANTERN_TRY(checkProjection(*spec.projection, object.empty() ? "projection" : object));
        rc.projection = *spec.projection;
        rc.description += " with explicit projection";
    }
    LANTERN_TRY(applyPose(scene, pose, spec, object, rc));
    rc.depth = depth;
    rc.clipFromView = vulkanClipFromView(rc.projection, aspect, depth);
    return rc;
}

} // namespace lantern::frame

// The public naming of views (lantern/Options.h) lives with the framing that uses it.
namespace lantern {
namespace {
constexpr double kPiValue = 3.14159265358979323846;
} // namespace

const char* toString(ViewDirection view) noexcept {
    switch (view) {
    case ViewDirection::ThreeQuarter: return "three-quarter";
    case ViewDirection::Front: return "front";
    case ViewDirection::Back: return "back";
    case ViewDirection::Left: return "left";
    case ViewDirection::Right: return "right";
    case ViewDirection::Top: return "top";
    case ViewDirection::Bottom: return "bottom";
    case ViewDirection::Iso: return "iso";
    }
    return "?";
}

std::optional<ViewDirection> parseViewDirection(std::string_view text) noexcept {
    for (ViewDirection v : kViewDirections)
        if (text == toString(v)) return v;
    return std::nullopt;
}

glm::dvec3 framingDirection(ViewDirection view) noexcept {
    // The camera's position relative to the scene; the camera looks the other way.
    glm::dvec3 from(0.0, 0.0, 1.0);
    switch (view) {
    case ViewDirection::ThreeQuarter: {
        // 45 degrees round from the front towards +X, 30 degrees up.
        const double c = std::cos(kPiValue / 6.0), s = std::sin(kPiValue / 6.0);
        from = glm::dvec3(c * std::sin(kPiValue / 4.0), s, c * std::cos(kPiValue / 4.0));
        break;
    }
    case ViewDirection::Front: from = {0, 0, 1}; break;
    case ViewDirection::Back: from = {0, 0, -1}; break;
    case ViewDirection::Left: from = {-1, 0, 0}; break;
    case ViewDirection::Right: from = {1, 0, 0}; break;
    case ViewDirection::Top: from = {0, 1, 0}; break;
    case ViewDirection::Bottom: from = {0, -1, 0}; break;
    case ViewDirection::Iso: from = glm::normalize(glm::dvec3(1, 1, 1)); break;
    }
    return -from;
}

} // namespace lantern
