// GL/GLU camera matrices element by element against the reference-page formulas, the Vulkan
// clip-space conversion, GL's matrix-stack order rule and the normal matrix.
#include <lantern/Camera.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace lantern;

constexpr double kPi = 3.14159265358979323846;

// Element (row r, column c) of a column-major matrix.
double at(const glm::dmat4& m, int r, int c) { return m[c][r]; }

void expectMatrix(const glm::dmat4& actual, const double (&rows)[4][4], double tol = 1e-15) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(at(actual, r, c), rows[r][c], tol * std::max(1.0, std::abs(rows[r][c])))
                << "element (" << r << ", " << c << ")";
}

TEST(CameraMath, OrthoMatchesTheGlReferencePage) {
    const double l = -2, r = 3, b = -1, t = 4, n = -5, f = 7;
    const double rows[4][4] = {{2 / (r - l), 0, 0, -(r + l) / (r - l)},
                               {0, 2 / (t - b), 0, -(t + b) / (t - b)},
                               {0, 0, -2 / (f - n), -(f + n) / (f - n)},
                               {0, 0, 0, 1}};
    expectMatrix(ortho(l, r, b, t, n, f), rows);
}

TEST(CameraMath, FrustumMatchesTheGlReferencePage) {
    const double l = -0.3, r = 0.5, b = -0.2, t = 0.4, n = 0.7, f = 90;
    const double rows[4][4] = {{2 * n / (r - l), 0, (r + l) / (r - l), 0},
                               {0, 2 * n / (t - b), (t + b) / (t - b), 0},
                               {0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)},
                               {0, 0, -1, 0}};
    expectMatrix(frustum(l, r, b, t, n, f), rows, 1e-14);
}

TEST(CameraMath, PerspectiveMatchesGluPerspective) {
    const double fovy = 53.0, aspect = 1.7, n = 0.25, f = 400;
    const double ff = 1.0 / std::tan(fovy * kPi / 360.0);
    const double rows[4][4] = {{ff / aspect, 0, 0, 0},
                               {0, ff, 0, 0},
                               {0, 0, (f + n) / (n - f), 2 * f * n / (n - f)},
                               {0, 0, -1, 0}};
    expectMatrix(perspective(fovy, aspect, n, f), rows, 1e-14);
}

TEST(CameraMath, InfiniteFarIsTheLimitOfFiniteFar) {
    const glm::dmat4 inf = perspective(60, 1.5, 0.1, kInfinity);
    const glm::dmat4 far = perspective(60, 1.5, 0.1, 1e15);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(at(inf, r, c), at(far, r, c), 1e-12);
    EXPECT_EQ(at(inf, 2, 2), -1.0);
    EXPECT_EQ(at(inf, 2, 3), -0.2);
}

TEST(CameraMath, LookAtMatchesGluLookAt) {
    // eye (0,0,5) looking at the origin: a pure translation by -5 along z.
    const glm::dmat4 m = lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    const double rows[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, -5}, {0, 0, 0, 1}};
    expectMatrix(m, rows);
    // A general case: the eye goes to the origin, the target onto -Z, up into +Y's half plane.
    const glm::dvec3 eye(1.5, -2, 3), target(-4, 0.5, -1), up(0.2, 1, 0.1);
    const glm::dmat4 v = lookAt(eye, target, up);
    const glm::dvec4 e = v * glm::dvec4(eye, 1), tg = v * glm::dvec4(target, 1);
    EXPECT_NEAR(glm::length(glm::dvec3(e)), 0.0, 1e-14);
    EXPECT_NEAR(tg.x, 0.0, 1e-14);
    EXPECT_NEAR(tg.y, 0.0, 1e-14);
    EXPECT_NEAR(tg.z, -glm::length(target - eye), 1e-13);
    const glm::dvec3 upEye = glm::dmat3(v) * up;
    EXPECT_NEAR(upEye.x, 0.0, 1e-14);
    EXPECT_GT(upEye.y, 0.0);
    const glm::dmat3 rot(v);
    const glm::dmat3 should = glm::transpose(rot) * rot;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(should[i][j], i == j ? 1.0 : 0.0, 1e-15);
}

TEST(CameraMath, ViewportMapsNdcToWindow) {
    const glm::dmat4 m = viewport(10, 20, 640, 480);
    const glm::dvec4 lo = m * glm::dvec4(-1, -1, -1, 1), hi = m * glm::dvec4(1, 1, 1, 1);
    EXPECT_DOUBLE_EQ(lo.x, 10);
    EXPECT_DOUBLE_EQ(lo.y, 20);
    EXPECT_DOUBLE_EQ(lo.z, 0);
    EXPECT_DOUBLE_EQ(hi.x, 650);
    EXPECT_DOUBLE_EQ(hi.y, 500);
    EXPECT_DOUBLE_EQ(hi.z, 1);
}

struct ProjectionCase {
    const char* name;
    Projection projection;
    double aspect;
};

void PrintTo(const ProjectionCase& c, std::ostream* os) { *os << c.name; }

class VulkanClip : public ::testing::TestWithParam<ProjectionCase> {};

TEST_P(VulkanClip, IsTheDocumentedMatrixTimesTheGlOne) {
    const auto& pc = GetParam();
    for (DepthMode mode : {DepthMode::Standard, DepthMode::ReversedZ}) {
        const glm::dmat4 closed = vulkanClipFromView(pc.projection, pc.aspect, mode);
        const glm::dmat4 composed = vulkanFromGlClip(mode) * glClipFromView(pc.projection, pc.aspect);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(at(closed, r, c), at(composed, r, c),
                            1e-12 * std::max(1.0, std::abs(at(composed, r, c))))
                    << pc.name << " element (" << r << ", " << c << ")";
    }
}

TEST_P(VulkanClip, MapsNearAndFarToTheDepthRange) {
    const auto& pc = GetParam();
    const Projection& p = pc.projection;
    auto depthAt = [&](double distance, DepthMode mode) {
        const glm::dvec4 clip = vulkanClipFromView(p, pc.aspect, mode) * glm::dvec4(0, 0, -distance, 1);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(depthAt(p.znear, DepthMode::Standard), 0.0, 1e-12);
    EXPECT_NEAR(depthAt(p.znear, DepthMode::ReversedZ), 1.0, 1e-12);
    if (std::isfinite(p.zfar)) {
        EXPECT_NEAR(depthAt(p.zfar, DepthMode::Standard), 1.0, 1e-12);
        EXPECT_NEAR(depthAt(p.zfar, DepthMode::ReversedZ), 0.0, 1e-12);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Projections, VulkanClip,
    ::testing::Values(
        ProjectionCase{"perspective", Projection::makePerspective(0.8, 0.0, 0.1, 100.0), 1.5},
        ProjectionCase{"perspective-inf", Projection::makePerspective(1.2, 2.0, 0.01, kInfinity), 1.0},
        ProjectionCase{"frustum", Projection::makeFrustum(-0.2, 0.3, -0.1, 0.25, 0.5, 1e4), 1.0},
        ProjectionCase{"ortho", Projection::makeOrtho(-3, 2, -1, 4, -10, 20), 1.0}),
    [](const auto& param) {
        std::string n = param.param.name;
        for (char& c : n)
            if (c == '-') c = '_';
        return n;
    });

TEST(CameraMath, VulkanClipFlipsY) {
    const Projection p = Projection::makeOrtho(-1, 1, -1, 1, -1, 1);
    const glm::dvec4 up = vulkanClipFromView(p, 1.0, DepthMode::Standard) * glm::dvec4(0, 1, 0, 1);
    EXPECT_DOUBLE_EQ(up.y, -1.0);  // GL's +y (top) is Vulkan's -y (row 0 at the top)
}

TEST(CameraMath, TransformStackAppliesTheLastTransformFirst) {
    TransformStack s;
    s.translate({10, 0, 0});
    s.rotate(90, {0, 0, 1});
    // The vertex is rotated first (x -> y), then translated.
    const glm::dvec4 p = s.top() * glm::dvec4(1, 0, 0, 1);
    EXPECT_NEAR(p.x, 10.0, 1e-14);
    EXPECT_NEAR(p.y, 1.0, 1e-14);
    s.push();
    s.scale({2, 2, 2});
    EXPECT_EQ(s.depth(), 2u);
    EXPECT_TRUE(s.pop());
    EXPECT_FALSE(s.pop());
    const glm::dvec4 q = s.top() * glm::dvec4(1, 0, 0, 1);
    EXPECT_NEAR(q.y, 1.0, 1e-14);
}

TEST(CameraMath, FovyFromLens) {
    // A 50 mm lens on 24 mm film height: 2 atan(12/50) = 26.99 degrees.
    EXPECT_NEAR(fovyFromLens(50, 24), 2 * std::atan(12.0 / 50.0) * 180 / kPi, 1e-12);
}

TEST(CameraMath, NormalMatrixIsFiniteForExtremeScales) {
    for (double sz : {1e-300, 1e-20, 1e-6, 1.0, 1e6, 1e20, 1e300}) {
        glm::dmat4 m(1.0);
        m[2][2] = sz;
        const glm::dmat3 n = normalMatrix(m);
        // A normal of the surface z = x transforms to the normal of z = sz * x.
        auto unit = [](glm::dvec3 v) {  // normalise without overflow: scale by the largest first
            v /= std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
            return glm::normalize(v);
        };
        const glm::dvec3 t = unit(n * glm::dvec3(-1, 0, 1));
        const glm::dvec3 expected = unit(glm::dvec3(-sz, 0, 1));
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(t[i], expected[i], 1e-12) << "scale " << sz;
    }
    glm::dmat4 flat(1.0);
    flat[2][2] = 0.0;  // a zero scale: a disc's normal is +-z, never NaN
    const glm::dvec3 n = normalMatrix(flat) * glm::dvec3(0.3, 0.4, 0.866);
    EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    EXPECT_NEAR(std::abs(glm::normalize(n).z), 1.0, 1e-12);
    glm::dmat4 mirror(1.0);
    mirror[0][0] = -1.0;
    EXPECT_NEAR((normalMatrix(mirror) * glm::dvec3(1, 0, 0)).x, -1.0, 1e-15);
}

TEST(CameraMath, ChecksRefuseDegenerateInput) {
    EXPECT_FALSE(checkLookAt({{0, 0, 0}, {0, 0, 0}, {0, 1, 0}}, "x"));
    EXPECT_FALSE(checkLookAt({{0, 0, 0}, {0, 0, -1}, {0, 0, 0}}, "x"));
    EXPECT_FALSE(checkLookAt({{0, 0, 0}, {0, 1, 0}, {0, 2, 0}}, "x"));
    EXPECT_TRUE(checkLookAt({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, "x"));
    EXPECT_FALSE(checkProjection(Projection::makePerspective(0.0, 1, 0.1, 10), "p"));
    EXPECT_FALSE(checkProjection(Projection::makePerspective(kPi, 1, 0.1, 10), "p"));
    EXPECT_FALSE(checkProjection(Projection::makePerspective(1, 1, 0.0, 10), "p"));
    EXPECT_FALSE(checkProjection(Projection::makePerspective(1, 1, 1, 1), "p"));
    EXPECT_FALSE(checkProjection(Projection::makeFrustum(1, 1, -1, 1, 1, 10), "p"));
    EXPECT_FALSE(checkProjection(Projection::makeOrtho(-1, 1, 2, 2, -1, 1), "p"));
    EXPECT_FALSE(checkProjection(Projection::makeOrtho(-1, 1, -1, 1, 3, 3), "p"));
    EXPECT_FALSE(checkProjection(Projection::makeOrtho(-1, 1, -1, 1, 0, kInfinity), "p"));
    EXPECT_TRUE(checkProjection(Projection::makePerspective(1, 1, 1e-6, 1e12), "p"));
    EXPECT_TRUE(checkProjection(Projection::makeOrtho(-1, 1, -1, 1, 5, -5), "p"));
    const auto e = checkProjection(Projection::makeFrustum(-1, 1, -1, 1, -1, 10), "--frustum");
    ASSERT_FALSE(e);
    EXPECT_EQ(e.error().object, "--frustum");
    EXPECT_NE(e.error().message.find("near"), std::string::npos);
}

} // namespace
