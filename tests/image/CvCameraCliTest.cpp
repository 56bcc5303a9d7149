// `lantern render --camera FILE`, --intrinsics, --world-to-camera, --camera-to-world and
// --write-camera: a camera file renders and writes back the same camera; glTF and OpenCV files
// render the identical image; the flags equal the file; the file sets the image size; every
// malformed file exits 1 naming the file and the key; conflicts are usage errors (exit 2).
#include "TestSupport.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::runLantern;
using lantern::test::testOutputDir;
using nlohmann::json;

const glm::dmat4 kFlip = glm::scale(glm::dmat4(1.0), glm::dvec3(1, -1, -1));

// OpenCV's world_to_camera looking at the teapot from the front right, above.
glm::dmat4 worldToCamera() { return kFlip * lookAt({3.0, 2.5, 7.0}, {0.0, 0.5, 0.0}, {0, 1, 0}); }

json rows(const glm::dmat4& m) {
    json out = json::array();
    for (int r = 0; r < 4; ++r) out.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
    return out;
}

glm::dmat4 matrixOf(const json& j) {
    glm::dmat4 m(0.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = j[std::size_t(r)][std::size_t(c)].get<double>();
    return m;
}

json cameraDoc() {
    return json{{"width", 160},
                {"height", 120},
                {"K", {{150.0, 0.0, 71.3}, {0.0, 118.0, 64.8}, {0.0, 0.0, 1.0}}},
                {"world_to_camera", rows(worldToCamera())},
                {"near", 0.25},
                {"far", 60.0}};
}

// testOutputDir() empties the folder on every call: each test takes it once.
std::string writeJson(const std::filesystem::path& dir, const std::string& name,
                      const json& doc) {
    const auto path = dir / name;
    std::ofstream(path) << doc.dump(2);
    return path.string();
}

json readJson(const std::filesystem::path& path) {
    std::ifstream in(path);
    return json::parse(in);
}

std::vector<std::string> render(const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args{"render", "builtin:teapot", "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

class CvCameraCli : public GpuTest {
protected:
    Image rendered(const std::filesystem::path& dir, const std::string& name,
                   std::vector<std::string> extra) {
        const std::string out = (dir / (name + ".exr")).string();
        const auto r = runLantern(render(out, std::move(extra)));
        EXPECT_EQ(r.exitCode, 0) << name << ": " << r.err;
        auto image = readExr(out);
        EXPECT_TRUE(image) << name << ": " << (image ? "" : image.error().describe());
        return image ? *image : Image();
    }
};

TEST_F(CvCameraCli, CameraFileRoundTripsThroughWriteCamera) {
    const auto dir = testOutputDir();
    const json in = cameraDoc();
    const std::string file = writeJson(dir, "camera.json", in);
    const auto out = dir / "round.exr";
    const auto r = runLantern(render(out.string(), {"--camera", file, "--write-camera"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto image = readExr(out);
    ASSERT_TRUE(image) << image.error().describe();
    EXPECT_EQ(image->width, 160) << "the file sets the image size";
    EXPECT_EQ(image->height, 120);
    EXPECT_GT(test::countCovered(*image), 1000u);
    const auto written = dir / "round.json";
    ASSERT_TRUE(std::filesystem::exists(written)) << r.out;
    const json j = readJson(written);
    EXPECT_EQ(j["width"], 160);
    EXPECT_EQ(j["height"], 120);
    EXPECT_EQ(j["convention"], "opencv");
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) {
            const double a = j["K"][row][col].get<double>(), b = in["K"][row][col].get<double>();
            EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, std::abs(b))) << "K " << row << col;
        }
    // The pose is exact: OpenCV's axes differ from Lantern's by signs only.
    EXPECT_EQ(matrixOf(j["world_to_camera"]), worldToCamera());
    EXPECT_NEAR(j["near"].get<double>(), 0.25, 1e-15);
    EXPECT_NEAR(j["far"].get<double>(), 60.0, 1e-12);
    // The other forms of the pose, against independent inverses.
    const glm::dmat4 c2w = glm::inverse(worldToCamera());
    const glm::dmat4 poses[] = {matrixOf(j["camera_to_world"]),
                                matrixOf(j["gltf"]["camera_to_world"]),
                                matrixOf(j["gltf"]["world_to_camera"])};
    const glm::dmat4 expected[] = {c2w, c2w * kFlip, kFlip * worldToCamera()};
    for (int p = 0; p < 3; ++p)
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row)
                EXPECT_NEAR(poses[p][col][row], expected[p][col][row], 1e-14) << p;
    // The projection matrix is the intrinsics' Vulkan projection (reversed-Z by default).
    Intrinsics k;
    k.width = 160, k.height = 120, k.fx = 150, k.fy = 118, k.cx = 71.3, k.cy = 64.8;
    k.znear = 0.25, k.zfar = 60;
    const glm::dmat4 clip = vulkanClipFromView(projectionFromIntrinsics(k), 160.0 / 120.0,
                                               DepthMode::ReversedZ);
    const glm::dmat4 matrix = matrixOf(j["projection_matrix"]);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row)
            EXPECT_NEAR(matrix[col][row], clip[col][row], 1e-12) << col << "," << row;
    EXPECT_EQ(j["depth"], "reversed");
    // The written file is a camera file: it renders the same picture.
    const Image again = rendered(dir, "again", {"--camera", written.string()});
    EXPECT_EQ(test::maxAbsDifference(again, *image), 0.0f);
}

TEST_F(CvCameraCli, GltfAndOpenCvFilesAndFlagsRenderTheIdenticalImage) {
    const auto dir = testOutputDir();
    const Image cv = rendered(dir, "opencv", {"--camera", writeJson(dir, "cv.json", cameraDoc())});
    json gltf = cameraDoc();
    gltf.erase("world_to_camera");
    gltf["convention"] = "gltf";
    gltf["camera_to_world"] = rows(glm::inverse(worldToCamera()) * kFlip);
    const Image g = rendered(dir, "gltf", {"--camera", writeJson(dir, "gltf.json", gltf)});
    EXPECT_EQ(test::maxAbsDifference(cv, g), 0.0f) << test::saveComparison(g, cv, "gltf");
    // The same camera from the flags.
    std::string pose;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            char b[40];
            std::snprintf(b, sizeof b, "%s%.17g", pose.empty() ? "" : ",", worldToCamera()[c][r]);
            pose += b;
        }
    const Image flags = rendered(dir, "flags", {"--width", "160", "--height", "120", "--intrinsics",
                                           "150,118,71.3,64.8,0.25,60", "--world-to-camera",
                                           pose});
    EXPECT_EQ(test::maxAbsDifference(cv, flags), 0.0f) << test::saveComparison(flags, cv, "flags");
    EXPECT_GT(test::countCovered(cv), 1000u);
}

TEST_F(CvCameraCli, WriteCameraDescribesEveryCameraAndEveryFrame) {
    // The scene's own camera (a symmetric perspective): square pixels, centred.
    const auto dir = testOutputDir();
    auto r = runLantern({"render", "builtin:spheres", "--width", "64", "--height", "48",
                         "--write-camera", "--frames", "0-1", "-o",
                         (dir / "f_#.exr").string(), "-o", (dir / "f_#.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* name : {"f_0.json", "f_1.json"}) {
        ASSERT_TRUE(std::filesystem::exists(dir / name)) << name;
        const json j = readJson(dir / name);
        const double fx = j["K"][0][0], fy = j["K"][1][1];
        EXPECT_NEAR(fx, fy, 1e-9 * fy) << name;
        EXPECT_NEAR(j["K"][0][2].get<double>(), 31.5, 1e-9) << "(width - 1) / 2";
        EXPECT_NEAR(j["K"][1][2].get<double>(), 23.5, 1e-9) << "(height - 1) / 2";
    }
    // --dry-run lists the camera files it would write.
    r = runLantern({"render", "builtin:spheres", "--write-camera", "--dry-run", "-o",
                    (dir / "dry.exr").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("dry.json"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "dry.json"));
}

TEST_F(CvCameraCli, WriteCameraNeverReplacesAFileLanternDidNotWrite) {
    const auto dir = testOutputDir();
    const std::string out = (dir / "shot.exr").string();
    const std::vector<std::string> args{"--width", "32", "--height", "24", "--write-camera"};
    // Lantern's own camera file is replaced by the next render.
    auto r = runLantern(render(out, args));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runLantern(render(out, args));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    // A user's JSON of that name, or a link there, is not: nothing is written.
    for (const bool link : {false, true}) {
        std::filesystem::remove(dir / "shot.exr");
        std::filesystem::remove(dir / "shot.json");
        if (link) {
            std::ofstream(dir / "target.json") << "{}";
            std::filesystem::create_symlink(dir / "target.json", dir / "shot.json");
        } else {
            std::ofstream(dir / "shot.json") << R"({"labels": [1, 2, 3]})";
        }
        r = runLantern(render(out, args));
        EXPECT_EQ(r.exitCode, 3) << r.err;
        EXPECT_NE(r.err.find("not replaced"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "shot.exr")) << "no image without its camera";
        EXPECT_TRUE(std::filesystem::is_symlink(dir / "shot.json") == link);
    }
    std::ifstream in(dir / "target.json");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{}");
}

TEST(CvCameraCliErrors, MalformedCameraFilesExit1NamingTheFileAndKey) {
    LANTERN_SKIP_IF_MISSING(test::missingVulkanDevice());
    struct Row {
        std::string name;
        json doc;
        std::string key, mention;
    };
    auto without = [](const char* key) {
        json d = cameraDoc();
        d.erase(key);
        return d;
    };
    auto with = [](const char* key, json value) {
        json d = cameraDoc();
        d[key] = std::move(value);
        return d;
    };
    const Row cases[] = {
        {"no-width", without("width"), "width", "missing"},
        {"no-k", without("K"), "K", "missing"},
        {"no-pose", without("world_to_camera"), "world_to_camera", "missing"},
        {"k-shape", with("K", {{1, 2, 3}}), "K", "3x3"},
        {"k-skew", with("K", {{150, 2, 71}, {0, 118, 64}, {0, 0, 1}}), "K", "skew"},
        {"k-text", with("K", {{150, 0, "c"}, {0, 118, 64}, {0, 0, 1}}), "K[0][2]", "number"},
        {"scaled-pose", with("world_to_camera", rows(glm::dmat4(2.0))), "world_to_camera",
         "last row"},
        {"sheared-pose",
         with("world_to_camera",
              rows(glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 1.5, 1.0)))),
         "world_to_camera", "not a rotation"},
        {"convention", with("convention", "blender"), "convention", "opencv"},
        {"near", with("near", -2), "near", "> 0"},
        {"far", with("far", 0.1), "near/far", "far"},
        {"typo", with("word_to_camera", 1), "word_to_camera", "not a camera key"},
        {"height", with("height", 0), "height", "1 to 16384"},
    };
    const auto dir = testOutputDir();
    for (const Row& row : cases) {
        const std::string file = writeJson(dir, row.name + ".json", row.doc);
        const auto out = dir / (row.name + ".exr");
        const auto r = runLantern(render(out.string(), {"--camera", file}));
        EXPECT_EQ(r.exitCode, 1) << row.name << ": " << r.err;
        EXPECT_NE(r.err.find(file), std::string::npos) << row.name << ": " << r.err;
        EXPECT_NE(r.err.find(row.key), std::string::npos) << row.name << ": " << r.err;
        EXPECT_NE(r.err.find(row.mention), std::string::npos) << row.name << ": " << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << row.name;
    }
    // Not JSON at all, a missing file, a size that contradicts --width.
    std::ofstream(dir / "broken.json") << "{\"width\": 160,";
    auto r = runLantern(render((dir / "x.exr").string(),
                               {"--camera", (dir / "broken.json").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not valid JSON"), std::string::npos) << r.err;
    r = runLantern(render((dir / "x.exr").string(), {"--camera", dir.string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
    r = runLantern(render((dir / "x.exr").string(), {"--camera", (dir / "absent.json").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("neither a scene camera index"), std::string::npos) << r.err;
    const std::string good = writeJson(dir, "good.json", cameraDoc());
    r = runLantern(render((dir / "x.exr").string(), {"--camera", good, "--width", "100"}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("--width"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("160"), std::string::npos) << r.err;
}

TEST(CvCameraCliErrors, ConflictingCameraOptionsAreUsageErrors) {
    LANTERN_SKIP_IF_MISSING(test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const std::string good = writeJson(dir, "good.json", cameraDoc());
    const std::string out = (dir / "x.exr").string();
    const std::vector<std::vector<std::string>> rows = {
        {"--camera", good, "--look-at", "0,0,5,0,0,0,0,1,0"},
        {"--camera", good, "--perspective", "40,1,0.1,10"},
        {"--camera", good, "--camera", "0"},
        {"--intrinsics", "100,100,31.5,23.5", "--ortho", "-1,1,-1,1,-1,1"},
        {"--world-to-camera", "1,0,0,0,0,1,0,0,0,0,1,5,0,0,0,1", "--look-at",
         "0,0,5,0,0,0,0,1,0"},
        {"--intrinsics", "100,100,31.5,23.5", "--viewport", "0,0,16,16"},
        {"--write-camera", "--layout", "quad"},
    };
    for (const auto& args : rows) {
        const auto r = runLantern(render(out, args));
        EXPECT_EQ(r.exitCode, 2) << args[0] << " " << args[1] << " " << args[2] << ": " << r.err;
    }
    // The viewer takes scene cameras and --look-at only (checked before a window opens).
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--camera", good},
          std::vector<std::string>{"--intrinsics", "100,100,31.5,23.5"}}) {
        std::vector<std::string> view{"view", "builtin:spheres"};
        view.insert(view.end(), args.begin(), args.end());
        const auto r = runLantern(view);
        EXPECT_EQ(r.exitCode, 2) << args[0] << ": " << r.err;
        EXPECT_NE(r.err.find("lantern render"), std::string::npos) << r.err;
    }
    // A pose that is not rigid, given as a flag: exit 1 naming the flag.
    const auto r = runLantern(render(out, {"--world-to-camera",
                                           "2,0,0,0,0,2,0,0,0,0,2,5,0,0,0,1"}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("--world-to-camera"), std::string::npos) << r.err;
}

} // namespace
