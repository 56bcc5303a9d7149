// Failures handled: device lost, out of memory and a full disk (fault injection), a real full
// disk (a tmpfs, where user namespaces are allowed), an image too large for memory refused
// before allocating, and synchronisation validation on an offscreen sequence. Each ends with a
// clear message and the right exit code, and leaves only complete files.
#include "TestSupport.h"

#include <lantern/Sequence.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::runProcess;
using lantern::test::testOutputDir;

std::vector<std::string> files(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

void expectOnlyCompleteExrs(const std::filesystem::path& dir) {
    for (const std::string& n : files(dir)) {
        EXPECT_EQ(n.find(".tmp-"), std::string::npos) << "temporary file left: " << n;
        EXPECT_TRUE(readExr(dir / n)) << n << " is not a complete EXR";
    }
}

bool hookedBuild() {
    // The fault hooks exist in dev and CI builds (LANTERN_TESTING_HOOKS), not in release ones.
    const auto r = runLantern({"render", "builtin:spheres", "--width", "8", "--height", "8", "-o", "/proc/x.exr"},
                              {"LANTERN_TEST_VK_FAULT=vkCreateDevice=VK_ERROR_INITIALIZATION_FAILED"});
    return r.err.find("VK_ERROR_INITIALIZATION_FAILED") != std::string::npos;
}

TEST(Failure, DeviceLostMidSequenceExits3AndKeepsFinishedFrames) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    // Uploads use the queue too: skip enough submissions that several frames are written first.
    const auto r = runLantern({"render", "builtin:spheres-animated", "--frames", "0-40", "--width", "48", "--height",
                               "32", "--encoder-threads", "1", "-o", (dir / "f_##.exr").string()},
                              {"LANTERN_TEST_VK_FAULT=vkQueueSubmit2(m_ctx=VK_ERROR_DEVICE_LOST@8"});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("device was lost"), std::string::npos) << r.err;
    const auto written = files(dir);
    EXPECT_GE(written.size(), 4u);
    EXPECT_LT(written.size(), 41u);
    expectOnlyCompleteExrs(dir);
}

TEST(Failure, OutOfDeviceMemoryExits3) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    const auto r = runLantern({"render", "builtin:spheres", "--width", "48", "--height", "32", "-o",
                               (dir / "x.exr").string()},
                              {"LANTERN_TEST_VK_FAULT=vkAllocateMemory=VK_ERROR_OUT_OF_DEVICE_MEMORY@3"});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
    EXPECT_TRUE(files(dir).empty());
}

// A frame that holds NaN or Inf after all (a renderer bug: the shaders are written so that
// none arises) is refused, never written with the values zeroed: exit 3, the count, the first
// pixel and the object drawn there. The readback hook plants a NaN where a shader bug would.
TEST(Failure, NonFiniteFrameExits3NamingTheObjectAndWritesNothing) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    const auto r = runLantern({"render", "builtin:spheres", "--width", "48", "--height", "32", "-o",
                               (dir / "x.exr").string(), "-o", (dir / "x.png").string()},
                              {"LANTERN_TEST_NONFINITE_PIXEL=24,16"});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("1 non-finite values (NaN or Inf), the first at pixel (24, 16) on nodes[1] \"sphere 1\""),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(files(dir).empty());
    // Without the NaN the same command writes both files: the refusal came from the NaN.
    const auto ok = runLantern({"render", "builtin:spheres", "--width", "48", "--height", "32", "-o",
                                (dir / "x.exr").string(), "-o", (dir / "x.png").string()});
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_EQ(files(dir).size(), 2u);
}

// A PNG written band by band (a PNG-only picture of 2^20 pixels) meets a full disk, a NaN in a
// band, or neither: the first two exit 3 naming the file or the pixel in the picture and leave
// nothing, not even the temporary file; the third writes both outputs.
TEST(Failure, ABandedPngThatFailsLeavesNothing) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    const std::vector<std::string> args{"render", "builtin:spheres", "--width", "1024", "--height",
                                        "1024", "-o", (dir / "a.png").string(), "-o",
                                        (dir / "b.png").string()};
    const auto full = runLantern(args, {"LANTERN_TEST_IO_FAULT=write=ENOSPC"});
    EXPECT_EQ(full.exitCode, 3) << full.err;
    EXPECT_NE(full.err.find("No space left on device (the disk is full)"), std::string::npos) << full.err;
    EXPECT_NE(full.err.find((dir / "a.png").string()), std::string::npos) << full.err;
    EXPECT_TRUE(files(dir).empty());
    // In the fourth band (rows 768-1023): the pixel is named in the picture's rows.
    const auto nan = runLantern(args, {"LANTERN_TEST_NONFINITE_PIXEL=600,10@3"});
    EXPECT_EQ(nan.exitCode, 3) << nan.err;
    EXPECT_NE(nan.err.find("the first at pixel (600, 778)"), std::string::npos) << nan.err;
    EXPECT_TRUE(files(dir).empty());
    const auto ok = runLantern(args);
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_EQ(files(dir), (std::vector<std::string>{"a.png", "b.png"}));
}

// In a sequence, the frames before the bad one are kept, complete, and no later one is written.
TEST(Failure, NonFiniteFrameMidSequenceKeepsTheFramesBefore) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    const auto r = runLantern({"render", "builtin:spheres-animated", "--frames", "0-9", "--width", "48",
                               "--height", "32", "--encoder-threads", "1", "-o", (dir / "f_##.exr").string()},
                              {"LANTERN_TEST_NONFINITE_PIXEL=24,16@3"});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("frame 3 (time 0.125 s) holds 1 non-finite values"), std::string::npos) << r.err;
    EXPECT_EQ(files(dir), (std::vector<std::string>{"f_00.exr", "f_01.exr", "f_02.exr"}));
    expectOnlyCompleteExrs(dir);
}

// A disk that fills mid-sequence, through the I/O fault hook (no privilege needed, so it runs
// everywhere): after 20 writes every write fails with ENOSPC, as on a full disk. A 160x120
// uncompressed float frame is about 310 kB, 6 of the EXR stream's writes, so a few frames are
// finished before the disk fills.
TEST(Failure, FullDiskExits3AndKeepsFinishedFrames) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    if (!hookedBuild()) GTEST_SKIP() << "this build has no fault-injection hooks (LANTERN_TESTING_HOOKS=OFF)";
    const auto dir = testOutputDir();
    const auto r = runLantern({"render", "builtin:spheres-animated", "--frames", "0-200", "--width",
                               "160", "--height", "120", "--compression", "none",
                               "--encoder-threads", "1", "-o", (dir / "f_###.exr").string()},
                              {"LANTERN_TEST_IO_FAULT=write=ENOSPC@20"});
    EXPECT_EQ(r.exitCode, 3) << "a full disk is a renderer failure (exit 3): " << r.err;
    // The message names the frame's file and says the disk is full.
    EXPECT_NE(r.err.find("No space left on device (the disk is full)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find((dir / "f_").string()), std::string::npos) << r.err;
    // With one encoder the frames finish in order: those before the full disk, and no other.
    const auto written = files(dir);
    EXPECT_GE(written.size(), 2u);
    EXPECT_LE(written.size(), 6u);
    for (std::size_t i = 0; i < written.size(); ++i)
        EXPECT_EQ(written[i], expandFramePattern("f_###.exr", int(i)));
    expectOnlyCompleteExrs(dir);
}

// The same on a real full disk: a 1 MiB tmpfs, which needs an unprivileged user namespace to
// mount. Machines that refuse one (a chroot, Docker's default profile) skip it, saying so; the
// fault-injection test above covers the behaviour there.
TEST(Failure, FullTmpfsExits3AndKeepsFinishedFrames) {
    LANTERN_SKIP_IF_MISSING(test::missingUserNamespaceMount());
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    std::filesystem::create_directories(dir / "mnt");
    std::filesystem::create_directories(dir / "copy");
    // A 1 MiB tmpfs in a private mount namespace fills after a few 160x120 float frames.
    const std::string script =
        "mount -t tmpfs -o size=1m tmpfs '" + (dir / "mnt").string() + "' || exit 77; '" +
        test::cliPath().string() +
        "' render builtin:spheres-animated --frames 0-200 --width 160 --height 120 --compression none "
        "--encoder-threads 1 -o '" + (dir / "mnt" / "f_###.exr").string() + "' 2>'" +
        (dir / "err").string() + "' >/dev/null; echo $? > '" + (dir / "rc").string() + "'; cp -a '" +
        (dir / "mnt").string() + "/.' '" + (dir / "copy").string() + "'";
    const auto r = runProcess({"unshare", "-rm", "sh", "-c", script});
    ASSERT_EQ(r.exitCode, 0) << "the probe allowed a tmpfs, but this mount failed: " << r.err;
    std::ifstream rcFile(dir / "rc");
    int rc = -1;
    rcFile >> rc;
    std::ifstream errFile(dir / "err");
    const std::string err((std::istreambuf_iterator<char>(errFile)),
                          std::istreambuf_iterator<char>());
    EXPECT_EQ(rc, 3) << "a full disk is a renderer failure (exit 3): " << err;
    EXPECT_NE(err.find("No space left on device (the disk is full)"), std::string::npos) << err;
    const auto written = files(dir / "copy");
    EXPECT_GE(written.size(), 2u);
    EXPECT_LT(written.size(), 201u);
    expectOnlyCompleteExrs(dir / "copy");
}

class Limits : public test::GpuTest {};

TEST_F(Limits, AnImageTooLargeForMemoryIsRefusedBeforeAllocating) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    RenderOptions o;
    o.width = 16384;
    o.height = 16384;
    o.msaa = 4;
    o.aovs.depth = true;
    const auto t0 = std::chrono::steady_clock::now();
    auto r = renderer().render(*scene, o, 0.0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::OutOfMemory) << r.error().describe();
    EXPECT_NE(r.error().message.find("MiB"), std::string::npos) << r.error().describe();
    EXPECT_LT(seconds, 5.0) << "it should be refused from an estimate, not by trying";
}

TEST_F(Limits, FlatStreamsBeyondTheDevicesLargestAllocationAreRefusedBeforeAllocating) {
    // 60M indices on three vertices (240 MB of scene): flat shading would need 60 bytes per
    // corner, 3.6 GB, beyond lavapipe's 2 GiB maxMemoryAllocationSize. Refused with the sizes
    // named; the same scene still renders in Phong, which needs no flat streams.
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    Primitive& p = scene->meshes.at(0).primitives.at(0);
    p.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    p.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
    p.colors.assign(3, glm::vec4(1.0f));
    p.texcoords.assign(3, glm::vec2(0.0f));
    p.indices.resize(60'000'000);
    for (std::size_t i = 0; i < p.indices.size(); ++i) p.indices[i] = std::uint32_t(i % 3);
    RenderOptions o;
    o.width = 8;
    o.height = 8;
    o.shading = ShadingMode::Flat;
    const auto t0 = std::chrono::steady_clock::now();
    auto flat = renderer().render(*scene, o, 0.0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_FALSE(flat);
    EXPECT_EQ(flat.error().code, ErrorCode::OutOfMemory) << flat.error().describe();
    EXPECT_NE(flat.error().message.find("flat geometry needs"), std::string::npos)
        << flat.error().describe();
    EXPECT_NE(flat.error().message.find("largest allocation"), std::string::npos)
        << flat.error().describe();
    EXPECT_LT(seconds, 20.0) << "refused from the size, before the streams are built";
    o.shading = ShadingMode::Phong;
    EXPECT_TRUE(renderer().render(*scene, o, 0.0));
}

TEST(SynchronizationValidation, OffscreenSequenceIsClean) {
    RendererDesc desc;
    desc.synchronizationValidation = true;
    std::vector<std::string> messages;
    desc.log = [&](LogLevel level, std::string_view m) {
        if (level >= LogLevel::Warning) messages.emplace_back(m);
    };
    auto renderer = Renderer::create(desc);
    if (!renderer) GTEST_SKIP() << "no Vulkan device: " << renderer.error().describe();
    if (!renderer->device().validationEnabled)
        GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed (vulkan-validationlayers)";
    auto scene = builtinScene("spheres-animated");
    ASSERT_TRUE(scene);
    auto prepared = renderer->prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared);
    RenderOptions o;
    o.width = 64;
    o.height = 48;
    o.msaa = 4;
    o.aovs.depth = o.aovs.normal = true;
    SequenceOptions s;
    s.frames = {0, 9};
    s.outputs = {(testOutputDir() / "f_#.exr").string()};
    auto r = renderer->renderSequence(*prepared, o, s);
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->framesWritten.size(), 10u);
    EXPECT_EQ(renderer->validationMessageCount(), 0u);
    for (const auto& m : messages) ADD_FAILURE() << m;
}

} // namespace
