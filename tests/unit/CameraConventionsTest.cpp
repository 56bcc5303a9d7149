// Computer-vision cameras without a device: OpenCV's K[R|t] and Lantern's view and Vulkan
// projection put every point on the same pixel (OpenCV's pixel centres at integers, Vulkan's at
// half-integers); the glTF and OpenCV poses give the same view; intrinsicsFromClip inverts the
// projection for every camera kind and depth mode; poses that are not rigid are refused; and
// the camera JSON file reads back what was written and names the file and key of every fault.
#include "TestSupport.h"

#include <lantern/CameraConventions.h>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <fstream>

namespace {

using namespace lantern;
using lantern::test::testOutputDir;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A world_to_camera [R | t] in OpenCV axes: rotated about a skew axis, translated.
glm::dmat4 openCvPose() {
    glm::dmat4 r = glm::rotate(glm::dmat4(1.0), 23 * kDeg, glm::normalize(glm::dvec3(1, -2, 0.5)));
    r[3] = glm::dvec4(0.3, -0.2, 4.0, 1.0);
    return r;
}

// Off-centre principal point, fx != fy: the two mistakes a centred, square test hides.
Intrinsics offCentre() {
    Intrinsics k;
    k.width = 160, k.height = 120;
    k.fx = 210.0, k.fy = 170.0, k.cx = 70.25, k.cy = 66.5;
    k.znear = 0.05, k.zfar = 80.0;
    return k;
}

// OpenCV: u = fx x/z + cx, v = fy y/z + cy, with (x, y, z) = [R | t] X.
glm::dvec2 openCvProject(const Intrinsics& k, const glm::dmat4& w2c, const glm::dvec3& X) {
    const glm::dvec3 c = glm::dvec3(w2c * glm::dvec4(X, 1.0));
    if (k.orthographic) return {k.fx * c.x + k.cx, k.fy * c.y + k.cy};
    return {k.fx * c.x / c.z + k.cx, k.fy * c.y / c.z + k.cy};
}

// Lantern: Vulkan clip, divide, viewport; framebuffer pixel (i, j) is centred at i + 0.5, so
// the OpenCV coordinate is the framebuffer coordinate minus 0.5. Also the Vulkan depth.
glm::dvec3 lanternProject(const glm::dmat4& clipFromView, const glm::dmat4& viewFromWorld,
                          int width, int height, const glm::dvec3& X) {
    const glm::dvec4 clip = clipFromView * viewFromWorld * glm::dvec4(X, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return {(ndc.x + 1.0) * width / 2.0 - 0.5, (ndc.y + 1.0) * height / 2.0 - 0.5, ndc.z};
}

TEST(CameraConventions, OpenCvPointsLandOnTheSamePixelThroughLanternsMatrices) {
    for (bool ortho : {false, true})
        for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
            Intrinsics k = offCentre();
            if (ortho) k.orthographic = true, k.fx = 31.0, k.fy = 23.0, k.znear = -2.0;
            const glm::dmat4 w2c = openCvPose();
            const glm::dmat4 view = viewFromPose(w2c, PoseConvention::OpenCV);
            const Projection p = projectionFromIntrinsics(k);
            ASSERT_TRUE(checkProjection(p, "p"));
            const glm::dmat4 clip =
                vulkanClipFromView(p, double(k.width) / double(k.height), mode);
            double worst = 0.0;
            for (double x : {-1.0, -0.3, 0.4, 1.1})
                for (double y : {-0.8, 0.2, 0.9})
                    for (double z : {-1.0, 0.0, 2.5}) {
                        const glm::dvec3 X(x, y, z);
                        const glm::dvec2 cv = openCvProject(k, w2c, X);
                        const glm::dvec3 ln = lanternProject(clip, view, k.width, k.height, X);
                        worst = std::max(worst, glm::length(glm::dvec2(ln) - cv));
                    }
            EXPECT_LT(worst, 1e-9) << (ortho ? "orthographic " : "pinhole ") << toString(mode);
            // The image's corners: OpenCV's (-0.5, -0.5) is the outer corner of the top-left
            // pixel, Vulkan's NDC (-1, -1).
            const double zc = ortho ? 1.0 : 3.0;
            const glm::dvec3 corner((-0.5 - k.cx) / k.fx * (ortho ? 1.0 : zc),
                                    (-0.5 - k.cy) / k.fy * (ortho ? 1.0 : zc), zc);
            const glm::dvec4 c = clip * glm::dvec4(corner.x, -corner.y, -corner.z, 1.0);
            EXPECT_NEAR(c.x / c.w, -1.0, 1e-12);
            EXPECT_NEAR(c.y / c.w, -1.0, 1e-12);
        }
}

TEST(CameraConventions, NearAndFarMapToTheDepthModesEnds) {
    const Intrinsics k = offCentre();
    const Projection p = projectionFromIntrinsics(k);
    for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
        const glm::dmat4 clip = vulkanClipFromView(p, 160.0 / 120.0, mode);
        auto depth = [&](double d) {
            const glm::dvec4 c = clip * glm::dvec4(0.1, 0.1, -d, 1.0);
            return c.z / c.w;
        };
        EXPECT_NEAR(depth(k.znear), mode == DepthMode::ReversedZ ? 1.0 : 0.0, 1e-12);
        EXPECT_NEAR(depth(k.zfar), mode == DepthMode::ReversedZ ? 0.0 : 1.0, 1e-12);
    }
}

TEST(CameraConventions, GltfAndOpenCvPosesGiveTheSameView) {
    const glm::dmat4 w2c = openCvPose();
    // glTF's camera_to_world, built independently: the camera's world matrix with its y and z
    // axes flipped (glTF's camera looks down -z with +y up; OpenCV's down +z with +y down).
    const glm::dmat4 flip = glm::scale(glm::dmat4(1.0), glm::dvec3(1, -1, -1));
    const glm::dmat4 c2wGltf = glm::inverse(w2c) * flip;
    const glm::dmat4 a = viewFromPose(w2c, PoseConvention::OpenCV);
    const glm::dmat4 b = viewFromPose(c2wGltf, PoseConvention::Gltf);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-14) << c << "," << r;
    // And back: poseFromView inverts viewFromPose in both conventions.
    const glm::dmat4 w = poseFromView(a, PoseConvention::OpenCV);
    const glm::dmat4 g = poseFromView(a, PoseConvention::Gltf);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_EQ(w[c][r], w2c[c][r]);  // only signs change: exact
            EXPECT_NEAR(g[c][r], c2wGltf[c][r], 1e-14);
        }
    // A glTF camera at the origin with no rotation is Lantern's default eye space.
    EXPECT_EQ(viewFromPose(glm::dmat4(1.0), PoseConvention::Gltf), glm::dmat4(1.0));
}

TEST(CameraConventions, IntrinsicsComeBackFromEveryProjection) {
    // The intrinsics' own projection, pinhole and orthographic, finite and infinite far.
    for (bool ortho : {false, true})
        for (double far : {80.0, kInfinity})
            for (DepthMode mode : {DepthMode::ReversedZ, DepthMode::Standard}) {
                if (ortho && std::isinf(far)) continue;
                Intrinsics k = offCentre();
                k.orthographic = ortho;
                k.zfar = far;
                const glm::dmat4 clip = vulkanClipFromView(projectionFromIntrinsics(k),
                                                           160.0 / 120.0, mode);
                const auto back = intrinsicsFromClip(clip, k.width, k.height,
                                                     mode == DepthMode::ReversedZ);
                ASSERT_TRUE(back);
                EXPECT_EQ(back->orthographic, ortho);
                EXPECT_NEAR(back->fx, k.fx, 1e-12 * k.fx);
                EXPECT_NEAR(back->fy, k.fy, 1e-12 * k.fy);
                EXPECT_NEAR(back->cx, k.cx, 1e-12 * k.width);
                EXPECT_NEAR(back->cy, k.cy, 1e-12 * k.height);
                EXPECT_NEAR(back->znear, k.znear, 1e-12);
                if (std::isinf(far))
                    EXPECT_TRUE(std::isinf(back->zfar));
                else
                    EXPECT_NEAR(back->zfar, far, 1e-10 * far);
            }
    // gluPerspective 60 degrees in 200 x 100: fy = 50 / tan(30 deg), centred (99.5, 49.5).
    const glm::dmat4 clip = vulkanClipFromView(
        Projection::makePerspective(60 * kDeg, 0.0, 0.1, kInfinity), 2.0, DepthMode::ReversedZ);
    const auto k = intrinsicsFromClip(clip, 200, 100, true);
    ASSERT_TRUE(k);
    EXPECT_NEAR(k->fy, 50.0 / std::tan(30 * kDeg), 1e-9);
    EXPECT_NEAR(k->fx, k->fy, 1e-9);
    EXPECT_NEAR(k->cx, 99.5, 1e-12);
    EXPECT_NEAR(k->cy, 49.5, 1e-12);
    EXPECT_NEAR(k->znear, 0.1, 1e-15);
    EXPECT_TRUE(std::isinf(k->zfar));
    // A matrix of another form has no intrinsics.
    glm::dmat4 skewed = clip;
    skewed[1][0] = 0.1;
    EXPECT_FALSE(intrinsicsFromClip(skewed, 200, 100, true));
}

TEST(CameraConventions, PosesThatAreNotRigidAreRefused) {
    EXPECT_TRUE(checkPose(openCvPose(), "pose"));
    struct Row {
        glm::dmat4 m;
        const char* mention;
    };
    glm::dmat4 nan = openCvPose();
    nan[3][0] = std::nan("");
    glm::dmat4 row = openCvPose();
    row[0][3] = 0.5;
    const Row rows[] = {
        {glm::scale(openCvPose(), glm::dvec3(2, 2, 2)), "not a rotation"},
        {glm::scale(openCvPose(), glm::dvec3(1, 1, 1.01)), "not a rotation"},
        {glm::scale(openCvPose(), glm::dvec3(1, 1, -1)), "mirrors"},
        {nan, "non-finite"},
        {row, "last row"},
    };
    for (const Row& r : rows) {
        auto result = checkPose(r.m, "world_to_camera");
        ASSERT_FALSE(result) << r.mention;
        EXPECT_EQ(result.error().object, "world_to_camera");
        EXPECT_NE(result.error().message.find(r.mention), std::string::npos)
            << result.error().message;
    }
}

TEST(CameraConventions, IntrinsicsThatCannotRenderAreRefused) {
    EXPECT_TRUE(checkIntrinsics(offCentre(), "K"));
    auto with = [](auto change) {
        Intrinsics k = offCentre();
        change(k);
        return k;
    };
    const std::pair<Intrinsics, const char*> rows[] = {
        {with([](Intrinsics& k) { k.fx = 0; }), "focal"},
        {with([](Intrinsics& k) { k.fy = -3; }), "focal"},
        {with([](Intrinsics& k) { k.cx = std::nan(""); }), "finite"},
        {with([](Intrinsics& k) { k.width = 0; }), "image size"},
        {with([](Intrinsics& k) { k.height = 20000; }), "image size"},
        {with([](Intrinsics& k) { k.znear = -1; }), "near"},
        {with([](Intrinsics& k) { k.zfar = 0.01; }), "far"},
    };
    for (const auto& [k, mention] : rows) {
        auto r = checkIntrinsics(k, "K");
        ASSERT_FALSE(r) << mention;
        EXPECT_NE(r.error().message.find(mention), std::string::npos) << r.error().message;
    }
    // Automatic near planes pass: the renderer fits them to the scene.
    EXPECT_TRUE(checkIntrinsics(with([](Intrinsics& k) { k.znear = 0.0; }), "K"));
    EXPECT_TRUE(automaticNear(with([](Intrinsics& k) { k.znear = 0.0; })));
    EXPECT_TRUE(automaticNear(with([](Intrinsics& k) { k.znear = std::nan(""); })));
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

TEST(CameraFile, WrittenCamerasReadBackExactly) {
    const auto dir = testOutputDir();
    for (bool ortho : {false, true}) {
        CameraModel m{offCentre(), openCvPose()};
        m.intrinsics.orthographic = ortho;
        if (ortho) m.intrinsics.fx = 31, m.intrinsics.fy = 23, m.intrinsics.znear = -2;
        const auto path = dir / (ortho ? "ortho.json" : "pinhole.json");
        const glm::dmat4 clip = vulkanClipFromView(projectionFromIntrinsics(m.intrinsics),
                                                   160.0 / 120.0, DepthMode::ReversedZ);
        ASSERT_TRUE(writeCameraFile(path, m, clip));
        auto back = readCameraFile(path);
        ASSERT_TRUE(back) << back.error().describe();
        const Intrinsics& a = back->intrinsics;
        EXPECT_EQ(a.width, 160);
        EXPECT_EQ(a.height, 120);
        EXPECT_EQ(a.orthographic, ortho);
        // Seventeen significant digits: every double reads back to itself.
        EXPECT_EQ(a.fx, m.intrinsics.fx);
        EXPECT_EQ(a.fy, m.intrinsics.fy);
        EXPECT_EQ(a.cx, m.intrinsics.cx);
        EXPECT_EQ(a.cy, m.intrinsics.cy);
        EXPECT_EQ(a.znear, m.intrinsics.znear);
        EXPECT_EQ(a.zfar, m.intrinsics.zfar);
        EXPECT_EQ(back->worldToCamera, m.worldToCamera);
    }
    EXPECT_EQ(cameraFilePath("out/frame_0001.exr"), std::filesystem::path("out/frame_0001.json"));
}

TEST(CameraFile, GltfFilesGiveTheSameCameraAsOpenCvFiles) {
    const auto dir = testOutputDir();
    const glm::dmat4 w2c = openCvPose();
    const glm::dmat4 flip = glm::scale(glm::dmat4(1.0), glm::dvec3(1, -1, -1));
    const glm::dmat4 c2w = glm::inverse(w2c) * flip;
    auto rows = [](const glm::dmat4& m) {
        std::string s = "[";
        for (int r = 0; r < 4; ++r) {
            s += r ? ", [" : "[";
            for (int c = 0; c < 4; ++c) {
                char b[40];
                std::snprintf(b, sizeof b, "%s%.17g", c ? ", " : "", m[c][r]);
                s += b;
            }
            s += "]";
        }
        return s + "]";
    };
    const std::string head =
        R"({"width": 160, "height": 120, "K": [[210, 0, 70.25], [0, 170, 66.5], [0, 0, 1]], )";
    writeText(dir / "cv.json", head + R"("world_to_camera": )" + rows(w2c) + "}");
    writeText(dir / "gltf.json",
              head + R"("convention": "gltf", "camera_to_world": )" + rows(c2w) + "}");
    auto a = readCameraFile(dir / "cv.json");
    auto b = readCameraFile(dir / "gltf.json");
    ASSERT_TRUE(a) << a.error().describe();
    ASSERT_TRUE(b) << b.error().describe();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(a->worldToCamera[c][r], b->worldToCamera[c][r], 1e-14);
    EXPECT_TRUE(automaticNear(a->intrinsics)) << "no near in the file: automatic";
    EXPECT_TRUE(std::isinf(a->intrinsics.zfar));
}

TEST(CameraFile, MalformedFilesNameTheFileAndTheKey) {
    const auto dir = testOutputDir();
    const std::string K = R"("K": [[200, 0, 79.5], [0, 200, 59.5], [0, 0, 1]])";
    const std::string pose =
        R"("world_to_camera": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]])";
    const std::string size = R"("width": 160, "height": 120)";
    struct Row {
        std::string text, key, mention;
    };
    const Row rows[] = {
        {"{" + size + ", " + K + ", " + pose, "", "not valid JSON"},
        {"[1, 2]", "", "JSON object"},
        {"{" + K + ", " + pose + R"(, "height": 120})", "width", "missing"},
        {"{" + size + ", " + pose + "}", "K", "missing"},
        {"{" + size + ", " + K + "}", "world_to_camera", "missing"},
        {R"({"width": 160.5, "height": 120, )" + K + ", " + pose + "}", "width", "whole number"},
        {R"({"width": 0, "height": 120, )" + K + ", " + pose + "}", "width", "1 to 16384"},
        {"{" + size + R"(, "K": [[200, 0, 79.5], [0, 200, 59.5]], )" + pose + "}", "K",
         "3x3"},
        {"{" + size + R"(, "K": [[200, 0.5, 79.5], [0, 200, 59.5], [0, 0, 1]], )" + pose + "}",
         "K", "skew"},
        {"{" + size + R"(, "K": [[-200, 0, 79.5], [0, 200, 59.5], [0, 0, 1]], )" + pose + "}",
         "K", "focal"},
        {"{" + size + R"(, "K": [[200, 0, "x"], [0, 200, 59.5], [0, 0, 1]], )" + pose + "}",
         "K[0][2]", "number"},
        {"{" + size + ", " + K +
             R"(, "world_to_camera": [[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 5], [0, 0, 0, 1]]})",
         "world_to_camera", "not a rotation"},
        {"{" + size + ", " + K +
             R"(, "world_to_camera": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5]]})",
         "world_to_camera", "4x4"},
        {"{" + size + ", " + K + ", " + pose + R"(, "convention": "blender"})", "convention",
         "opencv"},
        {"{" + size + ", " + K + ", " + pose + R"(, "near": -1})", "near", "> 0"},
        {"{" + size + ", " + K + ", " + pose + R"(, "near": 1, "far": 0.5})", "near/far",
         "far"},
        {"{" + size + ", " + K + ", " + pose + R"(, "projection": "fisheye"})", "projection",
         "orthographic"},
        {"{" + size + ", " + K + ", " + pose + R"(, "word_to_camera": 1})", "word_to_camera",
         "not a camera key"},
        {"{" + size + ", " + K + ", " + pose +
             R"(, "camera_to_world": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]]})",
         "camera_to_world", "inverse"},
    };
    int i = 0;
    for (const Row& r : rows) {
        const auto path = dir / ("bad" + std::to_string(i++) + ".json");
        writeText(path, r.text);
        auto result = readCameraFile(path);
        ASSERT_FALSE(result) << r.text;
        const Error& e = result.error();
        EXPECT_EQ(e.code, ErrorCode::InvalidInput) << r.text;
        EXPECT_EQ(e.file, path.string()) << r.text;
        EXPECT_EQ(e.object, r.key) << r.text << ": " << e.describe();
        EXPECT_NE(e.message.find(r.mention), std::string::npos) << r.text << ": " << e.describe();
    }
    auto missing = readCameraFile(dir / "absent.json");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::IoError);
}

} // namespace
