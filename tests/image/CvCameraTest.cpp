// Computer-vision cameras rendered through the API: known 3D points appear where OpenCV's
// K[R|t] puts them (ramp quads located to ~0.01 px, and the coverage centroids of small bright
// squares within half a pixel) for an off-centre principal point and fx != fy; the same camera
// given as OpenCV's world_to_camera or glTF's camera_to_world renders the identical image; the
// depth AOV is the distance to the camera plane for orthographic and pinhole intrinsics alike;
// intrinsics for another image size are refused.
#include "CameraTestSupport.h"
#include "TestSupport.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstdio>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// 160 x 120 pixels, principal point well off the centre (79.5, 59.5), fx != fy.
Intrinsics intrinsics() {
    Intrinsics k;
    k.width = 160, k.height = 120;
    k.fx = 150.0, k.fy = 118.0, k.cx = 71.3, k.cy = 64.8;
    k.znear = 0.1, k.zfar = 100.0;
    return k;
}

// OpenCV's world_to_camera: a camera turned 20 degrees about a skew axis, 0.4 to the side.
glm::dmat4 worldToCamera() {
    glm::dmat4 w = glm::rotate(glm::dmat4(1.0), 20 * kDeg, glm::normalize(glm::dvec3(0.3, 1, 0.2)));
    w[3] = glm::dvec4(0.4, -0.1, 0.5, 1.0);
    return w;
}

// The world point whose OpenCV camera coordinates are `c`.
glm::dvec3 worldOf(const glm::dmat4& w2c, const glm::dvec3& c) {
    return glm::dvec3(glm::inverse(w2c) * glm::dvec4(c, 1.0));
}

// u = fx x / z + cx, v = fy y / z + cy with (x, y, z) = [R | t] X; OpenCV's pixel centres are at
// integers, the test images' at half-integers: image coordinates are (u + 0.5, v + 0.5).
glm::dvec2 expectedImagePoint(const Intrinsics& k, const glm::dmat4& w2c, const glm::dvec3& X) {
    const glm::dvec3 c = glm::dvec3(w2c * glm::dvec4(X, 1.0));
    return {k.fx * c.x / c.z + k.cx + 0.5, k.fy * c.y / c.z + k.cy + 0.5};
}

// A quad centred on world point X, parallel to the image plane (its normal towards the camera).
glm::dmat4 facingCamera(const glm::dmat4& w2c, const glm::dvec3& X) {
    glm::dmat4 m = glm::inverse(viewFromPose(w2c, PoseConvention::OpenCV));
    m[3] = glm::dvec4(X, 1.0);
    return m;
}

// OpenCV camera coordinates of the known points: spread over the image, 2 to 6 units away.
const glm::dvec3 kPoints[] = {{-0.9, -0.7, 3.0}, {0.8, -0.5, 2.5}, {-0.4, 0.6, 2.2},
                              {1.1, 0.9, 4.0},   {0.0, 0.0, 6.0},  {-1.6, 0.3, 4.5}};

class CvCamera : public GpuTest {};

TEST_F(CvCamera, KnownPointsLandWhereKRtPutsThem) {
    const Intrinsics k = intrinsics();
    const glm::dmat4 w2c = worldToCamera();
    Scene scene = test::emptyScene();
    std::vector<glm::dvec3> world;
    for (std::size_t i = 0; i < std::size(kPoints); ++i) {
        world.push_back(worldOf(w2c, kPoints[i]));
        test::addRampQuad(scene, 0.4, 0.4, float(i + 1) / 8.0f, facingCamera(w2c, world.back()));
    }
    RenderOptions o;
    o.width = k.width, o.height = k.height;
    o.background = glm::vec4(0.0f);
    o.camera = CameraSpec::fromPose(k, w2c, PoseConvention::OpenCV);
    double worst = 0.0;
    for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
        o.depth = mode;
        auto image = renderer().render(scene, o, 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        for (std::size_t i = 0; i < world.size(); ++i) {
            const glm::dvec2 expected = expectedImagePoint(k, w2c, world[i]);
            const auto got = test::locateRamp(*image, {0, 0, k.width, k.height},
                                              float(i + 1) / 8.0f, 0.5, 0.5);
            ASSERT_TRUE(got) << "point " << i << " not found; expected at " << expected.x
                             << ", " << expected.y << test::savedAs(*image, "known-points");
            const double error = glm::length(*got - expected);
            worst = std::max(worst, error);
            // The bound is half a pixel; the ramp fit is good to about 0.01 px, so a
            // tenth still catches a half-pixel-centre slip, a swapped fx/fy or a y flip.
            EXPECT_LT(error, 0.1) << "point " << i << " at " << got->x << ", " << got->y
                                  << ", expected " << expected.x << ", " << expected.y
                                  << test::savedAs(*image, "known-points");
        }
    }
    std::printf("largest distance from K[R|t] (ramp fit): %.2e px\n", worst);
}

TEST_F(CvCamera, BrightSquaresCentroidsAreWithinHalfAPixel) {
    // Small squares parallel to the image plane project to squares (constant depth): the
    // centroid of their coverage (alpha, multisampled) is the image of their centre.
    const Intrinsics k = intrinsics();
    const glm::dmat4 w2c = worldToCamera();
    Scene scene = test::emptyScene();
    std::vector<glm::dvec3> world;
    for (const glm::dvec3& c : kPoints) {
        world.push_back(worldOf(w2c, c));
        test::addRampQuad(scene, 0.06 * c.z, 0.06 * c.z, 1.0f, facingCamera(w2c, world.back()));
    }
    RenderOptions o;
    o.width = k.width, o.height = k.height;
    o.background = glm::vec4(0.0f);
    o.msaa = 4;  // lavapipe's most for float colour and depth
    o.camera = CameraSpec::fromPose(k, w2c, PoseConvention::OpenCV);
    auto image = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(image) << image.error().describe();
    double worst = 0.0;
    for (const glm::dvec3& X : world) {
        const glm::dvec2 e = expectedImagePoint(k, w2c, X);
        glm::dvec2 sum(0.0);
        double weight = 0.0;
        for (int y = int(e.y) - 12; y <= int(e.y) + 12; ++y)
            for (int x = int(e.x) - 12; x <= int(e.x) + 12; ++x) {
                if (x < 0 || y < 0 || x >= k.width || y >= k.height) continue;
                const double a = image->pixel(x, y)[3];
                sum += a * glm::dvec2(x + 0.5, y + 0.5);
                weight += a;
            }
        ASSERT_GT(weight, 20.0) << "square at " << e.x << ", " << e.y << " not drawn"
                                << test::savedAs(*image, "squares");
        const double error = glm::length(sum / weight - e);
        worst = std::max(worst, error);
        EXPECT_LT(error, 0.5) << "centroid " << (sum / weight).x << ", " << (sum / weight).y
                              << ", expected " << e.x << ", " << e.y
                              << test::savedAs(*image, "squares");
    }
    std::printf("largest centroid distance from K[R|t]: %.4f px\n", worst);
}

TEST_F(CvCamera, GltfAndOpenCvPosesRenderTheIdenticalImage) {
    auto loaded = loadScene("builtin:teapot");
    ASSERT_TRUE(loaded) << loaded.error().describe();
    const Intrinsics k = intrinsics();
    // Looking at the teapot from the front right, above: OpenCV's world_to_camera from a
    // lookAt, and glTF's camera_to_world computed from it independently (general inverse).
    const glm::dmat4 flip = glm::scale(glm::dmat4(1.0), glm::dvec3(1, -1, -1));
    const glm::dmat4 w2c = flip * lookAt({3.0, 2.5, 7.0}, {0.0, 0.5, 0.0}, {0, 1, 0});
    const glm::dmat4 c2wGltf = glm::inverse(w2c) * flip;
    RenderOptions o;
    o.width = k.width, o.height = k.height;
    o.camera = CameraSpec::fromPose(k, w2c, PoseConvention::OpenCV);
    auto a = renderer().render(*loaded, o, 0.0);
    o.camera = CameraSpec::fromPose(k, c2wGltf, PoseConvention::Gltf);
    auto b = renderer().render(*loaded, o, 0.0);
    ASSERT_TRUE(a && b);
    EXPECT_GT(test::countCovered(*a), 1000u) << test::savedAs(*a, "teapot");
    EXPECT_EQ(test::maxAbsDifference(*a, *b), 0.0f) << test::saveComparison(*b, *a, "gltf");
    // The same camera as Lantern's lookAt and an explicit frustum: the conversion is the
    // frustum through the border pixels' outer edges.
    o.camera = CameraSpec{};
    o.camera.source = CameraSpec::Source::GlDefault;
    o.camera.lookAt = LookAt{{3.0, 2.5, 7.0}, {0.0, 0.5, 0.0}, {0, 1, 0}};
    const double n = k.znear;
    o.camera.projection = Projection::makeFrustum(-(k.cx + 0.5) * n / k.fx,
                                                  (k.width - 0.5 - k.cx) * n / k.fx,
                                                  -(k.height - 0.5 - k.cy) * n / k.fy,
                                                  (k.cy + 0.5) * n / k.fy, n, k.zfar);
    auto c = renderer().render(*loaded, o, 0.0);
    ASSERT_TRUE(c);
    EXPECT_LT(test::maxAbsDifference(*a, *c), 1e-5f) << test::saveComparison(*c, *a, "lookat");
    // The image carries its intrinsics back.
    auto model = cameraModelOf(*a);
    ASSERT_TRUE(model) << model.error().describe();
    EXPECT_NEAR(model->intrinsics.fx, k.fx, 1e-9);
    EXPECT_NEAR(model->intrinsics.fy, k.fy, 1e-9);
    EXPECT_NEAR(model->intrinsics.cx, k.cx, 1e-9);
    EXPECT_NEAR(model->intrinsics.cy, k.cy, 1e-9);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row)
            EXPECT_NEAR(model->worldToCamera[col][row], w2c[col][row], 1e-12);
}

// Where the ray through pixel (i, j)'s centre meets the plane through `p0` with normal `n`
// (view space), as the distance along -z from the camera plane.
double planeDepth(const Intrinsics& k, int i, int j, const glm::dvec3& p0, const glm::dvec3& n) {
    const double x = (i - k.cx) / k.fx, y = -(j - k.cy) / k.fy;
    if (k.orthographic) {
        // The ray starts at (x, y, 0) and runs along -z.
        const double z = p0.z - (n.x * (x - p0.x) + n.y * (y - p0.y)) / n.z;
        return -z;
    }
    // The ray is t (x, y, -1): t = dot(n, p0) / dot(n, (x, y, -1)); depth is t.
    return glm::dot(n, p0) / glm::dot(n, glm::dvec3(x, y, -1.0));
}

TEST_F(CvCamera, DepthIsTheDistanceToTheCameraPlane) {
    // A large quad tilted 35 degrees about x and 20 about y, seen from 6 units: its depth varies
    // across the image, and every covered pixel's depth must be the analytic plane depth.
    Scene scene = test::emptyScene();
    glm::dmat4 plane = glm::rotate(glm::dmat4(1.0), 35 * kDeg, glm::dvec3(1, 0, 0));
    plane = glm::rotate(plane, 20 * kDeg, glm::dvec3(0, 1, 0));
    test::addRampQuad(scene, 40.0, 40.0, 0.5f, plane);
    const glm::dmat4 view = lookAt({0.5, 0.3, 6.0}, {0.2, 0.0, 0.0}, {0, 1, 0});
    const glm::dvec3 p0 = glm::dvec3(view * plane * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 n = glm::dvec3(view * plane * glm::dvec4(0, 0, 1, 0));
    for (bool ortho : {true, false}) {
        Intrinsics k = intrinsics();
        k.orthographic = ortho;
        if (ortho) k.fx = 14.0, k.fy = 11.0, k.znear = -10.0, k.zfar = 30.0;
        RenderOptions o;
        o.width = k.width, o.height = k.height;
        o.background = glm::vec4(0.0f);
        o.aovs.depth = true;
        o.camera = CameraSpec::fromPose(k, poseFromView(view, PoseConvention::OpenCV));
        auto image = renderer().render(scene, o, 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        ASSERT_EQ(image->depth.size(), image->pixelCount());
        double worst = 0.0, lo = 1e300, hi = 0.0;
        std::size_t checked = 0;
        for (int j = 0; j < k.height; ++j)
            for (int i = 0; i < k.width; ++i) {
                if (image->pixel(i, j)[3] < 1.0f) continue;
                const double expected = planeDepth(k, i, j, p0, n);
                const double got = image->depth[std::size_t(j) * std::size_t(k.width) + i];
                // Relative to the depth, or absolute within a unit of it (orthographic depths
                // pass through 0 in front of the camera plane).
                worst = std::max(worst, std::abs(got - expected) /
                                            std::max(1.0, std::abs(expected)));
                lo = std::min(lo, expected), hi = std::max(hi, expected);
                ++checked;
            }
        EXPECT_GT(checked, std::size_t(k.width * k.height / 2)) << test::savedAs(*image, "plane");
        EXPECT_GT(hi - lo, 1.0) << "the plane must span a range of depths";
        // Single-precision interpolation of the eye-space z: a few ulps of the depth.
        EXPECT_LT(worst, 1e-5) << (ortho ? "orthographic" : "pinhole")
                               << test::savedAs(*image, "plane");
        std::printf("%s depth: %zu pixels, depths %.3f to %.3f, largest relative error %.2e\n",
                    ortho ? "orthographic" : "pinhole", checked, lo, hi, worst);
    }
}

TEST_F(CvCamera, AutomaticNearFitsTheSceneAndIntrinsicsMustMatchTheImage) {
    Scene scene = test::emptyScene();
    test::addRampQuad(scene, 2.0, 2.0, 0.5f, glm::dmat4(1.0));
    Intrinsics k = intrinsics();
    k.znear = 0.0;  // automatic
    k.zfar = kInfinity;
    const glm::dmat4 view = lookAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    RenderOptions o;
    o.width = k.width, o.height = k.height;
    o.camera = CameraSpec::fromPose(k, poseFromView(view, PoseConvention::OpenCV));
    auto image = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(image) << image.error().describe();
    EXPECT_GT(test::countCovered(*image), 100u);
    auto model = cameraModelOf(*image);
    ASSERT_TRUE(model);
    // The quad's bounding sphere: centre 10 away, radius sqrt(2); near 1.5 radii before it.
    EXPECT_NEAR(model->intrinsics.znear, 10.0 - 1.5 * std::sqrt(2.0), 1e-9);
    EXPECT_TRUE(std::isinf(model->intrinsics.zfar));

    o.width = 100;
    auto refused = renderer().render(scene, o, 0.0);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(refused.error().message.find("160x120"), std::string::npos)
        << refused.error().describe();
}

} // namespace
