// Only what the scene requires: the features a scene uses select the pipeline variant
// (specialisation constants), --explain reports both, and variants are cached.
#include "LightingCompare.h"

#include <algorithm>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

std::string joined(const FeatureReport& r) {
    std::string s = "features:";
    for (const auto& f : r.features)
        s += "\n  " + f;
    s += "\nvariants:";
    for (const auto& v : r.variants)
        s += "\n  " + v;
    return s;
}

Scene oneDirectionalNoSpecular() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 16, 8), Material{}, glm::dmat4(1.0)}); // GL: specular 0
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    return s.build();
}

Scene everyCostlyFeature() {
    LitScene s;
    const Material m = test::phongMaterial({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8, 1}, {1, 1, 1}, 30.0);
    s.objects.push_back({makeSphere(1.0, 16, 8), m, glm::dmat4(1.0)});
    Light spot = test::makeLight(LightType::Spot);
    spot.spotCutoffDeg = 30.0;
    spot.attenuation = {1.0, 0.1, 0.0};
    s.lights.push_back({spot, test::aimed({0, 0, 3}, {0, 0, -1})});
    Light gltf = test::makeLight(LightType::Point);
    gltf.falloff = LightFalloff::Gltf;
    s.lights.push_back({gltf, test::translation({2, 2, 2})});
    return s.build();
}

class LightingVariants : public GpuTest {};

// One directional light and no specular: no spot, attenuation, falloff or specular code.
TEST_F(LightingVariants, OneDirectionalLightWithoutSpecularCompilesNothingElse) {
    const Scene scene = oneDirectionalNoSpecular();
    const RenderOptions o = test::optionsFor(48, 48, ShadingMode::Phong);
    auto r = renderer().explain(scene, o);
    ASSERT_TRUE(r) << r.error().describe();
    const std::string all = joined(*r);
    EXPECT_TRUE(anyContains(r->features, "light:directional x1")) << all;
    EXPECT_TRUE(anyContains(r->features, "specular:none")) << all;
    for (const char* absent :
         {"point", "spot", "attenuation", "falloff", "specular:blinn", "specular:phong"})
        EXPECT_FALSE(anyContains(r->features, absent)) << absent << "\n" << all;
    ASSERT_EQ(r->variants.size(), 1u) << all;
    EXPECT_NE(r->variants[0].find("phong: lights=directional unrolled=1 specular=none"),
              std::string::npos)
        << all;
    for (const char* absent :
         {"attenuation", "gl-spot", "gltf-falloff", "point", "spot ", "vertex-color", "texture",
          "alpha-mask", "two-sided", "local-viewer"})
        EXPECT_EQ(r->variants[0].find(absent), std::string::npos) << absent << "\n" << all;
    // The constants themselves, as the pipeline receives them.
    auto plan = render::planFrame(scene, o, 0.0);
    ASSERT_TRUE(plan);
    const auto& sc = plan->list.views[0].draws[0].pipeline.constants;
    EXPECT_EQ(sc[LANTERN_SC_LIGHT_TYPES], std::uint32_t(LANTERN_LIGHT_BIT_DIRECTIONAL));
    EXPECT_EQ(sc[LANTERN_SC_GL_ATTENUATION], 0u);
    EXPECT_EQ(sc[LANTERN_SC_GL_SPOT], 0u);
    EXPECT_EQ(sc[LANTERN_SC_GLTF_FALLOFF], 0u);
    EXPECT_EQ(sc[LANTERN_SC_SPECULAR], std::uint32_t(LANTERN_SPECULAR_NONE));
    EXPECT_EQ(sc[LANTERN_SC_UNROLLED_LIGHTS], 1u);
    EXPECT_EQ(sc[LANTERN_SC_LIGHT_KINDS], std::uint32_t(LANTERN_LIGHT_DIRECTIONAL));
    EXPECT_EQ(sc[LANTERN_SC_LIGHTS_UNIFORM], 0u);  // unrolled: the storage buffer
    // And the specialised pipeline renders the equation.
    const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
    EXPECT_LE(c.worst, 1.0 / 255.0) << c.describe("variant_minimal");
}

// The same scene with a GL spot with attenuation and a glTF light: all of it is compiled in.
TEST_F(LightingVariants, CostlyFeaturesAppearWhenUsed) {
    const Scene scene = everyCostlyFeature();
    auto r = renderer().explain(scene, test::optionsFor(48, 48, ShadingMode::Phong));
    ASSERT_TRUE(r) << r.error().describe();
    const std::string all = joined(*r);
    for (const char* present : {"light:spot x1", "light:point x1", "attenuation:gl", "spot-cone:gl",
                                "falloff:gltf", "specular:blinn"})
        EXPECT_TRUE(anyContains(r->features, present)) << present << "\n" << all;
    ASSERT_EQ(r->variants.size(), 1u) << all;
    for (const char* present :
         {"lights=point+spot", "specular=blinn", "attenuation", "gl-spot", "gltf-falloff"})
        EXPECT_NE(r->variants[0].find(present), std::string::npos) << present << "\n" << all;
}

// FeatureMode::AllFeatures turns every costly feature on, and still draws the same picture.
TEST_F(LightingVariants, AllFeaturesVariantDrawsTheSamePicture) {
    const Scene scene = oneDirectionalNoSpecular();
    RenderOptions o = test::optionsFor(48, 48, ShadingMode::Phong);
    auto minimal = renderer().render(scene, o, 0.0);
    o.features = FeatureMode::AllFeatures;
    auto r = renderer().explain(scene, o);
    ASSERT_TRUE(r && minimal);
    ASSERT_EQ(r->variants.size(), 1u);
    for (const char* present : {"lights=directional+point+spot", "attenuation", "gl-spot",
                                "gltf-falloff", "vertex-color", "texture", "alpha-mask"})
        EXPECT_NE(r->variants[0].find(present), std::string::npos) << present << "\n" << joined(*r);
    auto full = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(full);
    for (std::size_t i = 0; i < full->rgba.size(); ++i)
        ASSERT_NEAR(full->rgba[i], minimal->rgba[i], 1e-6) << i;
}

// `scene` with `count` - 1 more point lights (GL falloff), for the unrolled-light tests.
Scene withPointLights(LitScene s, int count) {
    for (int i = 1; i < count; ++i) {
        Light l = test::makeLight(LightType::Point);
        l.diffuse = l.specular = glm::dvec3(0.5 / count);
        s.lights.push_back({l, test::translation({0.5 * i - 2.0, 1.5, 3.0})});
    }
    return s.build();
}

// Up to LANTERN_MAX_UNROLLED_LIGHTS lights are unrolled, each compiled for its own kind (type
// and falloff, as the light's packed LightData says); more lights, and the all-features
// variant, loop over frame.lightCount.
TEST_F(LightingVariants, AFewLightsAreUnrolledEachForItsKind) {
    const Scene costly = everyCostlyFeature();  // a GL spot, then a glTF point light
    RenderOptions o = test::optionsFor(48, 48, ShadingMode::Gouraud);
    auto plan = render::planFrame(costly, o, 0.0);
    ASSERT_TRUE(plan) << plan.error().describe();
    const gpu::ViewCommands& view = plan->list.views[0];
    ASSERT_EQ(view.lights.size(), 2u);
    const auto& sc = view.draws[0].pipeline.constants;
    EXPECT_EQ(sc[LANTERN_SC_UNROLLED_LIGHTS], 2u);
    EXPECT_EQ(sc[LANTERN_SC_LIGHT_KINDS],
              std::uint32_t(LANTERN_LIGHT_SPOT | LANTERN_FALLOFF_GL << 2 |
                            (LANTERN_LIGHT_POINT | LANTERN_FALLOFF_GLTF << 2) << 4));
    for (std::size_t i = 0; i < view.lights.size(); ++i)
        EXPECT_EQ((sc[LANTERN_SC_LIGHT_KINDS] >> (4 * i)) & 0xFu,
                  view.lights[i].info.x | view.lights[i].info.y << 2)
            << "light " << i << ": the kind compiled in is not the light's";

    LitScene base;
    base.objects.push_back({makeSphere(1.0, 16, 8), Material{}, glm::dmat4(1.0)});
    base.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    for (const int count : {LANTERN_MAX_UNROLLED_LIGHTS, LANTERN_MAX_UNROLLED_LIGHTS + 1}) {
        auto p = render::planFrame(withPointLights(base, count), o, 0.0);
        ASSERT_TRUE(p) << p.error().describe();
        EXPECT_EQ(p->list.views[0].draws[0].pipeline.constants[LANTERN_SC_UNROLLED_LIGHTS],
                  count <= LANTERN_MAX_UNROLLED_LIGHTS ? std::uint32_t(count) : 0u)
            << count << " lights";
    }
    o.features = FeatureMode::AllFeatures;
    auto all = render::planFrame(costly, o, 0.0);
    ASSERT_TRUE(all);
    EXPECT_EQ(all->list.views[0].draws[0].pipeline.constants[LANTERN_SC_UNROLLED_LIGHTS], 0u);
}

// A loop over up to LANTERN_UNIFORM_LIGHTS lights reads them from the uniform buffer; unrolled
// lights, more lights and the all-features variant read the storage buffer.
TEST_F(LightingVariants, ALoopOverAUniformBuffersLightsReadsThemFromOne) {
    LitScene base;
    base.objects.push_back({makeSphere(1.0, 16, 8), Material{}, glm::dmat4(1.0)});
    base.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    RenderOptions o = test::optionsFor(32, 32, ShadingMode::Gouraud);
    for (const int count : {LANTERN_MAX_UNROLLED_LIGHTS, LANTERN_MAX_UNROLLED_LIGHTS + 1,
                            LANTERN_UNIFORM_LIGHTS, LANTERN_UNIFORM_LIGHTS + 1}) {
        auto p = render::planFrame(withPointLights(base, count), o, 0.0);
        ASSERT_TRUE(p) << p.error().describe();
        const bool uniform = count > LANTERN_MAX_UNROLLED_LIGHTS && count <= LANTERN_UNIFORM_LIGHTS;
        EXPECT_EQ(p->list.views[0].draws[0].pipeline.constants[LANTERN_SC_LIGHTS_UNIFORM],
                  uniform ? 1u : 0u)
            << count << " lights";
    }
    o.features = FeatureMode::AllFeatures;
    auto all = render::planFrame(withPointLights(base, 2), o, 0.0);
    ASSERT_TRUE(all);
    EXPECT_EQ(all->list.views[0].draws[0].pipeline.constants[LANTERN_SC_LIGHTS_UNIFORM], 0u);
}

// A specular sphere under three kinds of light: directional, a GL spot with attenuation, a
// glTF point light.
LitScene threeKindsOfLight() {
    LitScene s;
    s.objects.push_back(
        {makeSphere(1.0, 32, 16),
         test::phongMaterial({0.1, 0.1, 0.1}, {0.6, 0.6, 0.6, 1}, {1, 1, 1}, 20.0), glm::dmat4(1.0)});
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0.3, -0.3, -1})});
    Light spot = test::makeLight(LightType::Spot);
    spot.spotCutoffDeg = 12.0;
    spot.attenuation = {1.0, 0.1, 0.0};
    s.lights.push_back({spot, test::aimed({0.3, 0.3, 3}, {-0.1, -0.1, -1})});
    Light gltf = test::makeLight(LightType::Point);
    gltf.falloff = LightFalloff::Gltf;
    s.lights.push_back({gltf, test::translation({-2, 1, 2})});
    return s;
}

// The unrolled lights draw the loop's picture in every mode, and their kinds are used: the spot
// compiled as a point light is refused by the reference.
TEST_F(LightingVariants, UnrolledLightsDrawTheLoopsPicture) {
    const LitScene s = threeKindsOfLight();
    const Scene scene = s.build();
    test::PixelCheck check;
    check.skipSilhouettes = true;
    render::FrameEdits loop;
    loop.list = [](gpu::DrawList& list) {
        for (gpu::ViewCommands& v : list.views)
            for (gpu::DrawCommand& d : v.draws) d.pipeline.constants[LANTERN_SC_UNROLLED_LIGHTS] = 0;
    };
    for (const ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
        const RenderOptions o = test::optionsFor(64, 64, mode);
        auto unrolled = test::renderWithIds(device(), scene, o, {}, 0.0);
        auto looped = test::renderWithIds(device(), scene, o, loop, 0.0);
        ASSERT_TRUE(unrolled && looped);
        const std::vector<float>& a = unrolled->readback.image.rgba;
        const std::vector<float>& b = looped->readback.image.rgba;
        ASSERT_EQ(a.size(), b.size());
        float worst = 0.0f;
        for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
        EXPECT_LE(worst, 1e-6f) << toString(mode);
        EXPECT_GT(test::brightestColour(unrolled->readback.image), 0.3f) << toString(mode);
        const test::ReferenceComparison right = test::compareWithReference(device(), scene, o, check);
        EXPECT_LE(right.worst, 1.0 / 255.0) << right.describe("unrolled");
    }
    render::FrameEdits wrongKind;
    wrongKind.list = [](gpu::DrawList& list) {
        for (gpu::ViewCommands& v : list.views)
            for (gpu::DrawCommand& d : v.draws) {
                std::uint32_t& kinds = d.pipeline.constants[LANTERN_SC_LIGHT_KINDS];
                ASSERT_EQ((kinds >> 4) & 3u, std::uint32_t(LANTERN_LIGHT_SPOT));
                kinds = (kinds & ~0x30u) | LANTERN_LIGHT_POINT << 4;  // the spot as a point light
            }
    };
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    const test::ReferenceComparison c = test::compareWithReference(device(), scene, o, check, wrongKind);
    EXPECT_GT(c.worst, 0.1) << "the reference did not notice the spot compiled as a point light";
}

// The lights read from the uniform buffer draw the storage buffer's picture, looped (12 lights)
// and unrolled (3: read from the uniform buffer only when forced), in every mode, and the
// reference accepts both.
TEST_F(LightingVariants, UniformLightsDrawTheStorageBuffersPicture) {
    const LitScene s = threeKindsOfLight();
    LitScene many = s;
    for (int i = 0; i < 9; ++i) {
        Light l = test::makeLight(LightType::Point);
        l.diffuse = l.specular = glm::dvec3(0.05);
        l.attenuation = {1.0, 0.0, 0.05 * i};
        many.lights.push_back({l, test::translation({0.6 * i - 2.4, -1.5, 2.5})});
    }
    test::PixelCheck check;
    check.skipSilhouettes = true;
    auto reading = [](std::uint32_t fromUniform) {
        render::FrameEdits e;
        e.list = [fromUniform](gpu::DrawList& list) {
            for (gpu::ViewCommands& v : list.views)
                for (gpu::DrawCommand& d : v.draws)
                    d.pipeline.constants[LANTERN_SC_LIGHTS_UNIFORM] = fromUniform;
        };
        return e;
    };
    const LitScene* const scenes[] = {&s, &many};
    for (const LitScene* lit : scenes) {
        const Scene scene = lit->build();
        for (const ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
            const RenderOptions o = test::optionsFor(64, 64, mode);
            auto uniform = test::renderWithIds(device(), scene, o, reading(1), 0.0);
            auto stored = test::renderWithIds(device(), scene, o, reading(0), 0.0);
            ASSERT_TRUE(uniform && stored);
            EXPECT_LE(test::maxAbsDifference(uniform->readback.image, stored->readback.image), 1e-6f)
                << toString(mode) << ", " << lit->lights.size() << " lights";
            EXPECT_GT(test::brightestColour(uniform->readback.image), 0.3f) << toString(mode);
            const test::ReferenceComparison right =
                test::compareWithReference(device(), scene, o, check, reading(1));
            EXPECT_LE(right.worst, 1.0 / 255.0)
                << right.describe("uniform lights") << ", " << lit->lights.size() << " lights";
        }
    }
}

// Variants are created once and reused.
TEST_F(LightingVariants, PipelinesAreCached) {
    const Scene scene = everyCostlyFeature();
    const RenderOptions o = test::optionsFor(32, 32, ShadingMode::Gouraud);
    ASSERT_TRUE(renderer().render(scene, o, 0.0));
    ASSERT_TRUE(renderer().render(scene, o, 0.0));
    EXPECT_EQ(renderer().lastFrameStats().pipelinesCreated, 0u);
}

// The command prints the features and the variants.
class LightingExplainCli : public GpuTest {}; // skips without a device

TEST_F(LightingExplainCli, PrintsFeaturesAndVariants) {
    const auto dir = test::testOutputDir();
    const auto r = test::runLantern({"render", "builtin:spheres", "--width", "32", "--height", "24",
                                     "--explain", "-o", (dir / "explain.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* text :
         {"features:", "light:directional x1", "light:point x1", "attenuation:gl", "specular:blinn",
          "pipeline variants:", "phong: lights=directional+point"})
        EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
}

// The reference is independent of the pipeline variants: it reads the scene's materials and
// the frame's lighting switches, not the specialisation constants. So a variant compiled
// with one term switched off that the scene needs (here the specular term of a shiny sphere,
// or the vertex colours of a coloured one) renders a picture the reference refuses, while
// the right variant agrees to one 8-bit step.
TEST_F(LightingVariants, AWrongSpecialisationFailsAgainstTheReference) {
    struct Row {
        const char* name;
        int constant;
        std::uint32_t wrongValue;
        ShadingMode mode;
    };
    LitScene shiny;
    shiny.objects.push_back(
        {makeSphere(1.0, 32, 16),
         test::phongMaterial({0.1, 0.1, 0.1}, {0.5, 0.5, 0.5, 1}, {1, 1, 1}, 20.0), glm::dmat4(1.0)});
    shiny.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0.3, -0.3, -1})});
    LitScene coloured = shiny;
    Primitive& p = coloured.objects[0].primitive;
    for (const glm::vec3& v : p.positions) p.colors.push_back(glm::vec4(v * 0.5f + 0.5f, 1.0f));
    for (const Row& row : {Row{"specular_off", LANTERN_SC_SPECULAR, LANTERN_SPECULAR_NONE, ShadingMode::Phong},
                           Row{"specular_off_gouraud", LANTERN_SC_SPECULAR, LANTERN_SPECULAR_NONE,
                               ShadingMode::Gouraud},
                           Row{"vertex_colors_off", LANTERN_SC_VERTEX_COLOR, 0u, ShadingMode::Phong}}) {
        const Scene scene = row.constant == LANTERN_SC_VERTEX_COLOR ? coloured.build() : shiny.build();
        const RenderOptions o = test::optionsFor(64, 64, row.mode);
        test::PixelCheck check;
        check.skipSilhouettes = true;
        const test::ReferenceComparison right = test::compareWithReference(device(), scene, o, check);
        EXPECT_GT(right.compared, 500u) << row.name;
        EXPECT_LE(right.worst, 1.0 / 255.0) << row.name << ": " << right.describe(row.name);
        render::FrameEdits wrong;
        wrong.list = [&](gpu::DrawList& list) {
            for (gpu::ViewCommands& v : list.views)
                for (gpu::DrawCommand& d : v.draws) {
                    ASSERT_NE(d.pipeline.constants[std::size_t(row.constant)], row.wrongValue)
                        << row.name << ": the scene needs this term";
                    d.pipeline.constants[std::size_t(row.constant)] = row.wrongValue;
                }
        };
        const test::ReferenceComparison c =
            test::compareWithReference(device(), scene, o, check, wrong);
        EXPECT_GT(c.worst, 0.1) << row.name << ": the reference did not notice the missing term";
    }
}

} // namespace

