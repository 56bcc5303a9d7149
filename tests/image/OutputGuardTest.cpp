// The output guard (shaders/include/guard.glsl): a frame whose colours were all made by stages
// that check them (the guarded vertex variants of gouraud and flat, the per-triangle flat
// pre-pass, the floor's constant) is not read again on the host for NaN/Inf unless one of
// them tripped the guard. These tests hold the two halves together: a guarded frame has the
// pixels of the same frame unguarded; a NaN, an Inf or a value above LANTERN_GUARD_BOUND that
// the shaders make sends the frame to the host's check, which finds what it found before the
// guard existed; and every frame the guard's argument does not cover (phong, an emissive map,
// the overlays, a clear colour above the bound) is checked on the host.
#include "LightingCompare.h"

#include "gpu/Context.h"
#include "gpu/SceneBuffers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

class OutputGuard : public GpuTest {
protected:
    // The device lets the vertex stage store (the guarded gouraud and GL-flat variants).
    bool vertexStores() { return device().context().capabilities().vertexStores; }

    // One lit sphere (325 vertices) with `material`, rendered without AOVs unless `aovs`, with
    // every draw that can be guarded guarded (OutputGuard::Always), then edited by `edits`.
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
        render::FrameEdits always = edits;
        always.list = [&edits](gpu::DrawList& list) {
            list.outputGuard = gpu::OutputGuard::Always;
            if (edits.list) edits.list(list);
        };
        return render::renderFrame(device(), *buffers, m_scene, o, 0.0, stats, always);
    }

    static Material plastic() {
        return test::phongMaterial({0.2, 0.1, 0.05}, {0.8, 0.5, 0.3, 1.0}, {0.9, 0.9, 0.9}, 30.0);
    }

    // The guarded programs: gouraud and GL-compatible flat (the vertex stage checks), flat (lit
    // and checked per triangle by the pre-pass) and the bench's floor (a constant colour).
    struct Mode {
        const char* name;
        ShadingMode shading;
        bool glCompat = false, floor = false;
        bool vertexStage = false;  ///< checked by the vertex stage (needs its stores)
    };
    static std::vector<Mode> modes() {
        return {{"gouraud", ShadingMode::Gouraud, false, false, true},
                {"flat", ShadingMode::Flat},
                {"gl_flat", ShadingMode::Flat, true, false, true},
                {"floor", ShadingMode::Phong, false, true}};
    }
    bool usable(const Mode& m) { return !m.vertexStage || vertexStores(); }
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
        if (!usable(m)) {
            std::printf("[ SKIPPED ] %s: the device lacks vertexPipelineStoresAndAtomics\n", m.name);
            continue;
        }
        auto guarded = draw(plastic(), optionsOf(m), editsOf(m));
        ASSERT_TRUE(guarded) << m.name << ": " << guarded.error().describe();
        EXPECT_FALSE(guarded->readback.hostChecked) << m.name << ": the shaders vouched for it";
        EXPECT_EQ(guarded->readback.nonFinite, 0u) << m.name;
        // The same frame unguarded: the plain variants and the host's check.
        auto plain = draw(plastic(), optionsOf(m), editsOf(m, [](gpu::DrawList& list) {
                              list.outputGuard = gpu::OutputGuard::Never;
                          }));
        ASSERT_TRUE(plain) << m.name << ": " << plain.error().describe();
        EXPECT_TRUE(plain->readback.hostChecked) << m.name;
        EXPECT_TRUE(sameBits(guarded->readback.image.rgba, plain->readback.image.rgba))
            << m.name << ": the guard changed a pixel";
        EXPECT_GT(test::brightestColour(guarded->readback.image), 0.1f) << m.name;
        // With AOVs too (the fragment stage writes more; the colours are made the same way).
        auto aov = draw(plastic(), optionsOf(m), editsOf(m), true);
        ASSERT_TRUE(aov) << m.name << ": " << aov.error().describe();
        EXPECT_FALSE(aov->readback.hostChecked) << m.name << " with AOVs";
    }
    // Phong lights per fragment, where a check would cost every pixel: always the host's.
    auto phong = draw(plastic(), test::optionsFor(48, 40, ShadingMode::Phong));
    ASSERT_TRUE(phong) << phong.error().describe();
    EXPECT_TRUE(phong->readback.hostChecked);
}

// A NaN or an Inf in the material reaches the fragment's colour in every program: the guard
// trips, the host counts them as it always did (and scrubs its copy).
TEST_F(OutputGuard, ANaNOrInfFromTheShadersTripsItAndTheHostFindsThem) {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity()})
        for (const Mode& m : modes()) {
            if (m.floor || !usable(m)) continue;  // the floor's colour is a constant
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
    for (const Mode& m : modes()) {
        // --gl-compat clamps every lit colour to [0, 1], as OpenGL does.
        if (m.floor || m.glCompat || !usable(m)) continue;
        Material over = plastic();
        over.front.emission = {1e36, 0.0, 0.0};
        auto f = draw(over, optionsOf(m), editsOf(m));
        ASSERT_TRUE(f) << m.name << ": " << f.error().describe();
        EXPECT_TRUE(f->readback.hostChecked) << m.name;
        EXPECT_EQ(f->readback.nonFinite, 0u) << m.name;
        EXPECT_GE(test::brightestColour(f->readback.image), 1e36f) << m.name;
        // Under the bound the shaders vouch for the frame.
        Material under = plastic();
        under.front.emission = {1e34, 0.0, 0.0};
        auto g = draw(under, optionsOf(m), editsOf(m));
        ASSERT_TRUE(g) << m.name << ": " << g.error().describe();
        EXPECT_FALSE(g->readback.hostChecked) << m.name;
        EXPECT_GE(test::brightestColour(g->readback.image), 1e34f) << m.name;
    }
}

// What the guard's argument does not cover is checked on the host: an emissive map (which the
// fragment stage adds), the overlays' colours, a clear colour above the bound. An alpha-masked
// and a blended draw are covered (a discard makes no colour; a mix of two values within the
// bound, with an alpha in [0, 1], stays within it).
TEST_F(OutputGuard, FramesOutsideItsArgumentAreCheckedOnTheHost) {
    const Mode gouraud = modes()[0];
    if (!usable(gouraud)) GTEST_SKIP() << "the device lacks vertexPipelineStoresAndAtomics";
    const RenderOptions o = optionsOf(gouraud);
    Material blend = plastic();
    for (const AlphaMode mode : {AlphaMode::Mask, AlphaMode::Blend}) {
        blend.alphaMode = mode;
        blend.front.diffuse.a = mode == AlphaMode::Mask ? 0.8 : 0.5;
        auto f = draw(blend, o);
        ASSERT_TRUE(f) << f.error().describe();
        EXPECT_FALSE(f->readback.hostChecked) << (mode == AlphaMode::Mask ? "mask" : "blend");
    }
    // An alpha above 1 (a vertex colour's, say) would not keep a blend convex: it trips.
    render::FrameEdits opacity;
    opacity.list = [](gpu::DrawList& list) { list.materials[0].front.diffuse.w = 1.5f; };
    auto over = draw(blend, o, opacity);
    ASSERT_TRUE(over) << over.error().describe();
    EXPECT_TRUE(over->readback.hostChecked) << "alpha 1.5";

    render::FrameEdits emissiveMap;
    emissiveMap.list = [](gpu::DrawList& list) {
        for (gpu::ViewCommands& v : list.views)
            for (gpu::DrawCommand& d : v.draws)
                d.pipeline.constants[LANTERN_SC_MAPS] |= LANTERN_MAP_EMISSIVE;
    };
    auto mapped = draw(plastic(), o, emissiveMap);
    ASSERT_TRUE(mapped) << mapped.error().describe();
    EXPECT_TRUE(mapped->readback.hostChecked) << "emissive map";

    render::FrameEdits overlays;
    overlays.list = [](gpu::DrawList& list) { list.overlays.wireframe = true; };
    if (device().context().capabilities().fillModeNonSolid) {
        auto wire = draw(plastic(), o, overlays);
        ASSERT_TRUE(wire) << wire.error().describe();
        EXPECT_TRUE(wire->readback.hostChecked) << "overlays";
    }

    for (const float clear : {1e37f, std::numeric_limits<float>::infinity()}) {
        render::FrameEdits bright;
        bright.list = [clear](gpu::DrawList& list) { list.target.clear = {clear, 0.0f, 0.0f, 1.0f}; };
        auto f = draw(plastic(), o, bright);
        ASSERT_TRUE(f) << f.error().describe();
        EXPECT_TRUE(f->readback.hostChecked) << "clear " << clear;
        if (std::isinf(clear))
            EXPECT_GT(f->readback.nonFinite, 100u) << "the background is Inf";
        else
            EXPECT_EQ(f->readback.nonFinite, 0u) << "clear " << clear;
    }
}

// Left to choose (OutputGuard::Auto), the vertex stage checks only where that costs less than
// the host's pass: vertices under a 32nd of the pixels. The pre-pass and the floor always
// check (it costs them nothing).
TEST_F(OutputGuard, AutoGuardsTheVertexStageOnlyWhereItCostsLessThanTheHostsPass) {
    const Mode gouraud = modes()[0], flat = modes()[1];
    if (!usable(gouraud)) GTEST_SKIP() << "the device lacks vertexPipelineStoresAndAtomics";
    render::FrameEdits autoGuard;
    autoGuard.list = [](gpu::DrawList& list) { list.outputGuard = gpu::OutputGuard::Auto; };
    struct Row {
        int w, h;
        const Mode& mode;
        bool vouched;
    };
    // 325 vertices x 32 = 10,400: under 128 x 96 = 12,288 pixels, over 96 x 96 = 9,216.
    for (const Row& r : {Row{128, 96, gouraud, true}, Row{96, 96, gouraud, false},
                         Row{96, 96, flat, true}}) {
        RenderOptions o = optionsOf(r.mode);
        o.width = r.w;
        o.height = r.h;
        auto f = draw(plastic(), o, autoGuard);
        ASSERT_TRUE(f) << f.error().describe();
        EXPECT_EQ(f->readback.hostChecked, !r.vouched) << r.mode.name << " " << r.w << "x" << r.h;
    }
}

} // namespace
