// Precision by design, without a GPU: the float matrices the draw list uploads put points where
// double precision does even 1e7 units from the origin (numerics.md LW-1), while world-space
// floats would be tens of pixels off; normals survive scales from 0 and 1e-20 to 1e20
// (numerics.md 3.5); extreme but valid projections stay finite.
#include "render/FrameRender.h"

#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <lantern/Camera.h>
#include <lantern/Scene.h>

namespace {

using namespace lantern;

constexpr double kPi = 3.14159265358979323846;

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    // atan2(|a x b|, a.b): accurate for tiny angles, unlike acos.
    const glm::dvec3 ua = glm::normalize(a), ub = glm::normalize(b);
    return std::atan2(glm::length(glm::cross(ua, ub)), glm::dot(ua, ub));
}

glm::dmat3 rotation(double degrees, glm::dvec3 axis) {
    return glm::mat3_cast(glm::angleAxis(degrees * kPi / 180.0, glm::normalize(axis)));
}

// --- Normals ---------------------------------------------------------------------------------

struct NormalRow {
    const char* why;
    glm::dvec3 scale;
};

// Model = R1 * S * R2, so its inverse transpose is R1 * S^-1 * R2 exactly (rotations are
// orthogonal): the reference needs no matrix inversion. The model itself, composed in double,
// already carries a relative error of about 1e-16 times the condition number (largest over
// smallest scale) in its thin directions, so that bounds the normal's angle error; the
// tolerance is 4x that. Before the normal matrix used accurate cross products and
// determinant, the 1e6/1e-6 rows came out pointing backwards (the determinant's sign was lost).
const NormalRow kNormalRows[] = {
    {"unit", {1, 1, 1}},
    {"non-uniform 1e-6 on x", {1e-6, 1, 1}},
    {"non-uniform 1e6 on y", {1, 1e6, 1}},
    {"1e-6, 1, 1e6 (condition 1e12)", {1e-6, 1, 1e6}},
    {"1e6, 1e-6, 1e-6 (condition 1e12)", {1e6, 1e-6, 1e-6}},
    {"1e-3, 1e3, 1", {1e-3, 1e3, 1}},
    {"uniform 1e-20", {1e-20, 1e-20, 1e-20}},
    {"uniform 1e20", {1e20, 1e20, 1e20}},
    {"uniform 1e-300", {1e-300, 1e-300, 1e-300}},
    {"mirrored and non-uniform", {-2, 1e-6, 5e5}},
};

double conditionNumber(const glm::dvec3& s) {
    const glm::dvec3 a = glm::abs(s);
    return std::max({a.x, a.y, a.z}) / std::min({a.x, a.y, a.z});
}

TEST(CameraMathPrecision, NormalMatrixIsTheInverseTransposeAtExtremeScales) {
    const glm::dmat3 r1 = rotation(33, {1, 2, 3}), r2 = rotation(-71, {-2, 0.5, 1});
    const glm::dvec3 normals[] = {{0, 0, 1}, {1, 0, 0}, {0.3, -0.8, 0.52}, {-0.6, 0.1, 0.79}};
    for (const NormalRow& row : kNormalRows) {
        const glm::dvec3 s = row.scale;
        glm::dmat4 model(
            r1 * glm::dmat3(glm::dvec3(s.x, 0, 0), glm::dvec3(0, s.y, 0), glm::dvec3(0, 0, s.z)) *
            r2);
        const glm::dmat3 inverseTranspose =
            r1 *
            glm::dmat3(glm::dvec3(1 / s.x, 0, 0), glm::dvec3(0, 1 / s.y, 0),
                       glm::dvec3(0, 0, 1 / s.z)) *
            r2;
        const glm::dmat3 n = lantern::normalMatrix(model);
        // The normal matrix is normalised: its largest entry is 1 whatever the scale.
        double largest = 0;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                largest = std::max(largest, std::abs(n[c][r]));
        EXPECT_NEAR(largest, 1.0, 1e-15) << row.why;
        for (const glm::dvec3& normal : normals) {
            const glm::dvec3 got = n * normal;
            // Same direction as the inverse transpose, mirrors included (the cofactor alone
            // would point inwards there: it is det times the inverse transpose).
            const glm::dvec3 want = inverseTranspose * normal;
            // Compare directions after scaling both into a safe range.
            const double wm = std::max({std::abs(want.x), std::abs(want.y), std::abs(want.z)});
            const double tolerance = 4e-16 * conditionNumber(s) + 1e-15;
            EXPECT_LT(angleBetween(got, want / wm), tolerance) << row.why;

            // As the GPU sees it: the matrix and normal in float, normalised in float.
            const glm::mat3 nf(n);
            const glm::vec3 gf = glm::normalize(nf * glm::vec3(normal));
            EXPECT_TRUE(std::isfinite(gf.x) && std::isfinite(gf.y) && std::isfinite(gf.z))
                << row.why;
            EXPECT_LT(angleBetween(glm::dvec3(gf), want / wm), tolerance + 1e-6)
                << row.why << " (float)";
        }
    }
}

TEST(CameraMathPrecision, NormalMatrixOfAZeroScaleIsFinite) {
    const glm::dmat3 r1 = rotation(20, {0, 1, 1});
    struct Row {
        const char* why;
        glm::dvec3 scale;
        glm::dvec3 expected; ///< the only normal left, before r1; zero: none
    };
    const Row rows[] = {
        {"flattened along z: a disc", {1, 1, 0}, {0, 0, 1}},
        {"flattened along x, others 1e6 and 1e-6", {0, 1e6, 1e-6}, {1, 0, 0}},
        {"flattened along y, 1e20 elsewhere", {1e20, 0, 1e20}, {0, 1, 0}},
        {"two zero scales: a line has no normal", {0, 0, 3}, {0, 0, 0}},
        {"all zero", {0, 0, 0}, {0, 0, 0}},
    };
    for (const Row& row : rows) {
        const glm::dvec3 s = row.scale;
        const glm::dmat4 model(
            r1 * glm::dmat3(glm::dvec3(s.x, 0, 0), glm::dvec3(0, s.y, 0), glm::dvec3(0, 0, s.z)));
        const glm::dmat3 n = lantern::normalMatrix(model);
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                ASSERT_TRUE(std::isfinite(n[c][r])) << row.why;
        for (const glm::dvec3 normal : {glm::dvec3(0.3, 0.4, 0.866), glm::dvec3(0.9, -0.3, 0.3)}) {
            const glm::dvec3 got = n * normal;
            if (row.expected == glm::dvec3(0.0)) {
                EXPECT_EQ(got, glm::dvec3(0.0)) << row.why;
                continue;
            }
            const glm::dvec3 want = r1 * row.expected;
            EXPECT_NEAR(std::abs(glm::dot(glm::normalize(got), want)), 1.0, 1e-12) << row.why;
        }
    }
}

TEST(CameraMathPrecision, MirroringIsDetectedForIllConditionedTransforms) {
    // The plan flips the front-face winding of mirrored nodes; a wrong determinant sign would
    // cull the visible side of a thin, rotated object.
    // Twelve rotation pairs: the textbook determinant of an ill-conditioned row is noise of
    // either sign, so at least one pair would catch it.
    for (int k = 0; k < 12; ++k)
        for (const NormalRow& row : kNormalRows) {
            const glm::dmat3 r1 = rotation(33 + 29 * k, {1, 2 + k, 3}),
                             r2 = rotation(-71 + 17 * k, {-2, 0.5, 1 + k});
            const glm::dvec3 s = row.scale;
            Scene scene;
            scene.sourcePath = "test";
            scene.meshes.push_back(Mesh{"quad", {makePlane(1.0)}});
            Node node;
            node.mesh = 0;
            node.matrix = glm::dmat4(
                r1 *
                glm::dmat3(glm::dvec3(s.x, 0, 0), glm::dvec3(0, s.y, 0), glm::dvec3(0, 0, s.z)) *
                r2);
            scene.nodes.push_back(node);
            scene.roots.push_back(SceneRoot{"root", {0}, std::nullopt});
            RenderOptions options;
            options.camera.source = CameraSpec::Source::GlDefault;
            auto plan = render::planFrame(scene, options, 0.0);
            ASSERT_TRUE(plan) << plan.error().describe();
            ASSERT_EQ(plan->list.views.at(0).draws.size(), 1u) << row.why;
            EXPECT_EQ(plan->list.views[0].draws[0].frontClockwise, s.x * s.y * s.z < 0)
                << row.why << " " << k;
        }
}

// --- Extreme but valid projections -----------------------------------------------------------

TEST(CameraMathPrecision, ExtremeValidProjectionsAreFiniteAndOrdered) {
    const double deg = kPi / 180;
    struct Row {
        const char* why;
        Projection p;
        double viewportAspect;
    };
    const Row rows[] = {
        {"fovy 1e-4 deg", Projection::makePerspective(1e-4 * deg, 0, 0.1, kInfinity), 1},
        {"fovy 179.9 deg", Projection::makePerspective(179.9 * deg, 0, 0.1, 100), 1},
        {"aspect 1e-4", Projection::makePerspective(1, 1e-4, 0.1, 100), 1},
        {"aspect 1e4", Projection::makePerspective(1, 1e4, 0.1, 100), 1},
        {"near 1e-6 far 1e12", Projection::makePerspective(1, 0, 1e-6, 1e12), 1.5},
        {"frustum near 1e-6 far 1e12",
         Projection::makeFrustum(-1e-6, 2e-6, -1e-6, 1e-6, 1e-6, 1e12), 1},
        {"ortho 1e-6 thin", Projection::makeOrtho(-1e-6, 1e-6, -1, 1, 0, 1e-6), 1},
    };
    for (const Row& r : rows) {
        ASSERT_TRUE(checkProjection(r.p, "p")) << r.why;
        for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
            const glm::mat4 m(vulkanClipFromView(r.p, r.viewportAspect, mode)); // as uploaded
            for (int c = 0; c < 4; ++c)
                for (int k = 0; k < 4; ++k)
                    ASSERT_TRUE(std::isfinite(m[c][k])) << r.why;
            // Depth of three points inside the volume: in 0..1, ordered front to back.
            const double n = r.p.znear;
            const double f = std::isinf(r.p.zfar) ? n * 1e6 : r.p.zfar;
            double previous = mode == DepthMode::ReversedZ ? 2.0 : -1.0;
            for (double t : {0.001, 0.5, 0.999}) {
                const float z = float(-(n + (f - n) * t));
                const glm::vec4 clip = m * glm::vec4(0, 0, z, 1);
                const float d = clip.z / clip.w;
                EXPECT_TRUE(d >= 0.0f && d <= 1.0f) << r.why << " t=" << t << " d=" << d;
                if (mode == DepthMode::ReversedZ)
                    EXPECT_LE(d, previous) << r.why;
                else
                    EXPECT_GE(d, previous) << r.why;
                previous = d;
            }
        }
    }
}

// --- Large world coordinates (numerics.md LW-1) ----------------------------------------------

// One object 10 m ahead of a 1920x1080, 60-degree camera at (X, 0, 0). Returns the screen
// error in pixels of a vertex projected (a) with the float matrices the draw list uploads, applied
// in float as the GPU does, and (b) with world-space floats (the path Lantern avoids), both
// against the double-precision projection.
struct Errors {
    double cameraRelativePx, worldSpaceFloatPx;
};

Errors projectionErrors(double x) {
    const int w = 1920, h = 1080;
    Scene scene;
    scene.sourcePath = "test";
    Primitive quad = makePlane(0.5);
    scene.meshes.push_back(Mesh{"quad", {quad}});
    Node object;
    object.mesh = 0;
    object.translation = {x + 0.537, 0.3, -10.0};
    scene.nodes.push_back(object);
    Camera camera;
    camera.projection = Projection::makePerspective(60 * kPi / 180, 0, 0.1, kInfinity);
    camera.lookAt = LookAt{{x, 0, 0}, {x, 0, -1}, {0, 1, 0}};
    scene.cameras.push_back(camera);
    scene.roots.push_back(SceneRoot{"root", {0}, std::nullopt});
    RenderOptions options;
    options.width = w;
    options.height = h;
    auto plan = render::planFrame(scene, options, 0.0);
    EXPECT_TRUE(plan) << plan.error().describe();
    if (!plan) return {1e30, 1e30};
    const gpu::ViewCommands& view = plan->list.views.at(0);
    const gpu::DrawCommand& draw = view.draws.at(0);

    glm::mat4 viewFromModel, clipFromView;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            viewFromModel[c][r] = draw.block.viewFromModel[c * 4 + r];
            clipFromView[c][r] = view.frame.clipFromView.m[c * 4 + r];
        }
    auto toPixels = [&](const glm::dvec4& clip) {
        return glm::dvec2((clip.x / clip.w + 1) * w / 2, (clip.y / clip.w + 1) * h / 2);
    };
    const glm::dmat4 viewFromWorld =
        lookAt(camera.lookAt->eye, camera.lookAt->target, camera.lookAt->up);
    const glm::dmat4 clipExact =
        vulkanClipFromView(camera.projection, double(w) / h, DepthMode::ReversedZ);
    double relative = 0, world = 0;
    for (const glm::vec3& local : quad.positions) {
        const glm::dvec3 worldPoint = glm::dvec3(local) + object.translation;
        const glm::dvec2 exact = toPixels(clipExact * viewFromWorld * glm::dvec4(worldPoint, 1.0));
        // (a) what the GPU computes from Lantern's uploads.
        const glm::vec4 eye = viewFromModel * glm::vec4(local, 1.0f);
        const glm::dvec2 gpu = toPixels(glm::dvec4(clipFromView * eye));
        relative = std::max(relative, glm::length(gpu - exact));
        // (b) world-space floats: vertices pre-transformed to world, view uploaded as float.
        const glm::vec4 worldF(glm::vec3(worldPoint), 1.0f);
        const glm::vec4 eyeF = glm::mat4(viewFromWorld) * worldF;
        const glm::dvec2 naive = toPixels(glm::dvec4(clipFromView * eyeF));
        world = std::max(world, glm::length(naive - exact));
    }
    return {relative, world};
}

TEST(CameraMathPrecision, UploadedMatricesAreCameraRelative) {
    struct Row {
        double x;
        double maxWorldSpacePx; ///< the avoided path: at least this bad (shows the test sees it)
    };
    // float spacing at 1e6 is 6.25 cm and at 1e7 1 m: 10 m ahead at 935 px per unit tangent,
    // world-space floats are off by up to 0.5/10 * 935 = 47 px at 1e7 (x + 0.537 rounds to x + 1).
    const Row rows[] = {{0, 0}, {1e3, 0}, {1e4, 0}, {1e5, 0}, {1e6, 1.0}, {1e7, 10.0}, {1e8, 10.0}};
    for (const Row& r : rows) {
        const Errors e = projectionErrors(r.x);
        std::printf("camera at %8.0e: camera-relative %.2e px, world-space floats %.2e px\n", r.x,
                    e.cameraRelativePx, e.worldSpaceFloatPx);
        EXPECT_LT(e.cameraRelativePx, 1e-3) << "camera at x = " << r.x;
        if (r.maxWorldSpacePx > 0) {
            EXPECT_GT(e.worldSpaceFloatPx, r.maxWorldSpacePx) << "camera at x = " << r.x;
        }
    }
}

} // namespace
