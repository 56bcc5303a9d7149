// Large world coordinates (numerics.md section 2): a scene and its camera moved together far
// from the origin render the same image as at the origin, and a camera 1e6 or 1e7 units out
// stepped by 1 mm moves what it sees by the analytic sub-pixel amount, monotonically. Both
// hold because transforms are composed in double on the CPU and only camera-relative
// matrices reach the GPU (float world coordinates would be 2-3 px off at 1e6 and tens of
// pixels at 1e7: CameraMathPrecision.UploadedMatricesAreCameraRelative).
#include "CameraTestSupport.h"
#include "TestSupport.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Moves everything in the scene by `offset`: the root nodes (the others follow their parents).
Scene translated(Scene scene, const glm::dvec3& offset) {
    for (const SceneRoot& root : scene.roots)
        for (int i : root.nodes) {
            Node& n = scene.nodes[i];
            if (n.matrix)
                (*n.matrix)[3] += glm::dvec4(offset, 0.0);
            else
                n.translation += offset;
        }
    for (Camera& c : scene.cameras)
        if (c.lookAt) {
            c.lookAt->eye += offset;
            c.lookAt->target += offset;
        }
    return scene;
}

RenderOptions smallWithDepth() {
    RenderOptions o;
    o.width = 128;
    o.height = 96;
    o.aovs.depth = true; // to find silhouette edges
    return o;
}

// The built-in spheres: three lit spheres (directional sun, attenuated point lamp, specular),
// a ground plane and a camera node; everything is a root node.
class LargeWorld : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped()) return;
        auto scene = builtinScene("spheres");
        ASSERT_TRUE(scene);
        m_scene = *scene;
        auto image = renderer().render(m_scene, smallWithDepth(), 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        m_reference = std::move(*image);
    }

    test::ImageDifference differenceAt(double distance, Image* out = nullptr) {
        // Along a diagonal, so that every coordinate is large.
        const glm::dvec3 offset = distance * glm::dvec3(1.0, 0.5, -0.75);
        auto image = renderer().render(translated(m_scene, offset), smallWithDepth(), 0.0);
        EXPECT_TRUE(image) << image.error().describe();
        if (!image) return {1, 1, 1e30f};
        EXPECT_EQ(test::countNonFinite(*image), 0u);
        const auto d = test::compareAwayFromEdges(*image, m_reference, 1.0f / 255.0f);
        if (out) *out = std::move(*image);
        return d;
    }

    Scene m_scene;
    Image m_reference;
};

TEST_F(LargeWorld, SceneAndCameraMovedTogetherRenderTheSameImage) {
    for (double distance : {1e3, 1e6, 1e7}) {
        Image image;
        const auto d = differenceAt(distance, &image);
        EXPECT_GT(d.compared, m_reference.pixelCount() / 2) << distance;
        EXPECT_EQ(d.differing, 0u)
            << "moved by " << distance << ": " << d.differing << " pixels differ by more than "
            << "1/255 away from silhouette edges (largest " << d.largest << ")"
            << test::savedAs(image, "moved") << test::savedAs(m_reference, "origin");
    }
}

// Measures how far the scene can move before the image changes (the report's number); the
// assertion is the bound the large-world work set, 1e7.
TEST_F(LargeWorld, ReportsTheLargestTranslationThatStillMatches) {
    double largestMatching = 0.0;
    bool broken = false;
    std::printf("| translation | pixels differing > 1/255 (of compared) | largest difference |\n");
    std::printf("|---|---|---|\n");
    for (int k = 3; k <= 18; ++k) {
        const double distance = std::pow(10.0, k);
        const auto d = differenceAt(distance);
        std::printf("| 1e%d | %zu of %zu | %.2e |\n", k, d.differing, d.compared,
                    double(d.largest));
        if (d.differing == 0 && !broken)
            largestMatching = distance;
        else
            broken = true;
    }
    std::printf("largest translation that still matches: %.0e\n", largestMatching);
    EXPECT_GE(largestMatching, 1e7);
}

// numerics.md LW-2: a 0.25 m ramp quad 10 m ahead of a 10-degree camera (128 x 128: 73.1 px
// per metre at 10 m), the camera stepped sideways 1 mm at a time. The quad's centre must move
// 0.0731 px per step (+-10 %), always the same way, and sit where the analytic projection says
// (+-0.01 px). With world-space floats it would stand still or jump whole metres at 1e7.
TEST_F(LargeWorld, OneMillimetreCameraStepsMoveTheImageByTheAnalyticAmount) {
    const int size = 128;
    const double fovy = 10 * kDeg, distance = 10.0, step = 1e-3;
    const double pxPerMetre = (size / 2.0) / (distance * std::tan(fovy / 2));
    const double expectedStep = -step * pxPerMetre; // camera right: image left
    for (double x : {0.0, 1e6, 1e7}) {
        Scene scene = test::emptyScene();
        glm::dmat4 placement(1.0);
        placement[3] = glm::dvec4(x, 0.0, -distance, 1.0);
        test::addRampQuad(scene, 0.25, 0.25, 0.5f, placement);
        RenderOptions o;
        o.width = o.height = size;
        std::vector<double> centres;
        for (int k = 0; k <= 10; ++k) {
            const double eyeX = x + k * step;
            o.camera.source = CameraSpec::Source::GlDefault;
            o.camera.lookAt = LookAt{{eyeX, 0, 0}, {eyeX, 0, -distance}, {0, 1, 0}};
            o.camera.projection = Projection::makePerspective(fovy, 0.0, 0.1, kInfinity);
            auto image = renderer().render(scene, o, 0.0);
            ASSERT_TRUE(image) << image.error().describe();
            const auto at = test::locateRamp(*image, {0, 0, size, size}, 0.5f, 0.5, 0.5);
            ASSERT_TRUE(at) << "x = " << x << ", step " << k << test::savedAs(*image, "step");
            const double analytic = size / 2.0 + (x - eyeX) * pxPerMetre;
            EXPECT_NEAR(at->x, analytic, 0.01) << "camera at " << x << " + " << k << " mm";
            EXPECT_NEAR(at->y, size / 2.0, 0.01) << "camera at " << x << " + " << k << " mm";
            centres.push_back(at->x);
        }
        double worst = 0.0;
        for (std::size_t k = 1; k < centres.size(); ++k) {
            const double moved = centres[k] - centres[k - 1];
            worst = std::max(worst, std::abs(moved / expectedStep - 1.0));
            EXPECT_LT(moved, 0.0) << "not monotonic at camera " << x << " + " << k << " mm";
            EXPECT_NEAR(moved, expectedStep, 0.1 * std::abs(expectedStep))
                << "camera at " << x << " + " << k << " mm";
        }
        std::printf("camera at %.0e: step %.5f px (analytic %.5f), worst relative error %.2e\n", x,
                    (centres.back() - centres.front()) / 10.0, expectedStep, worst);
    }
}

} // namespace
