// OpenCV intrinsics and OpenCV/glTF poses to Lantern's view and projection and back, in double.
// The derivations are in docs/cameras.md ("Computer-vision cameras"); the one subtle point is
// the pixel convention: OpenCV puts pixel centres at integers, so the image's outer edges lie
// at u = -0.5 and u = width - 0.5, and the frustum's planes go through those edges.
#include <lantern/CameraConventions.h>

#include "math/Robust.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace lantern {
namespace {

constexpr int kMaxSide = 16384;  // the renderer's largest image side

std::string number(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

// viewFromWorld = flip * world_to_camera(OpenCV): OpenCV's y (down) and z (forward) are
// Lantern's -y and -z. The flip is its own inverse.
glm::dmat4 flipYZ(const glm::dmat4& m) {
    glm::dmat4 r = m;
    for (int c = 0; c < 4; ++c) {
        r[c][1] = -m[c][1];
        r[c][2] = -m[c][2];
    }
    return r;
}

} // namespace

bool automaticNear(const Intrinsics& k) noexcept {
    return std::isnan(k.znear) || (!k.orthographic && k.znear == 0.0);
}

const char* toString(PoseConvention convention) noexcept {
    return convention == PoseConvention::OpenCV ? "opencv" : "gltf";
}

std::optional<PoseConvention> parsePoseConvention(std::string_view text) noexcept {
    if (text == "opencv") return PoseConvention::OpenCV;
    if (text == "gltf") return PoseConvention::Gltf;
    return std::nullopt;
}

Result<void> checkIntrinsics(const Intrinsics& k, const std::string& object) {
    auto bad = [&](const std::string& what) {
        return makeError(ErrorCode::InvalidInput, what, object);
    };
    if (k.width < 1 || k.width > kMaxSide || k.height < 1 || k.height > kMaxSide)
        return bad("image size " + std::to_string(k.width) + "x" + std::to_string(k.height) +
                   " is not within 1..16384 on each side");
    for (double v : {k.fx, k.fy, k.cx, k.cy})
        if (!std::isfinite(v)) return bad("fx, fy, cx and cy must be finite numbers");
    if (!(k.fx > 0.0) || !(k.fy > 0.0))
        return bad("the focal lengths must be > 0 (fx " + number(k.fx) + ", fy " + number(k.fy) +
                   ")");
    // What the renderer fills in (an automatic near; an orthographic far left infinite) is
    // checked once it is known.
    if (automaticNear(k) || (k.orthographic && std::isinf(k.zfar))) {
        if (std::isnan(k.zfar) || (!k.orthographic && !(k.zfar > 0.0)))
            return bad("far must be > 0");
        return {};
    }
    const Projection p = projectionFromIntrinsics(k);
    return checkProjection(p, object);
}

Result<void> checkPose(const glm::dmat4& pose, const std::string& object) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(pose[c][r]))
                return makeError(ErrorCode::InvalidInput, "the matrix has a non-finite entry",
                                 object);
    if (pose[0][3] != 0.0 || pose[1][3] != 0.0 || pose[2][3] != 0.0 || pose[3][3] != 1.0)
        return makeError(ErrorCode::InvalidInput, "the last row must be 0, 0, 0, 1", object);
    const glm::dmat3 r(pose);
    const glm::dmat3 e = r * glm::transpose(r) - glm::dmat3(1.0);
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(e[c][i]));
    if (worst > 1e-6)
        return makeError(ErrorCode::InvalidInput,
                         "the 3x3 part is not a rotation (R R^T differs from the identity by " +
                             number(worst) + "; scale and shear are not allowed)",
                         object);
    if (glm::determinant(r) < 0.0)
        return makeError(ErrorCode::InvalidInput,
                         "the 3x3 part mirrors (its determinant is negative): not a rotation",
                         object);
    return {};
}

glm::dmat4 viewFromPose(const glm::dmat4& pose, PoseConvention convention) {
    return convention == PoseConvention::OpenCV ? flipYZ(pose) : math::inverseRigid(pose);
}

glm::dmat4 poseFromView(const glm::dmat4& viewFromWorld, PoseConvention convention) {
    return convention == PoseConvention::OpenCV ? flipYZ(viewFromWorld)
                                                : math::inverseRigid(viewFromWorld);
}

Projection projectionFromIntrinsics(const Intrinsics& k) {
    // The edges of the image in OpenCV pixels are u = -0.5 .. width - 0.5 and v = -0.5 ..
    // height - 0.5; v grows downwards, so v = -0.5 is GL's top.
    const double w = double(k.width), h = double(k.height);
    const double scale = k.orthographic ? 1.0 : k.znear;
    const double l = -(k.cx + 0.5) * scale / k.fx, r = (w - 0.5 - k.cx) * scale / k.fx;
    const double t = (k.cy + 0.5) * scale / k.fy, b = -(h - 0.5 - k.cy) * scale / k.fy;
    return k.orthographic ? Projection::makeOrtho(l, r, b, t, k.znear, k.zfar)
                          : Projection::makeFrustum(l, r, b, t, k.znear, k.zfar);
}

std::optional<Intrinsics> intrinsicsFromClip(const glm::dmat4& m, int width, int height,
                                             bool reversedDepth) {
    // Rows of Lantern's Vulkan matrices (m[column][row]): a pinhole has row 3 = (0, 0, -1, 0)
    // and x_ndc = m00 x/(-z) - m02; an orthographic box has row 3 = (0, 0, 0, 1) and
    // x_ndc = m00 x + m03. Vulkan's y_ndc grows down the image, as OpenCV's v does, and
    // OpenCV's Y is -y; u = (x_ndc + 1) width / 2 - 0.5.
    if (m[1][0] != 0.0 || m[0][1] != 0.0 || m[0][2] != 0.0 || m[1][2] != 0.0 || width < 1 ||
        height < 1 || m[0][0] == 0.0 || m[1][1] == 0.0)
        return std::nullopt;
    Intrinsics k;
    k.width = width, k.height = height;
    const double w = double(width), h = double(height);
    k.fx = m[0][0] * w / 2.0;
    k.fy = -m[1][1] * h / 2.0;
    const double m22 = m[2][2], m23 = m[3][2];
    if (m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == -1.0 && m[3][3] == 0.0) {
        k.cx = (1.0 - m[2][0]) * w / 2.0 - 0.5;
        k.cy = (1.0 - m[2][1]) * h / 2.0 - 0.5;
        // Reversed: m22 = n/(f-n), m23 = nf/(f-n); standard: m22 = -f/(f-n), m23 = -nf/(f-n).
        if (reversedDepth) {
            k.znear = m23 / (1.0 + m22);
            k.zfar = m22 == 0.0 ? kInfinity : m23 / m22;
        } else {
            k.znear = m23 / m22;
            k.zfar = m22 == -1.0 ? kInfinity : m23 / (m22 + 1.0);
        }
    } else if (m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == 0.0 && m[3][3] == 1.0 &&
               m[2][0] == 0.0 && m[2][1] == 0.0 && m22 != 0.0) {
        k.orthographic = true;
        k.cx = (1.0 + m[3][0]) * w / 2.0 - 0.5;
        k.cy = (1.0 + m[3][1]) * h / 2.0 - 0.5;
        // Reversed: m22 = 1/(f-n), m23 = f/(f-n); standard: m22 = -1/(f-n), m23 = -n/(f-n).
        const double a = m23 / m22, b = (m23 - 1.0) / m22;
        k.zfar = reversedDepth ? a : b;
        k.znear = reversedDepth ? b : a;
    } else {
        return std::nullopt;
    }
    return k;
}

Result<CameraModel> cameraModelOf(const Image& image) {
    if (!image.camera)
        return makeError(ErrorCode::InvalidInput, "the image carries no camera", "image.camera");
    if (!image.camera->wholeImage)
        return makeError(ErrorCode::InvalidInput,
                         "the image has several views: no one camera describes it",
                         "image.camera");
    auto k = intrinsicsFromClip(image.camera->clipFromView, image.width, image.height,
                                image.camera->reversedDepth);
    if (!k)
        return makeError(ErrorCode::InvalidInput,
                         "the image's projection has no pinhole or orthographic intrinsics",
                         "image.camera");
    return CameraModel{*k, poseFromView(image.camera->viewFromWorld, PoseConvention::OpenCV)};
}

} // namespace lantern
