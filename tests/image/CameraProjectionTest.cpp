// Every camera kind renders known points where the GL/GLU matrices computed on the CPU put
// them: gluPerspective (finite and infinite far, stretched aspect), glFrustum (off-axis,
// finite and infinite), glOrtho (off-axis, negative near), the GL default camera, a physical
// lens, a rolled gluLookAt, offset viewports and several viewports with their own cameras, in
// both depth schemes. The expected positions come from lantern::project() (gluProject) with
// glClipFromView and lookAt, i.e. GL's conventions; the renderer goes through Vulkan's clip
// space, y flip and viewport, so the test checks the whole conversion.
#include "CameraTestSupport.h"
#include "TestSupport.h"

#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The ramp quads of every case: one 2 x 1.5 quad tilted so it faces +X, +Y and +Z partly (so
// that views from any axis see it), at the origin.
constexpr double kQuadW = 2.0, kQuadH = 1.5;
constexpr float kId = 0.5f;

glm::dmat4 quadPlacement() {
    glm::dmat4 m(1.0);
    m = glm::rotate(m, 35 * kDeg, glm::dvec3(0, 1, 0));
    m = glm::rotate(m, -30 * kDeg, glm::dvec3(1, 0, 0));
    return m;
}

struct ViewCase {
    View view;
    glm::dmat4 viewFromWorld; ///< GL's, from lookAt (identity for the GL default camera)
    Projection projection;    ///< what the view uses (for glClipFromView)
};

struct CameraCase {
    const char* name;
    int width, height;
    std::vector<ViewCase> views;
    DepthMode depth = DepthMode::ReversedZ;
};

// One view with an explicit lookAt and projection.
ViewCase lookAtView(View rect, LookAt la, Projection p) {
    rect.camera.source = CameraSpec::Source::GlDefault;
    rect.camera.lookAt = la;
    rect.camera.projection = p;
    return {rect, lookAt(la.eye, la.target, la.up), p};
}

const LookAt kFront{{1.0, 0.8, 5.0}, {0.1, -0.1, 0.0}, {0, 1, 0}};

std::vector<CameraCase> cases() {
    std::vector<CameraCase> c;
    auto single = [](const char* name, int w, int h, LookAt la, Projection p) {
        return CameraCase{name, w, h, {lookAtView(View{0, 0, w, h, {}}, la, p)}};
    };
    c.push_back(single("perspective 40 deg, viewport aspect", 96, 64, kFront,
                       Projection::makePerspective(40 * kDeg, 0.0, 0.1, 100)));
    c.push_back(single("perspective, infinite far", 96, 64, kFront,
                       Projection::makePerspective(40 * kDeg, 0.0, 0.5, kInfinity)));
    c.push_back(single("perspective, aspect 2 on a square viewport (stretched)", 64, 64, kFront,
                       Projection::makePerspective(45 * kDeg, 2.0, 0.1, 50)));
    c.push_back(single("frustum off-axis", 96, 64, kFront,
                       Projection::makeFrustum(-0.02, 0.05, -0.03, 0.015, 0.1, 60)));
    c.push_back(single("frustum off-axis, infinite far", 96, 64, kFront,
                       Projection::makeFrustum(-0.03, 0.02, -0.02, 0.03, 0.1, kInfinity)));
    c.push_back(single("ortho off-axis, negative near", 96, 64,
                       {{0.3, 0.2, 1.0}, {0.3, 0.2, 0.0}, {0, 1, 0}},
                       Projection::makeOrtho(-2.2, 1.8, -1.1, 1.6, -3, 3)));
    c.push_back(single("physical lens 35 mm on 36 x 24 mm film", 96, 64, kFront,
                       Projection::makeLens(35, 36, 24, 0.1, kInfinity)));
    c.push_back(single("lookAt rolled 30 deg, from below", 96, 64,
                       {{-2.0, -1.0, 5.0}, {0, 0, 0}, {0.5, 0.866, 0}},
                       Projection::makePerspective(50 * kDeg, 0.0, 0.1, 100)));
    c.push_back(single("perspective fovy 1e-4 deg from 1500 km (nearly parallel)", 64, 64,
                       {{0.1, 0.05, 1.5e6}, {0.1, 0.05, 0}, {0, 1, 0}},
                       Projection::makePerspective(1e-4 * kDeg, 0.0, 1.0, kInfinity)));
    // 0.15 from the quad along its normal: the quad fills most of the 170-degree view.
    const glm::dvec3 normal = glm::dvec3(quadPlacement() * glm::dvec4(0, 0, 1, 0));
    c.push_back(single("perspective fovy 170 deg, close up", 64, 64,
                       {0.15 * normal, {0, 0, 0}, {0, 1, 0}},
                       Projection::makePerspective(170 * kDeg, 0.0, 0.001, 100)));
    {
        CameraCase gl{"GL default camera", 64, 64, {}};
        View v{0, 0, 64, 64, {}};
        v.camera.source = CameraSpec::Source::GlDefault;
        gl.views.push_back({v, glm::dmat4(1.0), glDefaultCamera().projection});
        c.push_back(gl);
    }
    c.push_back(CameraCase{"viewport offset inside a larger image",
                           96,
                           96,
                           {lookAtView(View{10, 20, 64, 48, {}}, kFront,
                                       Projection::makePerspective(40 * kDeg, 0.0, 0.1, 100))}});
    c.push_back(CameraCase{
        "three viewports, three cameras",
        128,
        96,
        {lookAtView(View{0, 0, 64, 96, {}}, kFront,
                    Projection::makePerspective(45 * kDeg, 0.0, 0.1, 100)),
         lookAtView(View{64, 48, 64, 48, {}}, {{6, 0.2, 0.1}, {0, 0.2, 0.1}, {0, 1, 0}},
                    Projection::makeOrtho(-1.6, 1.6, -1.2, 1.2, 0.1, 20)),
         lookAtView(View{64, 0, 64, 48, {}}, {{0.2, 5, 0.3}, {0.2, 0, 0.3}, {0, 0, -1}},
                    Projection::makeFrustum(-0.04, 0.04, -0.03, 0.03, 0.1, kInfinity))}});
    CameraCase standard = c.front();
    standard.name = "perspective 40 deg, standard depth";
    standard.depth = DepthMode::Standard;
    c.push_back(standard);
    return c;
}

class CameraProjection : public GpuTest {};

// Known points: a 3 x 3 grid on the quad, away from its border.
TEST_F(CameraProjection, KnownPointsLandWhereTheGlMatricesPutThem) {
    Scene scene = test::emptyScene();
    const glm::dmat4 worldFromQuad = quadPlacement();
    test::addRampQuad(scene, kQuadW, kQuadH, kId, worldFromQuad);
    // Half a pixel is the bound asked of the projections; the estimator is good to ~0.01 px, so a tenth of a
    // pixel still catches a pixel-centre (0.5 px) or y-flip error with a wide margin.
    const double tolerance = 0.1;
    double worst = 0.0;
    for (const CameraCase& cc : cases()) {
        RenderOptions o;
        o.background = glm::vec4(0.0f); // alpha is coverage in these checks
        o.width = cc.width;
        o.height = cc.height;
        o.depth = cc.depth;
        for (const ViewCase& vc : cc.views)
            o.views.push_back(vc.view);
        auto image = renderer().render(scene, o, 0.0);
        ASSERT_TRUE(image) << cc.name << ": " << image.error().describe();
        ASSERT_EQ(test::countNonFinite(*image), 0u) << cc.name;
        int located = 0;
        for (const ViewCase& vc : cc.views) {
            const View& v = vc.view;
            const glm::dmat4 clip =
                glClipFromView(vc.projection, double(v.width) / double(v.height));
            const glm::dvec4 viewport(v.x, v.y, v.width, v.height);
            for (double u : {0.2, 0.5, 0.8})
                for (double t : {0.2, 0.5, 0.8}) {
                    const glm::dvec3 world = glm::dvec3(
                        worldFromQuad * glm::dvec4(test::rampPoint(kQuadW, kQuadH, u, t), 1));
                    const auto window = project(world, vc.viewFromWorld, clip, viewport);
                    ASSERT_TRUE(window) << cc.name;
                    // The case must keep its points in front of the camera and in its view.
                    const glm::dvec4 eye = vc.viewFromWorld * glm::dvec4(world, 1);
                    ASSERT_TRUE(vc.projection.kind == ProjectionKind::Orthographic || eye.z < 0)
                        << cc.name << ": point behind the camera";
                    ASSERT_TRUE(window->x > v.x && window->x < v.x + v.width && window->y > v.y &&
                                window->y < v.y + v.height)
                        << cc.name << ": point (" << u << ", " << t << ") outside the view";
                    const glm::dvec2 expected = test::imageFromWindow(*window, cc.height);
                    const auto got =
                        test::locateRamp(*image, test::rectOfView(v, cc.height), kId, u, t);
                    ASSERT_TRUE(got)
                        << cc.name << ": point (" << u << ", " << t << ") not found; expected at "
                        << expected.x << ", " << expected.y << test::savedAs(*image, cc.name);
                    const double error = glm::length(*got - expected);
                    worst = std::max(worst, error);
                    EXPECT_LT(error, tolerance)
                        << cc.name << ": point (" << u << ", " << t << ") at " << got->x << ", "
                        << got->y << ", expected " << expected.x << ", " << expected.y
                        << test::savedAs(*image, cc.name);
                    ++located;
                }
        }
        EXPECT_EQ(located, 9 * int(cc.views.size())) << cc.name;
    }
    std::printf("largest projection error over all cameras: %.4f px\n", worst);
}

// Nothing is drawn outside a view's viewport (the scissor follows glViewport), and each view's
// camera aspect is its own viewport's.
TEST_F(CameraProjection, ViewsStayInsideTheirViewports) {
    Scene scene = test::emptyScene();
    // A quad far larger than any view: every pixel of every view is covered.
    test::addRampQuad(scene, 1e3, 1e3, kId, glm::dmat4(1.0));
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = 96;
    o.height = 64;
    const Projection p = Projection::makePerspective(60 * kDeg, 0.0, 0.1, kInfinity);
    o.views = {lookAtView(View{4, 8, 40, 30, {}}, kFront, p).view,
               lookAtView(View{50, 30, 30, 20, {}}, kFront, p).view};
    auto image = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(image) << image.error().describe();
    std::size_t inside = 0;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            bool in = false;
            for (const View& v : o.views) {
                const test::PixelRect r = test::rectOfView(v, o.height);
                in |= x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
            }
            const bool covered = image->pixel(x, y)[3] > 0.5f;
            EXPECT_EQ(covered, in) << "pixel " << x << ", " << y;
            inside += in;
        }
    EXPECT_EQ(inside, 40u * 30u + 30u * 20u);
}

// GL's default: counter-clockwise faces are front faces, and back faces are culled. A quad
// whose vertices run counter-clockwise seen from +Z shows from +Z and not from -Z; mirrored
// by a negative scale (its winding reverses on screen) it still shows its front, from +Z.
TEST_F(CameraProjection, FrontFacesAreCounterClockwiseAsInGl) {
    struct Row {
        const char* why;
        glm::dvec3 scale, eye;
        bool visible;
    };
    const Row rows[] = {
        {"seen from the front", {1, 1, 1}, {0, 0, 3}, true},
        {"seen from behind", {1, 1, 1}, {0, 0, -3}, false},
        {"mirrored in x, from the front", {-1, 1, 1}, {0, 0, 3}, true},
        {"mirrored in x, from behind", {-1, 1, 1}, {0, 0, -3}, false},
        {"mirrored in x and y (a rotation), from the front", {-1, -1, 1}, {0, 0, 3}, true},
    };
    for (const Row& r : rows) {
        Scene scene = test::emptyScene();
        Primitive quad = makePlane(1.0); // counter-clockwise seen from +Z, normal +Z
        quad.material = 0;
        Material m = test::unlitMaterial("single-sided");
        m.doubleSided = false;
        scene.materials.push_back(m);
        scene.meshes.push_back(Mesh{"quad", {quad}});
        Node n;
        n.mesh = 0;
        n.scale = r.scale;
        scene.nodes.push_back(n);
        scene.roots[0].nodes.push_back(0);
        RenderOptions o;
        o.background = glm::vec4(0.0f); // alpha is coverage in these checks
        o.width = o.height = 32;
        o.camera.source = CameraSpec::Source::GlDefault;
        o.camera.lookAt = LookAt{r.eye, {0, 0, 0}, {0, 1, 0}};
        o.camera.projection = Projection::makePerspective(40 * kDeg, 0.0, 0.1, 10);
        auto image = renderer().render(scene, o, 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        EXPECT_EQ(test::countCovered(*image) > 0, r.visible) << r.why;
    }
}

} // namespace
