// Transforms at the extremes, rendered: normals under non-uniform scales from 1e-6 to 1e6 and
// a zero scale (no NaN; the eye-space normal AOV points where the inverse transpose says),
// uniform scales of 1e-20 and 1e20 with the camera scaled alike (the same image as at scale
// 1), and extreme but valid projections (fovy 1e-4 and 179.9 degrees, aspect 1e-4 and 1e4,
// near 1e-6 with far 1e12), which render without NaN or Inf.
#include "CameraTestSupport.h"
#include "TestSupport.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A shiny sphere lit by a directional light (scale-free: no positions in the lighting).
test::SimpleScene litSphere() {
    test::SimpleScene s;
    s.primitive = makeSphere(1.0, 48, 24);
    s.material.front.diffuse = {0.6, 0.3, 0.2, 1.0};
    s.material.front.specular = {0.5, 0.5, 0.5};
    s.material.front.shininess = 40;
    Light sun;
    sun.type = LightType::Directional;
    glm::dmat4 sunFrom = glm::rotate(glm::dmat4(1.0), -30 * kDeg, glm::dvec3(1, 1, 0));
    s.lights.push_back({sun, sunFrom});
    return s;
}

RenderOptions withAovs(int size = 64) {
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = o.height = size;
    o.aovs.depth = true;
    o.aovs.normal = true;
    return o;
}

glm::dvec3 normalAt(const Image& image, int x, int y) {
    const float* n = image.normal.data() + (std::size_t(y) * image.width + x) * 3;
    return {n[0], n[1], n[2]};
}

// Pixels whose 3 x 3 neighbourhood is all covered (away from the rim, where the faceted
// sphere's own normals vary fastest).
template <typename F> void forEachInteriorPixel(const Image& image, F f) {
    for (int y = 1; y + 1 < image.height; ++y)
        for (int x = 1; x + 1 < image.width; ++x) {
            bool interior = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    interior &= image.pixel(x + dx, y + dy)[3] > 0.5f;
            if (interior) f(x, y);
        }
}

class CameraTransform : public GpuTest {};

TEST_F(CameraTransform, UniformScalesOf1e20And1eMinus20RenderLikeScaleOne) {
    auto build = [](double scale) {
        test::SimpleScene s = litSphere();
        s.model = glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
        s.lookAt = LookAt{{0, 0, 4 * scale}, {0, 0, 0}, {0, 1, 0}};
        s.projection = Projection::makePerspective(40 * kDeg, 0.0, 0.1 * scale, kInfinity);
        return s.build();
    };
    auto reference = renderer().render(build(1.0), withAovs(), 0.0);
    ASSERT_TRUE(reference) << reference.error().describe();
    ASSERT_GT(test::countCovered(*reference), 500u);
    for (double scale : {1e-20, 1e20}) {
        auto image = renderer().render(build(scale), withAovs(), 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        EXPECT_EQ(test::countNonFinite(*image), 0u) << scale;
        EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u) << scale;
        const auto d = test::compareAwayFromEdges(*image, *reference, 1.0f / 255.0f);
        EXPECT_EQ(d.differing, 0u)
            << "scale " << scale << ": largest difference " << d.largest
            << test::savedAs(*image, "scaled") << test::savedAs(*reference, "reference");
        double worst = 0;
        forEachInteriorPixel(*reference, [&](int x, int y) {
            worst =
                std::max(worst, glm::length(normalAt(*image, x, y) - normalAt(*reference, x, y)));
        });
        EXPECT_LT(worst, 1e-5) << "scale " << scale << ": normals differ";
    }
}

struct NonUniformRow {
    const char* why;
    glm::dvec3 scale;
    glm::dvec3 eye; ///< the camera looks from here at the origin
    int flatAxis;   ///< eye-space axis along which every interior normal must point (-1: none)
    int zeroAxis;   ///< eye-space axis that every interior normal must be perpendicular to
    double tolerance;
};

// The eye sits on a world axis, so eye-space axes are world axes (x right, y up, z towards
// the eye). A sphere flattened along the view axis is a disc whose normal is the view axis;
// one stretched along x by 1e6 is a cylinder whose normals have no x.
const NonUniformRow kNonUniform[] = {
    {"zero scale on z, seen from +z: a disc", {1, 1, 0}, {0, 0, 4}, 2, -1, 1e-6},
    {"1e-6 on z, seen from +z: nearly a disc", {1, 1, 1e-6}, {0, 0, 4}, 2, -1, 1e-4},
    {"zero scale on x, seen from +x", {0, 1, 1}, {4, 0, 0}, 2, -1, 1e-6},
    {"1e-6 on x, 1e6 on z, seen from +x", {1e-6, 1, 1e6}, {4, 0, 0}, 2, -1, 1e-4},
    {"1e6 on x, seen from +z: a cylinder", {1e6, 1, 1}, {0, 0, 4}, -1, 0, 1e-4},
    {"1e6 on y, 1e-6 on z, seen from +z", {1, 1e6, 1e-6}, {0, 0, 4}, 2, -1, 1e-4},
    {"1e6 on y, seen from +z: a cylinder", {1, 1e6, 1}, {0, 0, 4}, -1, 1, 1e-4},
};

TEST_F(CameraTransform, NonUniformAndZeroScalesGiveInverseTransposeNormals) {
    for (const NonUniformRow& row : kNonUniform) {
        test::SimpleScene s = litSphere();
        s.model = glm::scale(glm::dmat4(1.0), row.scale);
        s.lookAt = LookAt{row.eye, {0, 0, 0}, {0, 1, 0}};
        auto image = renderer().render(s.build(), withAovs(), 0.0);
        ASSERT_TRUE(image) << row.why << ": " << image.error().describe();
        EXPECT_EQ(test::countNonFinite(*image), 0u) << row.why;
        EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u) << row.why;
        std::size_t interior = 0;
        double worst = 0;
        forEachInteriorPixel(*image, [&](int x, int y) {
            const glm::dvec3 n = normalAt(*image, x, y);
            ++interior;
            EXPECT_NEAR(glm::length(n), 1.0, 1e-5) << row.why << " at " << x << ", " << y;
            if (row.flatAxis >= 0) worst = std::max(worst, 1.0 - n[row.flatAxis]);
            if (row.zeroAxis >= 0) worst = std::max(worst, std::abs(n[row.zeroAxis]));
        });
        EXPECT_GT(interior, 200u) << row.why << test::savedAs(*image, row.why);
        EXPECT_LT(worst, row.tolerance) << row.why << test::savedAs(*image, row.why);
    }
}

TEST_F(CameraTransform, ExtremeButValidProjectionsRenderWithoutNanOrInf) {
    struct Row {
        const char* why;
        Projection projection;
        LookAt lookAt;
        int width, height;
        bool visible; ///< the spheres must show
    };
    const LookAt front{{0, 1, 9}, {0, 0, 0}, {0, 1, 0}};
    // With a nearly 180-degree field only what lies nearly 90 degrees off the axis reaches a
    // pixel centre: the ground just below an eye half a unit above it (fovy 179.9), or the
    // spheres just beside an eye between two of them (aspect 1e4: 179.98 degrees across).
    const LookAt low{{0, -0.5, 4}, {0, -0.5, 3}, {0, 1, 0}};
    const LookAt between{{1.2, 0, 0}, {1.2, 0, -1}, {0, 1, 0}};
    const Row rows[] = {
        {"fovy 1e-4 deg", Projection::makePerspective(1e-4 * kDeg, 0, 0.1, kInfinity), front, 64,
         64, true},
        {"fovy 179.9 deg", Projection::makePerspective(179.9 * kDeg, 0, 0.01, kInfinity), low, 64,
         64, true},
        {"aspect 1e-4 (viewport 64 x 64)", Projection::makePerspective(40 * kDeg, 1e-4, 0.1, 100),
         front, 64, 64, true},
        {"aspect 1e4 (viewport 64 x 64)", Projection::makePerspective(40 * kDeg, 1e4, 0.001, 100),
         between, 64, 64, true},
        {"viewport aspect 256 x 1", Projection::makePerspective(40 * kDeg, 0, 0.1, 100), front, 256,
         1, false},
        {"near 1e-6, far 1e12", Projection::makePerspective(40 * kDeg, 0, 1e-6, 1e12), front, 64,
         64, true},
        {"frustum near 1e-6, far 1e12",
         Projection::makeFrustum(-4e-7, 4e-7, -3e-7, 3e-7, 1e-6, 1e12), front, 64, 48, true},
        {"ortho 1e-6 deep", Projection::makeOrtho(-3, 3, -2, 2, 8.0, 8.000001), front, 64, 48,
         false},
    };
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    for (const Row& r : rows) {
        ASSERT_TRUE(checkProjection(r.projection, r.why)) << r.why;
        RenderOptions o;
        o.background = glm::vec4(0.0f); // alpha is coverage in these checks
        o.width = r.width;
        o.height = r.height;
        o.aovs.depth = o.aovs.normal = true;
        o.camera.projection = r.projection;
        o.camera.lookAt = r.lookAt;
        for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
            o.depth = mode;
            auto image = renderer().render(*scene, o, 0.0);
            ASSERT_TRUE(image) << r.why << ": " << image.error().describe();
            EXPECT_EQ(test::countNonFinite(*image), 0u) << r.why;
            EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u) << r.why;
            if (r.visible) {
                EXPECT_GT(test::countCovered(*image), 0u)
                    << r.why << " (" << toString(mode) << ")" << test::savedAs(*image, r.why);
            }
        }
    }
}

} // namespace
