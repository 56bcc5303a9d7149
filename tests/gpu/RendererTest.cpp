// The renderer on the test machine's device: it renders, the validation layer is really
// watching (a provoked error is counted), bad options are refused before allocating, and
// frames are deterministic.
#include "TestSupport.h"

#include "gpu/Context.h"

#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

class Renderer_ : public GpuTest {};

RenderOptions small(int w = 96, int h = 64) {
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = w;
    o.height = h;
    return o;
}

TEST_F(Renderer_, DescribesItsDevice) {
    const DeviceInfo& d = renderer().device();
    EXPECT_FALSE(d.name.empty());
    EXPECT_GE(d.apiVersion, (1u << 22) | (3u << 12));
    EXPECT_FALSE(d.msaaSampleCounts.empty());
}

TEST_F(Renderer_, RendersTheBuiltinSpheres) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto img = renderer().render(*scene, small(), 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    EXPECT_EQ(img->width, 96);
    EXPECT_EQ(img->height, 64);
    EXPECT_EQ(lantern::test::countNonFinite(*img), 0u);
    EXPECT_EQ(renderer().lastFrameStats().nonFinite, 0u);
    const std::size_t covered = lantern::test::countCovered(*img);
    EXPECT_GT(covered, img->pixelCount() / 4);  // spheres and floor fill a good part
    EXPECT_LT(covered, img->pixelCount());      // the sky stays transparent
}

TEST_F(Renderer_, FramesAreBitIdentical) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto a = renderer().render(*scene, small(), 0.0);
    auto b = renderer().render(*scene, small(), 0.0);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->rgba, b->rgba);
}

// The memory a scene costs: its host arrays (summarize's hostBytes: at least the positions,
// normals and indices it holds) and the device memory its upload adds, given back when the
// last PreparedScene goes.
TEST_F(Renderer_, ReportsTheMemoryAPreparedSceneHolds) {
    auto scene = builtinScene("teapot");
    ASSERT_TRUE(scene);
    std::size_t arrays = 0;
    for (const Mesh& m : scene->meshes)
        for (const Primitive& p : m.primitives)
            arrays += p.positions.size() * 12 + p.normals.size() * 12 + p.indices.size() * 4;
    const SceneSummary summary = summarize(*scene);
    EXPECT_GE(summary.hostBytes, arrays);
    EXPECT_LT(summary.hostBytes, 4 * arrays + (1u << 20));

    const std::uint64_t before = renderer().deviceMemoryBytes();
    {
        auto prepared = renderer().prepare(std::make_shared<const Scene>(*scene));
        ASSERT_TRUE(prepared) << prepared.error().describe();
        const std::uint64_t uploaded = renderer().deviceMemoryBytes() - before;
        EXPECT_GE(uploaded, arrays) << "the geometry lives on the device";
        EXPECT_LT(uploaded, 8 * arrays + (1u << 20));
        ASSERT_TRUE(renderer().render(*prepared, small(), 0.0));
        EXPECT_GT(renderer().deviceMemoryBytes(), before + uploaded) << "the frame's targets";
    }
    const std::uint64_t targets = renderer().deviceMemoryBytes() - before;
    EXPECT_LT(targets, 96u * 64u * 64u) << "the scene's memory was given back";
}

TEST_F(Renderer_, RefusesBadOptionsBeforeAllocating) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto tooBig = renderer().render(*scene, small(1 << 20, 16), 0.0);
    ASSERT_FALSE(tooBig);
    EXPECT_EQ(tooBig.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(tooBig.error().message.find("maximum"), std::string::npos);
    auto empty = renderer().render(*scene, small(0, 16), 0.0);
    ASSERT_FALSE(empty);
    RenderOptions o = small();
    o.msaa = 3;
    EXPECT_FALSE(renderer().render(*scene, o, 0.0));
    o = small();
    o.camera.source = CameraSpec::Source::SceneCamera;
    o.camera.sceneCamera = 9;
    auto badCamera = renderer().render(*scene, o, 0.0);
    ASSERT_FALSE(badCamera);
    EXPECT_NE(badCamera.error().message.find("camera 9"), std::string::npos);
}

TEST_F(Renderer_, ExplainListsFeaturesAndVariants) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto r = renderer().explain(*scene, small());
    ASSERT_TRUE(r);
    auto has = [&](const std::string& f) {
        for (const auto& x : r->features)
            if (x.find(f) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("light:directional x1"));
    EXPECT_TRUE(has("light:point x1"));
    EXPECT_TRUE(has("attenuation:gl"));
    EXPECT_FALSE(has("spot"));
    EXPECT_FALSE(r->variants.empty());
}

TEST_F(Renderer_, MsaaAntialiasesColourAndKeepsAovsExact) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    RenderOptions o = small();
    o.aovs.depth = o.aovs.normal = true;
    auto one = renderer().render(*scene, o, 0.0);
    o.msaa = 4;
    auto four = renderer().render(*scene, o, 0.0);
    ASSERT_TRUE(one && four);
    // The AOVs are one value per pixel centre in both: identical.
    EXPECT_EQ(one->depth, four->depth);
    EXPECT_EQ(one->normal, four->normal);
    // The colour is antialiased: silhouette pixels get partial coverage.
    std::size_t partial = 0;
    for (std::size_t i = 0; i < four->pixelCount(); ++i) {
        const float a = four->rgba[i * 4 + 3];
        partial += a > 0.01f && a < 0.99f;
    }
    EXPECT_GT(partial, 20u);
    EXPECT_EQ(test::countNonFinite(*four), 0u);
}

// The proof that validation is really on: an invalid call must be counted.
TEST(ValidationLayer, CountsAProvokedError) {
    gpu::ContextDesc desc;
    desc.validation = true;
    std::string last;
    desc.log = [&](LogLevel level, std::string_view m) {
        if (level >= LogLevel::Warning) last = std::string(m);
    };
    auto ctx = gpu::Context::create(desc);
    if (!ctx) GTEST_SKIP() << "no Vulkan device: " << ctx.error().describe();
    if (!(*ctx)->validationEnabled())
        GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed (vulkan-validationlayers)";
    EXPECT_EQ((*ctx)->validationMessageCount(), 0u);
    VkBufferCreateInfo bad{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bad.size = 0;  // VUID-VkBufferCreateInfo-size-00912
    bad.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult r = vkCreateBuffer((*ctx)->device(), &bad, nullptr, &buffer);
    if (r == VK_SUCCESS && buffer) vkDestroyBuffer((*ctx)->device(), buffer, nullptr);
    EXPECT_GE((*ctx)->validationMessageCount(), 1u);
    EXPECT_NE(last.find("00912"), std::string::npos) << last;
}

} // namespace
