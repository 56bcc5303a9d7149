// GL/GLU camera matrices element by element against the reference-page formulas, the Vulkan
// clip-space conversion, GL's matrix-stack order rule and the normal matrix.
#include <lantern/Camera.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

TEST(CameraMath, LookAtMatchesTheGluReferencePageElementByElement) {
    // gluLookAt: F = target - eye, f = F/|F|, UP' = up/|up|, s = f x UP', u = (s/|s|) x f,
    // M = [s/|s|; u; -f] (rows), result M * translate(-eye).
    const glm::dvec3 eye(1.5, -2, 3), target(-4, 0.5, -1), up(0.2, 1, 0.1);
    const glm::dvec3 f = glm::normalize(target - eye);
    const glm::dvec3 s = glm::normalize(glm::cross(f, glm::normalize(up)));
    const glm::dvec3 u = glm::cross(s, f);
    const double rows[4][4] = {{s.x, s.y, s.z, -glm::dot(s, eye)},
                               {u.x, u.y, u.z, -glm::dot(u, eye)},
                               {-f.x, -f.y, -f.z, glm::dot(f, eye)},
                               {0, 0, 0, 1}};
    expectMatrix(lookAt(eye, target, up), rows, 1e-15);
    // The same view 1e7 units away: only the translation column changes, by -R * offset.
    const glm::dvec3 offset(1e7, -3e6, 5e6);
    const glm::dmat4 far = lookAt(eye + offset, target + offset, up);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(at(far, r, c), rows[r][c], 1e-15);
        const glm::dvec3 row(rows[r][0], rows[r][1], rows[r][2]);
        EXPECT_NEAR(at(far, r, 3), rows[r][3] - glm::dot(row, offset), 1e-8);
    }
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

TEST(CameraMath, InfiniteFrustumIsTheLimitOfFiniteFrustum) {
    const double l = -0.3, r = 0.5, b = -0.2, t = 0.4, n = 0.7;
    const double rows[4][4] = {{2 * n / (r - l), 0, (r + l) / (r - l), 0},
                               {0, 2 * n / (t - b), (t + b) / (t - b), 0},
                               {0, 0, -1, -2 * n},
                               {0, 0, -1, 0}};
    expectMatrix(frustum(l, r, b, t, n, kInfinity), rows, 1e-15);
    const glm::dmat4 far = frustum(l, r, b, t, n, 1e16);
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(at(far, row, c), rows[row][c], 1e-15);
}

TEST(CameraMath, ViewportWithDepthRangeMatchesGlViewport) {
    // glViewport(x, y, w, h) + glDepthRange(n, f): x_w = (x_ndc + 1) w/2 + x, same for y,
    // z_w = z_ndc (f - n)/2 + (f + n)/2.
    const double x = 7, y = -3, w = 320, h = 200, n = 0.25, f = 0.75;
    const double rows[4][4] = {{w / 2, 0, 0, x + w / 2},
                               {0, h / 2, 0, y + h / 2},
                               {0, 0, (f - n) / 2, (f + n) / 2},
                               {0, 0, 0, 1}};
    expectMatrix(viewport(x, y, w, h, n, f), rows);
}

TEST(CameraMath, VulkanFromGlClipIsTheDocumentedMatrix) {
    const double standard[4][4] = {{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, 0.5, 0.5}, {0, 0, 0, 1}};
    const double reversed[4][4] = {{1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -0.5, 0.5}, {0, 0, 0, 1}};
    expectMatrix(vulkanFromGlClip(DepthMode::Standard), standard, 0.0);
    expectMatrix(vulkanFromGlClip(DepthMode::ReversedZ), reversed, 0.0);
}

TEST(CameraMath, GlDefaultCameraIsTheOrthographicUnitCube) {
    const Camera c = glDefaultCamera();
    ASSERT_TRUE(c.lookAt);
    const double identity[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    expectMatrix(lookAt(c.lookAt->eye, c.lookAt->target, c.lookAt->up), identity, 0.0);
    // glOrtho(-1, 1, -1, 1, -1, 1) is diag(1, 1, -1, 1): GL's initial projection flips z only.
    const double projection[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -1, 0}, {0, 0, 0, 1}};
    expectMatrix(glClipFromView(c.projection, 1.0), projection, 0.0);
    EXPECT_TRUE(checkProjection(c.projection, "default"));
}

TEST(CameraMath, LensGivesTheFieldOfViewAndAspectOfItsFilm) {
    struct Row {
        double focal, filmW, filmH, yfovDeg, aspect;
        const char* why;
    };
    const Row rows[] = {
        {50, 36, 24, 2 * std::atan(12.0 / 50.0) * 180 / kPi, 1.5, "35 mm still, normal lens"},
        {24, 36, 24, 2 * std::atan(12.0 / 24.0) * 180 / kPi, 1.5, "wide angle"},
        {35, 0, 24, 2 * std::atan(12.0 / 35.0) * 180 / kPi, 0.0, "film width 0: viewport aspect"},
        {12, 24, 24, 90.0, 1.0, "f = h/2 is exactly 90 degrees"},
    };
    for (const Row& r : rows) {
        const Projection p = Projection::makeLens(r.focal, r.filmW, r.filmH, 0.1, kInfinity);
        EXPECT_EQ(p.kind, ProjectionKind::Perspective) << r.why;
        EXPECT_NEAR(p.yfov * 180 / kPi, r.yfovDeg, 1e-12) << r.why;
        EXPECT_NEAR(p.aspect, r.aspect, 1e-15) << r.why;
        EXPECT_TRUE(checkProjection(p, "lens")) << r.why;
    }
    // A zero focal length is a 180-degree field of view: refused, fovy named.
    const auto e = checkProjection(Projection::makeLens(0, 36, 24, 0.1, 10), "lens");
    ASSERT_FALSE(e);
    EXPECT_NE(e.error().message.find("fovy"), std::string::npos);
}

TEST(CameraMath, ProjectAndUnProjectFollowGlu) {
    const glm::dmat4 view = lookAt({1, 2, 3}, {0, 0, -1}, {0, 1, 0});
    const glm::dmat4 proj = perspective(45, 1.25, 0.5, 100);
    const glm::dvec4 vp(10, 20, 200, 160);
    const glm::dvec3 object(0.3, -0.2, -2.0);
    const auto win = project(object, view, proj, vp);
    ASSERT_TRUE(win);
    // gluProject's formulas, written out.
    const glm::dvec4 clip = proj * view * glm::dvec4(object, 1);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    EXPECT_NEAR(win->x, vp.x + vp.z * (ndc.x + 1) / 2, 1e-12);
    EXPECT_NEAR(win->y, vp.y + vp.w * (ndc.y + 1) / 2, 1e-12);
    EXPECT_NEAR(win->z, (ndc.z + 1) / 2, 1e-15);
    const auto back = unProject(*win, view, proj, vp);
    ASSERT_TRUE(back);
    EXPECT_NEAR(glm::length(*back - object), 0.0, 1e-12);
    // The eye itself has w = 0: no image.
    EXPECT_FALSE(project({1, 2, 3}, view, proj, vp));
    EXPECT_FALSE(unProject(*win, view, glm::dmat4(0.0), vp));
}

TEST(CameraMath, TransformStackRotateMatchesGlRotate) {
    // glRotate(a, x, y, z) reference page, with (x, y, z) normalised, c = cos a, s = sin a.
    const double angle = 37.0;
    const glm::dvec3 axis = glm::normalize(glm::dvec3(1, -2, 0.5));
    const double c = std::cos(angle * kPi / 180), s = std::sin(angle * kPi / 180);
    const double x = axis.x, y = axis.y, z = axis.z;
    const double rows[4][4] = {
        {x * x * (1 - c) + c, x * y * (1 - c) - z * s, x * z * (1 - c) + y * s, 0},
        {y * x * (1 - c) + z * s, y * y * (1 - c) + c, y * z * (1 - c) - x * s, 0},
        {x * z * (1 - c) - y * s, y * z * (1 - c) + x * s, z * z * (1 - c) + c, 0},
        {0, 0, 0, 1}};
    TransformStack st;
    st.rotate(angle, {1, -2, 0.5});  // not normalised: glRotate normalises
    expectMatrix(st.top(), rows);
}

TEST(CameraMath, TransformStackComposesLikeGl) {
    // glLoadIdentity; gluLookAt; glTranslate; glRotate; glScale; glMultMatrix: the product
    // V * T * R * S * M, so M acts first on a vertex and the lookAt last.
    glm::dmat4 extra(1.0);
    extra[1][0] = 0.25;  // a shear: row 0, column 1
    TransformStack st;
    st.lookAt({0, 1, 5}, {0, 0, 0}, {0, 1, 0});
    st.translate({1, 2, 3});
    st.rotate(90, {0, 1, 0});
    st.scale({2, 3, 4});
    st.multiply(extra);
    glm::dmat4 t(1.0), r(0.0), sc(1.0);
    t[3] = glm::dvec4(1, 2, 3, 1);
    r[0][2] = -1, r[1][1] = 1, r[2][0] = 1, r[3][3] = 1;  // 90 degrees about +y: x -> -z
    sc[0][0] = 2, sc[1][1] = 3, sc[2][2] = 4;
    const glm::dmat4 expected = lookAt({0, 1, 5}, {0, 0, 0}, {0, 1, 0}) * t * r * sc * extra;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            EXPECT_NEAR(at(st.top(), row, col), at(expected, row, col), 1e-15);
    // push copies the top; pop restores it; load and loadIdentity replace only the top.
    const glm::dmat4 saved = st.top();
    st.push();
    st.loadIdentity();
    EXPECT_EQ(st.top(), glm::dmat4(1.0));
    st.load(extra);
    EXPECT_EQ(st.top(), extra);
    EXPECT_TRUE(st.pop());
    EXPECT_EQ(st.top(), saved);
}

TEST(CameraMath, DepthModeNames) {
    EXPECT_STREQ(toString(DepthMode::ReversedZ), "reversed");
    EXPECT_STREQ(toString(DepthMode::Standard), "standard");
    EXPECT_EQ(parseDepthMode("reversed"), DepthMode::ReversedZ);
    EXPECT_EQ(parseDepthMode("standard"), DepthMode::Standard);
    EXPECT_FALSE(parseDepthMode("reversed-z"));
}

// Every refusal of part 4 of the camera issue, one row each, with the word the message must
// contain; and the extreme but valid values, which must pass.
TEST(CameraMath, ChecksRefuseWithAClearMessage) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double deg = kPi / 180;
    struct Row {
        const char* why;
        Projection p;
        const char* mention;  ///< nullptr: valid
    };
    const Row rows[] = {
        {"near 0, perspective", Projection::makePerspective(1, 1, 0, 10), "near"},
        {"near < 0, perspective", Projection::makePerspective(1, 1, -1, 10), "near"},
        {"near 0, frustum", Projection::makeFrustum(-1, 1, -1, 1, 0, 10), "near"},
        {"far == near, perspective", Projection::makePerspective(1, 1, 2, 2), "far"},
        {"far < near, perspective", Projection::makePerspective(1, 1, 2, 1), "far"},
        {"far == near, frustum", Projection::makeFrustum(-1, 1, -1, 1, 2, 2), "far"},
        {"far == near, ortho", Projection::makeOrtho(-1, 1, -1, 1, 2, 2), "far == near"},
        {"left == right, frustum", Projection::makeFrustum(1, 1, -1, 1, 1, 2), "left == right"},
        {"left == right, ortho", Projection::makeOrtho(1, 1, -1, 1, 1, 2), "left == right"},
        {"bottom == top, frustum", Projection::makeFrustum(-1, 1, 3, 3, 1, 2), "bottom == top"},
        {"bottom == top, ortho", Projection::makeOrtho(-1, 1, 3, 3, 1, 2), "bottom == top"},
        {"fovy 0", Projection::makePerspective(0, 1, 0.1, 10), "fovy"},
        {"fovy 180", Projection::makePerspective(180 * deg, 1, 0.1, 10), "fovy"},
        {"fovy < 0", Projection::makePerspective(-10 * deg, 1, 0.1, 10), "fovy"},
        {"fovy > 180", Projection::makePerspective(200 * deg, 1, 0.1, 10), "fovy"},
        {"aspect < 0", Projection::makePerspective(1, -1, 0.1, 10), "aspect"},
        {"fovy NaN", Projection::makePerspective(nan, 1, 0.1, 10), "fovy"},
        {"aspect inf", Projection::makePerspective(1, kInfinity, 0.1, 10), "aspect"},
        {"near NaN", Projection::makePerspective(1, 1, nan, 10), "near"},
        {"near inf", Projection::makeFrustum(-1, 1, -1, 1, kInfinity, kInfinity), "near"},
        {"far NaN", Projection::makePerspective(1, 1, 0.1, nan), "far"},
        {"far -inf", Projection::makePerspective(1, 1, 0.1, -kInfinity), "far"},
        {"ortho far inf", Projection::makeOrtho(-1, 1, -1, 1, 0, kInfinity), "far"},
        {"left NaN", Projection::makeOrtho(nan, 1, -1, 1, 0, 1), "finite"},
        {"top inf", Projection::makeFrustum(-1, 1, -1, kInfinity, 1, 2), "finite"},
        {"width overflows", Projection::makeOrtho(-1e308, 1e308, -1, 1, 0, 1), "too large"},
        {"depth overflows", Projection::makeOrtho(-1, 1, -1, 1, -1e308, 1e308), "too deep"},
        {"width 1e-40 (float overflow)", Projection::makeFrustum(0, 1e-40, -1, 1, 1, 2), "overflows"},
        {"fovy 1e-40 deg", Projection::makePerspective(1e-40 * deg, 1, 0.1, 10), "overflows"},
        {"near 1e-40 (flushes to 0)", Projection::makePerspective(1, 1, 1e-40, 10), "underflows"},
        {"ortho 1e40 wide", Projection::makeOrtho(-1e40, 1e40, -1, 1, 0, 1), "underflows"},
        // Extreme but valid.
        {"fovy 1e-4 deg", Projection::makePerspective(1e-4 * deg, 1, 0.1, 10), nullptr},
        {"fovy 179.9 deg", Projection::makePerspective(179.9 * deg, 1, 0.1, 10), nullptr},
        {"aspect 1e-4", Projection::makePerspective(1, 1e-4, 0.1, 10), nullptr},
        {"aspect 1e4", Projection::makePerspective(1, 1e4, 0.1, 10), nullptr},
        {"near 1e-6 far 1e12", Projection::makePerspective(1, 1, 1e-6, 1e12), nullptr},
        {"near 1e-6 far inf", Projection::makeFrustum(-1e-6, 1e-6, -1e-6, 1e-6, 1e-6, kInfinity), nullptr},
        {"aspect 0 (the viewport's)", Projection::makePerspective(1, 0, 0.1, 10), nullptr},
        {"ortho near > far (GL allows)", Projection::makeOrtho(-1, 1, -1, 1, 5, -5), nullptr},
        {"ortho negative near", Projection::makeOrtho(-1, 1, -1, 1, -1e6, 1e6), nullptr},
    };
    for (const Row& r : rows) {
        const auto result = checkProjection(r.p, "--camera-object");
        if (!r.mention) {
            EXPECT_TRUE(result) << r.why << ": " << result.error().message;
            continue;
        }
        ASSERT_FALSE(result) << r.why;
        EXPECT_EQ(result.error().code, ErrorCode::InvalidInput) << r.why;
        EXPECT_EQ(result.error().object, "--camera-object") << r.why;
        EXPECT_NE(result.error().message.find(r.mention), std::string::npos)
            << r.why << ": \"" << result.error().message << "\" should mention " << r.mention;
    }

    struct LookAtRow {
        const char* why;
        LookAt la;
        const char* mention;
    };
    const LookAtRow lookAts[] = {
        {"eye == target", {{1, 2, 3}, {1, 2, 3}, {0, 1, 0}}, "same point"},
        {"eye == target at 1e7", {{1e7, 0, 0}, {1e7, 0, 0}, {0, 1, 0}}, "same point"},
        {"up zero", {{0, 0, 0}, {0, 0, -1}, {0, 0, 0}}, "zero length"},
        {"up along view", {{0, 0, 0}, {0, 0, -1}, {0, 0, -3}}, "parallel"},
        {"up against view", {{0, 0, 0}, {0, 0, -1}, {0, 0, 2}}, "parallel"},
        {"up nearly along view", {{0, 0, 0}, {0, 0, -1}, {1e-14, 0, 1}}, "parallel"},
        {"eye NaN", {{nan, 0, 0}, {0, 0, -1}, {0, 1, 0}}, "non-finite"},
        {"target inf", {{0, 0, 0}, {0, 0, -kInfinity}, {0, 1, 0}}, "non-finite"},
        {"up NaN", {{0, 0, 0}, {0, 0, -1}, {0, nan, 0}}, "non-finite"},
        {"distance overflows", {{-1e308, 0, 0}, {1e308, 0, 0}, {0, 1, 0}}, "too far apart"},
        {"tiny up is a direction", {{0, 0, 0}, {0, 0, -1}, {0, 1e-200, 0}}, nullptr},
        {"huge up is a direction", {{0, 0, 0}, {0, 0, -1}, {1e300, 1e300, 0}}, nullptr},
        {"eye at 1e7, 1 mm view", {{1e7, 0, 0}, {1e7 + 1e-3, 0, 0}, {0, 1, 0}}, nullptr},
    };
    for (const LookAtRow& r : lookAts) {
        const auto result = checkLookAt(r.la, "--look-at");
        if (!r.mention) {
            EXPECT_TRUE(result) << r.why << ": " << result.error().message;
            const glm::dmat4 v = lookAt(r.la.eye, r.la.target, r.la.up);
            for (int c = 0; c < 4; ++c)
                for (int row = 0; row < 4; ++row) EXPECT_TRUE(std::isfinite(v[c][row])) << r.why;
            continue;
        }
        ASSERT_FALSE(result) << r.why;
        EXPECT_EQ(result.error().object, "--look-at") << r.why;
        EXPECT_NE(result.error().message.find(r.mention), std::string::npos)
            << r.why << ": \"" << result.error().message << "\" should mention " << r.mention;
    }
}

} // namespace

namespace {

TEST(CameraMath, FitViewportAspectWidensTheBoxAboutItsCentre) {
    lantern::Projection p = lantern::Projection::makeOrtho(0, 16, 0, 19.2, -10, 10);
    // Off by default: the box is used as given.
    EXPECT_EQ(lantern::fittedProjection(p, 16.0 / 9.0).right, 16.0);
    p.fitViewportAspect = true;
    const auto wide = lantern::fittedProjection(p, 16.0 / 9.0);
    EXPECT_DOUBLE_EQ(wide.top - wide.bottom, 19.2);
    EXPECT_NEAR((wide.right - wide.left) / (wide.top - wide.bottom), 16.0 / 9.0, 1e-12);
    EXPECT_NEAR(0.5 * (wide.left + wide.right), 8.0, 1e-12);
    const auto tall = lantern::fittedProjection(p, 0.5);
    EXPECT_DOUBLE_EQ(tall.right - tall.left, 16.0);
    EXPECT_NEAR((tall.right - tall.left) / (tall.top - tall.bottom), 0.5, 1e-12);
    EXPECT_NEAR(0.5 * (tall.bottom + tall.top), 9.6, 1e-12);
    // The matrix uses the fitted box.
    const glm::dmat4 m = lantern::glClipFromView(p, 16.0 / 9.0);
    EXPECT_NEAR(m[0][0], 2.0 / (wide.right - wide.left), 1e-15);
}

} // namespace
