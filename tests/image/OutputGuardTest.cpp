// The output guard (shaders/include/output.glsl): a frame drawn only by guarded fragment
// variants is checked for NaN/Inf where its colours are made, and the host reads the picture
// again only when a fragment tripped the guard. These tests hold the two halves together:
// a guarded frame has the pixels of the unguarded variants; a NaN, an Inf or a value above
// LANTERN_GUARD_BOUND made by the shaders sends the frame to the host's check, which finds
// what it found before the guard existed; and every frame the guard's argument does not cover
// (alpha mask, the overlays, a clear colour above the bound) is checked on the host.
#include "LightingCompare.h"

#include "gpu/Context.h"
#include "gpu/SceneBuffers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

class OutputGuard : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (!device().context().capabilities().fragmentStores)
            GTEST_SKIP() << "the device lacks fragmentStoresAndAtomics: every frame is checked "
                            "on the host";
    }

    // One lit sphere with `material`, rendered without AOVs (the guarded variants) unless
    // `aovs`, edited by `edits`.
    Result<render::RenderedFrame> draw(const Material& material, const RenderOptions& options,
                                       const render::FrameEdits& edits = {}, bool aovs = false) {
        LitScene s;
        s.objects.push_back({makeSphere(1.0, 24, 12), material, glm::dmat4(1.0)});
        Light point = test::makeLight(LightType::Point);
        point.attenuation = {1.0, 0.05, 0.01};
        s.lights.push_back({point, test::translation({1.0, 1.5, 3.0})});
        m_scene = s.build();
        RenderOptions o = options;
        if (aovs) o.aovs.depth = true;
        LANTERN_TRY(render::checkOptions(device(), o));
        auto buffers = device().upload(
            std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &m_scene));
        if (!buffers) return std::move(buffers).error();
        FrameStats stats;
        return render::renderFrame(device(), *buffers, m_scene, o, 0.0, stats, edits);
    }

    static Material plastic() {
        return test::phongMaterial({0.2, 0.1, 0.05}, {0.8, 0.5, 0.3, 1.0}, {0.9, 0.9, 0.9}, 30.0);
    }

    // Every shading program a default frame can use: phong, gouraud, flat (lit per triangle by
    // the pre-pass), GL-compatible flat (provoking vertex) and the bench's floor.
    struct Mode {
        const char* name;
        ShadingMode shading;
        bool glCompat = false, floor = false;
    };
    static std::vector<Mode> modes() {
        return {{"phong", ShadingMode::Phong},
                {"gouraud", ShadingMode::Gouraud},
                {"flat", ShadingMode::Flat},
                {"gl_flat", ShadingMode::Flat, true},
                {"floor", ShadingMode::Phong, false, true}};
    }
    static RenderOptions optionsOf(const Mode& m) {
        RenderOptions o = test::optionsFor(48, 40, m.shading);
        o.glCompat = m.glCompat;
        return o;
    }
    // `edit` applied to the draw list, and in the floor mode every draw made a floor draw.
    static render::FrameEdits editsOf(const Mode& m, std::function<void(gpu::DrawList&)> edit = {}) {
        render::FrameEdits e;
        e.list = [m, edit](gpu::DrawList& list) {
            if (m.floor)
                for (gpu::ViewCommands& v : list.views)
                    for (gpu::DrawCommand& d : v.draws) d.pipeline.program = frame::Program::Floor;
            if (edit) edit(list);
        };
        return e;
    }

    Scene m_scene;
};

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && !a.empty() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST_F(OutputGuard, AGuardedFrameHasTheUnguardedPixelsAndNoHostCheck) {
    for (const Mode& m : modes()) {
        auto guarded = draw(plastic(), optionsOf(m), editsOf(m));
        ASSERT_TRUE(guarded) << m.name << ": " << guarded.error().describe();
        EXPECT_FALSE(guarded->readback.hostChecked) << m.name << ": the shaders vouched for it";
        EXPECT_EQ(guarded->readback.nonFinite, 0u) << m.name;
        // The same frame with a depth AOV uses the unguarded variants and the host's check.
        auto plain = draw(plastic(), optionsOf(m), editsOf(m), true);
        ASSERT_TRUE(plain) << m.name << ": " << plain.error().describe();
        EXPECT_TRUE(plain->readback.hostChecked) << m.name;
        EXPECT_TRUE(sameBits(guarded->readback.image.rgba, plain->readback.image.rgba))
            << m.name << ": the guard changed a pixel";
        EXPECT_GT(test::brightestColour(guarded->readback.image), 0.1f) << m.name;
    }
}

// A NaN or an Inf in the material reaches the fragment's colour in every program: the guard
// trips, the host counts them as it always did (and scrubs its copy).
TEST_F(OutputGuard, ANaNOrInfFromTheShadersTripsItAndTheHostFindsThem) {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity()})
        for (const Mode& m : modes()) {
            if (m.floor) continue;  // the floor's colour is a constant
            const std::string name = std::string(m.name) + (std::isnan(bad) ? " NaN" : " Inf");
            auto f = draw(plastic(), optionsOf(m), editsOf(m, [bad](gpu::DrawList& list) {
                              list.materials[0].front.emission.x = bad;
                          }));
            ASSERT_TRUE(f) << name << ": " << f.error().describe();
            EXPECT_TRUE(f->readback.hostChecked) << name << ": the guard did not trip";
            EXPECT_GT(f->readback.nonFinite, 100u) << name;
            EXPECT_GE(f->readback.nonFiniteX, 0) << name;
            EXPECT_EQ(test::countNonFinite(f->readback.image), 0u) << name << ": scrubbed";
        }
}

// A finite colour above the bound trips the guard too (a blend of such values could overflow):
// the host checks the frame, finds nothing, and the value is kept as it was drawn.
TEST_F(OutputGuard, AFiniteValueAboveTheBoundIsCheckedOnTheHostAndKept) {
    Material m = plastic();
    m.front.emission = {1e37, 0.0, 0.0};
    auto f = draw(m, test::optionsFor(32, 32, ShadingMode::Phong));
    ASSERT_TRUE(f) << f.error().describe();
    EXPECT_TRUE(f->readback.hostChecked);
    EXPECT_EQ(f->readback.nonFinite, 0u);
    EXPECT_GE(test::brightestColour(f->readback.image), 1e37f);
    // Just under the bound the shaders vouch for the frame.
    m.front.emission = {1e35, 0.0, 0.0};
    auto under = draw(m, test::optionsFor(32, 32, ShadingMode::Phong));
    ASSERT_TRUE(under) << under.error().describe();
    EXPECT_FALSE(under->readback.hostChecked);
    EXPECT_GE(test::brightestColour(under->readback.image), 1e35f);
}

// What the guard's argument does not cover is checked on the host: a draw that may discard
// (alpha mask: the guarded variants test depth before the shader), the overlays' colours, a
// clear colour above the bound. A blended draw is covered (a mix of two values within the
// bound, with an alpha in [0, 1], stays within it).
TEST_F(OutputGuard, FramesOutsideItsArgumentAreCheckedOnTheHost) {
    Material mask = plastic();
    mask.alphaMode = AlphaMode::Mask;
    mask.front.diffuse.a = 0.8;
    auto masked = draw(mask, test::optionsFor(32, 32, ShadingMode::Phong));
    ASSERT_TRUE(masked) << masked.error().describe();
    EXPECT_TRUE(masked->readback.hostChecked) << "alpha mask";

    Material blend = plastic();
    blend.alphaMode = AlphaMode::Blend;
    blend.front.diffuse.a = 0.5;
    auto blended = draw(blend, test::optionsFor(32, 32, ShadingMode::Phong));
    ASSERT_TRUE(blended) << blended.error().describe();
    EXPECT_FALSE(blended->readback.hostChecked) << "blend";

    render::FrameEdits overlays;
    overlays.list = [](gpu::DrawList& list) { list.overlays.wireframe = true; };
    if (device().context().capabilities().fillModeNonSolid) {
        auto wire = draw(plastic(), test::optionsFor(32, 32, ShadingMode::Phong), overlays);
        ASSERT_TRUE(wire) << wire.error().describe();
        EXPECT_TRUE(wire->readback.hostChecked) << "overlays";
    }

    for (const float clear : {1e37f, std::numeric_limits<float>::infinity()}) {
        render::FrameEdits bright;
        bright.list = [clear](gpu::DrawList& list) { list.target.clear = {clear, 0.0f, 0.0f, 1.0f}; };
        auto f = draw(plastic(), test::optionsFor(32, 32, ShadingMode::Phong), bright);
        ASSERT_TRUE(f) << f.error().describe();
        EXPECT_TRUE(f->readback.hostChecked) << "clear " << clear;
        if (std::isinf(clear))
            EXPECT_GT(f->readback.nonFinite, 100u) << "the background is Inf";
        else
            EXPECT_EQ(f->readback.nonFinite, 0u) << "clear " << clear;
    }
}

} // namespace
