// Reading frames back on the test machine's device: the path each plane takes is the one its
// properties allow (gpu/ReadbackPath.h), and a frame read in place is bit-identical to the
// same frame staged through a buffer (LANTERN_TEST_READBACK=staged), with multisampling,
// AOVs, the probe's ids, odd sizes (a linear image's rows may be padded) and a sequence with
// two frames in flight. Clearing by drawing is compared with the attachments' clear the same way.
#include "TestSupport.h"

#include "gpu/ClearDraw.h"
#include "gpu/Context.h"
#include "gpu/ReadbackPath.h"
#include "gpu/Targets.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>

namespace {

using namespace lantern;
using lantern::test::testOutputDir;

// A renderer with validation (and synchronisation validation) whose debug log is kept, made
// with every plane staged when `staged`.
struct LoggedRenderer {
    std::mutex mutex;
    std::vector<std::string> lines;
    std::optional<Renderer> renderer;

    explicit LoggedRenderer(bool staged)
        : LoggedRenderer("LANTERN_TEST_READBACK", staged ? "staged" : nullptr) {}
    // Made with the test switch `variable` set to `value` (null: unset).
    LoggedRenderer(const char* variable, const char* value) {
        if (value) ::setenv(variable, value, 1);
        RendererDesc desc;
        desc.validation = true;
        desc.synchronizationValidation = true;
        desc.log = [this](LogLevel, std::string_view m) {
            std::lock_guard lock(mutex);
            lines.emplace_back(m);
        };
        auto r = Renderer::create(desc);
        if (r) renderer.emplace(std::move(*r));
        ::unsetenv(variable);
    }
    // The log line that names how `plane` of a width x height target is read back.
    std::string choice(const std::string& plane, int w, int h) {
        const std::string prefix =
            plane + " " + std::to_string(w) + "x" + std::to_string(h) + " read back ";
        std::lock_guard lock(mutex);
        for (const std::string& l : lines)
            if (l.rfind(prefix, 0) == 0) return l.substr(prefix.size());
        return "(not logged)";
    }
};

// The device's own answer for the float colour plane, from its properties alone.
gpu::ReadbackChoice deviceChoice(std::uint32_t w, std::uint32_t h) {
    gpu::ContextDesc desc;
    auto ctx = gpu::Context::create(desc);
    if (!ctx) return {false, "no context: " + ctx.error().describe()};
    VkFormatProperties fp{};
    vkGetPhysicalDeviceFormatProperties((*ctx)->physicalDevice(), gpu::kColorFormat, &fp);
    gpu::LinearSupport linear;
    linear.features = fp.linearTilingFeatures;
    VkImageFormatProperties ip{};
    linear.imageSupported =
        vkGetPhysicalDeviceImageFormatProperties(
            (*ctx)->physicalDevice(), gpu::kColorFormat, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_LINEAR,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 0,
            &ip) == VK_SUCCESS;
    linear.maxExtent = ip.maxExtent;
    return gpu::chooseReadback(linear, gpu::inPlaceFeatures(true), (*ctx)->memoryProperties(),
                               ~0u, w, h);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    // memcmp may not be given the null data() of an empty plane (UBSan's nonnull check).
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

class Readback : public ::testing::Test {
protected:
    void SetUp() override {
        LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
        inPlace = std::make_unique<LoggedRenderer>(false);
        staged = std::make_unique<LoggedRenderer>(true);
        ASSERT_TRUE(inPlace->renderer && staged->renderer);
    }
    void TearDown() override {
        if (!inPlace) return;
        EXPECT_EQ(inPlace->renderer->validationMessageCount(), 0u);
        EXPECT_EQ(staged->renderer->validationMessageCount(), 0u);
    }
    // Skips the comparisons when the device reads everything staged anyway (they would
    // compare the staged path with itself).
    void requireInPlace(int w, int h) {
        RenderOptions o;
        o.width = w;
        o.height = h;
        ASSERT_TRUE(inPlace->renderer->render(*builtinScene("spheres"), o, 0.0));
        const std::string how = inPlace->choice("colour", w, h);
        if (how.rfind("in place", 0) != 0) GTEST_SKIP() << "this device reads back " << how;
    }
    // Options for a w x h picture, the rest default.
    static RenderOptions sized(int w, int h) {
        RenderOptions o;
        o.width = w;
        o.height = h;
        return o;
    }
    // builtin:spheres prepared on `r`.
    static std::optional<PreparedScene> spheres(LoggedRenderer& r) {
        auto scene = builtinScene("spheres");
        if (!scene) return std::nullopt;
        auto prepared = r.renderer->prepare(std::make_shared<const Scene>(std::move(*scene)));
        if (!prepared) return std::nullopt;
        return std::move(*prepared);
    }
    std::unique_ptr<LoggedRenderer> inPlace, staged;
};

TEST_F(Readback, ThePathFollowsTheDeviceProperties) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    RenderOptions o;
    o.width = 67;
    o.height = 45;
    ASSERT_TRUE(inPlace->renderer->render(*scene, o, 0.0));
    ASSERT_TRUE(staged->renderer->render(*scene, o, 0.0));
    const gpu::ReadbackChoice expected = deviceChoice(67, 45);
    // The logged choice is the device's, followed for an in-place plane by its row pitch.
    EXPECT_EQ(inPlace->choice("colour", 67, 45).rfind(expected.why, 0), 0u)
        << inPlace->choice("colour", 67, 45) << " / " << expected.why;
    EXPECT_EQ(staged->choice("colour", 67, 45), "staged: reading in place switched off (LANTERN_TEST_READBACK=staged)");
    // A device whose every memory type is device-local, host-visible and host-cached (a CPU
    // device such as lavapipe) and whose float format renders linear reads in place.
    gpu::ContextDesc desc;
    auto ctx = gpu::Context::create(desc);
    ASSERT_TRUE(ctx);
    const auto& mem = (*ctx)->memoryProperties();
    bool allHostMemory = mem.memoryTypeCount > 0;
    for (std::uint32_t i = 0; i < mem.memoryTypeCount; ++i)
        allHostMemory &= (mem.memoryTypes[i].propertyFlags & 0xF) == 0xF;
    VkFormatProperties fp{};
    vkGetPhysicalDeviceFormatProperties((*ctx)->physicalDevice(), gpu::kColorFormat, &fp);
    const VkFormatFeatureFlags needed = gpu::inPlaceFeatures(true);
    if (allHostMemory && (fp.linearTilingFeatures & needed) == needed) {
        EXPECT_TRUE(expected.inPlace) << expected.why;
    }
}

// Colour, depth and normal planes, and the probe's ids, identical to the bit on both paths.
void compareFrames(LoggedRenderer& a, LoggedRenderer& b, const RenderOptions& o) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto x = a.renderer->render(*scene, o, 0.0);
    auto y = b.renderer->render(*scene, o, 0.0);
    ASSERT_TRUE(x && y);
    EXPECT_EQ(a.renderer->lastFrameStats().nonFinite, 0u);
    EXPECT_TRUE(sameBits(x->rgba, y->rgba));
    EXPECT_TRUE(sameBits(x->depth, y->depth));
    EXPECT_TRUE(sameBits(x->normal, y->normal));
    EXPECT_TRUE(sameBits(x->range, y->range));
    EXPECT_TRUE(sameBits(x->uv, y->uv));
    EXPECT_EQ(x->instance, y->instance);
    EXPECT_EQ(x->range.size(), o.aovs.range ? x->pixelCount() : 0u);
    EXPECT_EQ(x->instance.size(), o.aovs.instance ? x->pixelCount() : 0u);
    EXPECT_EQ(x->depth.size(), o.aovs.depth ? x->pixelCount() : 0u);
    EXPECT_EQ(x->normal.size(), o.aovs.normal ? x->pixelCount() * 3 : 0u);
    std::size_t covered = 0;
    for (std::size_t i = 3; i < x->rgba.size(); i += 4) covered += x->rgba[i] > 0.5f;
    EXPECT_GT(covered, x->pixelCount() / 4);  // something was drawn, not just cleared
    // The probe reads the ids plane: the same triangle under the same pixel.
    for (const auto& [px, py] : {std::pair{33, 30}, std::pair{10, 40}, std::pair{60, 5}}) {
        auto p = a.renderer->probe(*scene, o, 0.0, px, py);
        auto q = b.renderer->probe(*scene, o, 0.0, px, py);
        ASSERT_TRUE(p && q);
        EXPECT_EQ(p->hit, q->hit);
        EXPECT_EQ(p->node, q->node);
        EXPECT_EQ(p->primitive, q->primitive);
        EXPECT_EQ(p->triangle, q->triangle);
    }
}

TEST_F(Readback, InPlaceIsBitIdenticalToStaged) {
    requireInPlace(67, 45);
    RenderOptions o;
    o.width = 67;  // rows of 1072 bytes: a linear image may pad them
    o.height = 45;
    compareFrames(*inPlace, *staged, o);
}

TEST_F(Readback, InPlaceIsBitIdenticalToStagedWithMsaaAndAovs) {
    RenderOptions o;
    o.width = 67;
    o.height = 45;
    o.aovs.depth = o.aovs.normal = true;
    ASSERT_TRUE(inPlace->renderer->render(*builtinScene("spheres"), o, 0.0));
    requireInPlace(67, 45);
    EXPECT_EQ(inPlace->choice("aov normal+depth", 67, 45).rfind("in place", 0), 0u);
    compareFrames(*inPlace, *staged, o);
    o.aovs.normal = false;  // depth alone
    compareFrames(*inPlace, *staged, o);
    o.msaa = 4;
    o.aovs.normal = true;
    compareFrames(*inPlace, *staged, o);
    o.aovs.range = o.aovs.uv = o.aovs.instance = true;  // the uv+range plane and the ids
    compareFrames(*inPlace, *staged, o);
    EXPECT_EQ(inPlace->choice("aov uv+range", 67, 45).rfind("in place", 0), 0u);
    o.msaa = 1;
    compareFrames(*inPlace, *staged, o);
    o.aovs = {};
    compareFrames(*inPlace, *staged, o);
}

// Clearing by drawing one triangle over the picture (what a CPU device prefers,
// gpu/ClearDraw.h) and clearing with LOAD_OP_CLEAR give the same bits in every plane: a
// coloured and a transparent background, with and without MSAA and AOVs (the MSAA AOV pass is
// cleared on its own), and with several views in one picture.
TEST(ClearByDrawing, IsBitIdenticalToTheAttachmentsClear) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    LoggedRenderer drawn("LANTERN_TEST_CLEAR", "draw"), loaded("LANTERN_TEST_CLEAR", "load");
    ASSERT_TRUE(drawn.renderer && loaded.renderer);
    RenderOptions o;
    o.width = 67;
    o.height = 45;
    o.background = {0.25f, 0.5f, 0.75f, 0.625f};
    compareFrames(drawn, loaded, o);
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto x = drawn.renderer->render(*scene, o, 0.0);
    ASSERT_TRUE(x);
    EXPECT_EQ(x->rgba[0], 0.25f);  // a corner pixel is the background, exactly
    EXPECT_EQ(x->rgba[3], 0.625f);
    o.aovs.depth = o.aovs.normal = true;
    compareFrames(drawn, loaded, o);
    o.msaa = 4;
    compareFrames(drawn, loaded, o);
    o.aovs.range = o.aovs.uv = o.aovs.instance = true;
    compareFrames(drawn, loaded, o);
    o.msaa = 1;
    compareFrames(drawn, loaded, o);
    o.background = {0.0f, 0.0f, 0.0f, 0.0f};
    o.aovs = {};
    compareFrames(drawn, loaded, o);
    o.views = {View{0, 0, 30, 45, {}}, View{30, 10, 37, 30, {}}};  // a strip between them
    compareFrames(drawn, loaded, o);
    EXPECT_EQ(drawn.renderer->validationMessageCount(), 0u);
    EXPECT_EQ(loaded.renderer->validationMessageCount(), 0u);
}

// Which frames clear by drawing without the test switch: on a CPU device, frames of a megapixel
// and more after a renderer's first; small ones and the first keep the attachment's clear (its
// cost is below the clear pipeline's JIT).
TEST(ClearByDrawing, ACpuDeviceDrawsTheClearOfLargeFramesAfterTheFirstOnly) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    gpu::ContextDesc desc;
    auto ctx = gpu::Context::create(desc);
    ASSERT_TRUE(ctx);
    const bool cpu = (*ctx)->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    EXPECT_EQ(gpu::ClearDraw::preferred(**ctx, 1920, 1080, false), cpu);
    EXPECT_EQ(gpu::ClearDraw::preferred(**ctx, 1000, 1000, false), cpu);
    EXPECT_FALSE(gpu::ClearDraw::preferred(**ctx, 999, 1000, false));
    EXPECT_FALSE(gpu::ClearDraw::preferred(**ctx, 256, 256, false));
    EXPECT_FALSE(gpu::ClearDraw::preferred(**ctx, 1920, 1080, true));
    EXPECT_FALSE(gpu::ClearDraw::preferred(**ctx, 1000, 1000, true));
}

// Two frames in flight: frame k+1 renders into the other slot's images while frame k is read;
// an animated scene makes every frame differ, so a slot overwritten too early would show.
TEST_F(Readback, ASequenceInPlaceMatchesStagedFrameForFrame) {
    auto scene = builtinScene("spheres-animated");
    ASSERT_TRUE(scene);
    RenderOptions o;
    o.width = 48;
    o.height = 32;
    o.aovs.depth = true;
    ASSERT_TRUE(inPlace->renderer->render(*scene, o, 0.0));
    requireInPlace(48, 32);
    SequenceOptions s;
    s.frames = {0, 5};
    s.fps = 10;
    s.encoderThreads = 2;
    const auto shared = std::make_shared<const Scene>(std::move(*scene));
    std::vector<Image> frames[2];
    const auto dir = testOutputDir();  // made empty by each call
    for (int i = 0; i < 2; ++i) {
        LoggedRenderer& r = i == 0 ? *inPlace : *staged;
        auto prepared = r.renderer->prepare(shared);
        ASSERT_TRUE(prepared);
        s.outputs = {(dir / (std::to_string(i) + "_##.exr")).string()};
        auto report = r.renderer->renderSequence(*prepared, o, s);
        ASSERT_TRUE(report) << report.error().describe();
        ASSERT_EQ(report->framesWritten.size(), 6u);
        for (int frame = 0; frame <= 5; ++frame) {  // framesWritten is in the order of encoding
            char name[32];
            std::snprintf(name, sizeof name, "%d_%02d.exr", i, frame);
            auto img = readExr(dir / name);
            ASSERT_TRUE(img) << img.error().describe();
            frames[i].push_back(std::move(*img));
        }
    }
    for (std::size_t k = 0; k < frames[0].size(); ++k) {
        EXPECT_TRUE(sameBits(frames[0][k].rgba, frames[1][k].rgba))
            << "frame " << k << " differs by up to "
            << lantern::test::maxAbsDifference(frames[0][k], frames[1][k]);
        EXPECT_TRUE(sameBits(frames[0][k].depth, frames[1][k].depth)) << "frame " << k;
        if (k > 0) {
            EXPECT_FALSE(sameBits(frames[0][k].rgba, frames[0][k - 1].rgba)) << "frame " << k;
        }
    }
}

} // namespace

// Renderer::render(..., Image& into) reuses the Image's memory: the pixels, AOV planes and
// metadata it leaves are those render() returns, whatever the Image held before (a larger
// picture with AOVs, a smaller one without), and no plane keeps stale values.
TEST_F(Readback, RenderIntoAnImageGivesWhatRenderReturns) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    auto prepared = inPlace->renderer->prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared) << prepared.error().describe();
    Image into;
    RenderOptions big;
    big.width = 80;
    big.height = 50;
    big.aovs.depth = big.aovs.normal = true;
    RenderOptions small;
    small.width = 33;
    small.height = 21;
    small.shading = ShadingMode::Flat;
    // The same sizes again with other pixels (an overwrite that missed a row would show), and a
    // picture of 16 MiB, overwritten in two bands when the Image has its size.
    RenderOptions bigPhong = big, smallGouraud = small;
    bigPhong.shading = ShadingMode::Phong;
    smallGouraud.shading = ShadingMode::Gouraud;
    RenderOptions large, largeFlat;
    large.width = largeFlat.width = 1024;
    large.height = largeFlat.height = 1024;
    largeFlat.shading = ShadingMode::Flat;
    for (const RenderOptions* o :
         {&big, &small, &big, &bigPhong, &small, &smallGouraud, &large, &largeFlat}) {
        auto fresh = inPlace->renderer->render(*prepared, *o, 0.25);
        ASSERT_TRUE(fresh) << fresh.error().describe();
        const float* before = into.rgba.empty() ? nullptr : into.rgba.data();
        ASSERT_TRUE(inPlace->renderer->render(*prepared, *o, 0.25, into));
        EXPECT_EQ(into.width, o->width);
        EXPECT_EQ(into.height, o->height);
        EXPECT_TRUE(sameBits(into.rgba, fresh->rgba));
        EXPECT_TRUE(sameBits(into.depth, fresh->depth));
        EXPECT_TRUE(sameBits(into.normal, fresh->normal));
        EXPECT_EQ(into.metadata, fresh->metadata);
        ASSERT_TRUE(into.camera && fresh->camera);
        EXPECT_EQ(into.camera->viewFromWorld, fresh->camera->viewFromWorld);
        // The small picture fits in the big one's memory: no new allocation.
        if (o == &small && before) {
            EXPECT_EQ(into.rgba.data(), before);
        }
    }
}

// Renderer::renderView leaves the colour where the device put it: each row read through the
// view is the row render() returns, bit for bit, on both paths (in place: the linear render
// target, padded rows included; staged: the buffer the image was copied into), with and
// without multisampling, and toImage() is render()'s Image (metadata and camera too).
TEST_F(Readback, AViewOfTheFrameHoldsWhatRenderReturns) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    const auto shared = std::make_shared<const Scene>(std::move(*scene));
    for (LoggedRenderer* r : {inPlace.get(), staged.get()}) {
        auto prepared = r->renderer->prepare(shared);
        ASSERT_TRUE(prepared) << prepared.error().describe();
        for (int msaa : {1, 4})
            for (auto [w, h] : {std::pair{67, 45}, std::pair{33, 21}, std::pair{64, 64}}) {
                SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " msaa " +
                             std::to_string(msaa) + (r == staged.get() ? " staged" : " in place"));
                RenderOptions o;
                o.width = w;
                o.height = h;
                o.msaa = msaa;
                auto fresh = r->renderer->render(*prepared, o, 0.5);
                ASSERT_TRUE(fresh) << fresh.error().describe();
                auto view = r->renderer->renderView(*prepared, o, 0.5);
                ASSERT_TRUE(view) << view.error().describe();
                ASSERT_TRUE(view->valid());
                EXPECT_EQ(view->width(), w);
                EXPECT_EQ(view->height(), h);
                // The rows are where the frame lies: the linear render target's (at the row
                // pitch the renderer logged for it) when read in place, else the staging
                // buffer's, packed.
                const std::string how = r->choice("colour", w, h);
                if (how.rfind("in place", 0) == 0)
                    EXPECT_NE(how.find(", rows " + std::to_string(view->rowPitch()) + " bytes apart"),
                              std::string::npos)
                        << how;
                else
                    EXPECT_EQ(view->rowPitch(), std::size_t(w) * 16) << how;
                for (int y = 0; y < h; ++y) {
                    ASSERT_NE(view->row(y), nullptr);
                    EXPECT_EQ(std::memcmp(view->row(y), fresh->pixel(0, y), std::size_t(w) * 16), 0)
                        << "row " << y;
                }
                EXPECT_EQ(view->pixel(w - 1, h - 1), view->row(h - 1) + (w - 1) * 4);
                EXPECT_EQ(view->row(h), nullptr);
                EXPECT_EQ(view->row(-1), nullptr);
                EXPECT_EQ(view->pixel(w, 0), nullptr);
                const Image copy = view->toImage();
                EXPECT_TRUE(sameBits(copy.rgba, fresh->rgba));
                EXPECT_EQ(copy.metadata, fresh->metadata);
                ASSERT_TRUE(copy.camera && fresh->camera);
                EXPECT_EQ(copy.camera->clipFromView, fresh->camera->clipFromView);
                EXPECT_TRUE(copy.depth.empty());
            }
    }
}

// A view lives until the renderer submits its next frame (of any size: the slot's target may
// be reallocated) or is destroyed; then it says so and gives no pointer.
TEST_F(Readback, AViewEndsWithTheNextFrameOrTheRenderer) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    const auto shared = std::make_shared<const Scene>(std::move(*scene));
    auto prepared = inPlace->renderer->prepare(shared);
    ASSERT_TRUE(prepared);
    RenderOptions o = sized(40, 30);
    auto first = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_TRUE(first);
    EXPECT_TRUE(first->valid());
    const FrameView kept = *first;  // copies share the view's life
    RenderOptions other = o;
    other.width = 300;
    ASSERT_TRUE(inPlace->renderer->render(*prepared, other, 0.0));
    EXPECT_FALSE(first->valid());
    EXPECT_FALSE(kept.valid());
    EXPECT_EQ(first->row(0), nullptr);
    EXPECT_EQ(first->pixel(0, 0), nullptr);
    EXPECT_TRUE(first->toImage().rgba.empty());
    EXPECT_FALSE(FrameView{}.valid());

    auto second = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_TRUE(second);
    auto third = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_TRUE(third);
    EXPECT_FALSE(second->valid());
    EXPECT_TRUE(third->valid());

    auto own = Renderer::create();
    ASSERT_TRUE(own);
    auto p = own->prepare(shared);
    ASSERT_TRUE(p);
    auto view = own->renderView(*p, o, 0.0);
    ASSERT_TRUE(view);
    const FrameView outlives = *view;
    EXPECT_TRUE(outlives.valid());
    *p = PreparedScene{};
    {
        auto replacement = Renderer::create();
        ASSERT_TRUE(replacement);
        *own = std::move(*replacement);  // the first renderer, its device and memory are gone
    }
    EXPECT_FALSE(outlives.valid());
    EXPECT_EQ(outlives.row(0), nullptr);
}

// A view is the colour only; AOVs are refused with a message that points to render().
TEST_F(Readback, AViewRefusesAovPlanes) {
    const std::optional<PreparedScene> prepared = spheres(*inPlace);
    ASSERT_TRUE(prepared);
    RenderOptions o = sized(16, 16);
    o.aovs.depth = true;
    auto view = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_FALSE(view);
    EXPECT_EQ(view.error().code, ErrorCode::Usage);
    EXPECT_NE(view.error().message.find("render()"), std::string::npos) << view.error().message;
    o.aovs = {};
    o.aovs.cryptoObject = true;
    EXPECT_FALSE(inPlace->renderer->renderView(*prepared, o, 0.0));
    o.aovs = {};
    o.width = 0;
    auto bad = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::InvalidInput);
}

// No NaN or Inf reaches the host through a view either: a frame that holds one (injected where
// a shader bug would leave it) is refused, naming the pixel, as render() refuses it, also into
// a kept Image. A large picture is checked in two halves on two threads: a value in either
// half is found.
TEST_F(Readback, AViewOfAFrameWithNaNIsRefused) {
    const std::optional<PreparedScene> prepared = spheres(*inPlace);
    ASSERT_TRUE(prepared);
    struct Case {
        int w, h;
        const char* pixel;
    };
    for (const Case& c : {Case{48, 32, "24,16"}, Case{1024, 300, "700,250"}, Case{1024, 300, "513,3"}}) {
        SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " at " + c.pixel);
        RenderOptions o = sized(c.w, c.h);
        ::setenv("LANTERN_TEST_NONFINITE_PIXEL", c.pixel, 1);
        auto view = inPlace->renderer->renderView(*prepared, o, 0.0);
        auto image = inPlace->renderer->render(*prepared, o, 0.0);
        Image kept(c.w, c.h);  // render() into an Image of the frame's size: overwritten
        auto into = inPlace->renderer->render(*prepared, o, 0.0, kept);
        ::unsetenv("LANTERN_TEST_NONFINITE_PIXEL");
        ASSERT_FALSE(view);
        ASSERT_FALSE(image);
        ASSERT_FALSE(into);
        EXPECT_EQ(into.error().message, image.error().message);
        EXPECT_TRUE(kept.rgba.empty());
        EXPECT_EQ(view.error().code, image.error().code);
        std::string at = c.pixel;
        at = "1 non-finite values (NaN or Inf), the first at pixel (" + at.replace(at.find(','), 1, ", ") + ")";
        EXPECT_NE(view.error().message.find(at), std::string::npos) << view.error().message;
        EXPECT_EQ(view.error().message, image.error().message);
        auto clean = inPlace->renderer->renderView(*prepared, o, 0.0);
        ASSERT_TRUE(clean) << clean.error().describe();
    }
}

// A PNG made from a view (no float copy of the picture: `lantern render -o x.png`) has the
// bytes of the PNG made from render()'s Image, transparent edges (un-premultiplied) included;
// a stale view writes nothing.
TEST_F(Readback, APngFromAViewIsThePngOfTheImage) {
    const std::optional<PreparedScene> prepared = spheres(*inPlace);
    ASSERT_TRUE(prepared);
    RenderOptions o = sized(67, 45);
    o.msaa = 4;
    o.background = glm::vec4(0.0f);
    auto image = inPlace->renderer->render(*prepared, o, 0.0);
    ASSERT_TRUE(image);
    auto view = inPlace->renderer->renderView(*prepared, o, 0.0);
    ASSERT_TRUE(view);
    const auto dir = testOutputDir();
    ASSERT_TRUE(writePng(dir / "image.png", *image));
    ASSERT_TRUE(writePng(dir / "view.png", *view));
    auto bytes = [](const std::filesystem::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_GT(bytes(dir / "view.png").size(), 100u);
    EXPECT_EQ(bytes(dir / "view.png"), bytes(dir / "image.png"));
    ASSERT_TRUE(inPlace->renderer->render(*prepared, o, 0.0));
    auto stale = writePng(dir / "stale.png", *view);
    ASSERT_FALSE(stale);
    EXPECT_EQ(stale.error().code, ErrorCode::Usage);
    EXPECT_FALSE(std::filesystem::exists(dir / "stale.png"));
}
