// The glTF loader's scene mapping: LANTERN_materials_phong and the PBR fallback, unlit and alpha
// modes, base-colour textures, KHR_lights_punctual with and without LANTERN_lights_phong,
// cameras (perspective with and without zfar, orthographic, LANTERN_camera), LANTERN_lighting,
// nodes and scenes; each bad value refused with its object path and reason.
#include "GltfTestSupport.h"

#include "io/gltf/GltfInternal.h"

#include <lantern/Renderer.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::GltfBuilder;
using lantern::test::loadCapturing;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using json = nlohmann::json;


/// A triangle using material 0 = `material`.
Result<Scene> loadMaterial(const json& material, const std::string& name = "m") {
    GltfBuilder b;
    b.doc["materials"] = json::array({material});
    b.addTriangle({{"material", 0}});
    return loadCapturing(b.write(testOutputDir(), name)).scene;
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, const char* what) {
    EXPECT_LT(glm::length(a - b), 1e-12) << what << ": (" << a.x << "," << a.y << "," << a.z << ") vs ("
                                         << b.x << "," << b.y << "," << b.z << ")";
}

// --- Materials ------------------------------------------------------------------------------

// The mapping of docs/scene-format-support.md ("Materials"), each value worked out by hand:
// f0 = mix(0.04, b, m), w = r^2; diffuse = b(1-m) + f0 w m; s = clamp(2/r^4 - 2, 1, 1e4);
// specular = f0 (1 - w m) (s + 8)/8.
TEST(GltfScene, PbrFallbackMapsAsDocumented) {
    struct Case {
        glm::dvec4 base;
        double metallic, roughness;
        glm::dvec3 diffuse, specular;
        double shininess;
        const char* why;
    };
    const Case cases[] = {
        {{1.0, 1.0, 1.0, 1.0}, 1.0, 1.0, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, 1.0,
         "glTF's default (metal, roughness 1): all of it diffuse, a matte light surface"},
        {{0.8, 0.4, 0.2, 1.0}, 0.0, 1.0, {0.8, 0.4, 0.2}, {0.045, 0.045, 0.045}, 1.0,
         "rough dielectric: 2/1-2 = 0 raised to 1; specular 0.04 * 9/8"},
        {{0.8, 0.4, 0.2, 0.5}, 1.0, 0.5, {0.2, 0.1, 0.05}, {2.85, 1.425, 0.7125}, 30.0,
         "metal: w = 0.25 of the base diffuse; s = 2/0.0625-2 = 30; base * 0.75 * 38/8"},
        {{0.5, 0.5, 0.5, 1.0}, 0.25, 0.2, glm::dvec3(0.375 + 0.155 * 0.04 * 0.25),
         glm::dvec3(0.155 * 0.99 * 1256.0 / 8.0), 1248.0, "mixed: f0 = 0.155, s = 2/0.0016-2"},
        {{1.0, 1.0, 1.0, 1.0}, 0.0, 0.0, {1.0, 1.0, 1.0}, glm::dvec3(0.04 * 10008.0 / 8.0),
         gltf::kMaxPbrShininess, "roughness 0 clamps to the maximum"},
        {{1.0, 1.0, 1.0, 1.0}, 0.0, 0.05, {1.0, 1.0, 1.0}, glm::dvec3(0.04 * 10008.0 / 8.0),
         gltf::kMaxPbrShininess, "2/r^4-2 = 319998 above the maximum"},
    };
    for (const Case& c : cases) {
        auto s = loadMaterial({{"pbrMetallicRoughness",
                                {{"baseColorFactor", {c.base.r, c.base.g, c.base.b, c.base.a}},
                                 {"metallicFactor", c.metallic},
                                 {"roughnessFactor", c.roughness}}},
                               {"emissiveFactor", {0.1, 0.2, 0.3}}});
        ASSERT_TRUE(s) << s.error().describe();
        const Material& m = s->materials[0];
        EXPECT_LT(glm::length(glm::dvec3(m.front.diffuse) - c.diffuse), 1e-12) << c.why;
        EXPECT_DOUBLE_EQ(m.front.diffuse.a, c.base.a) << c.why;
        EXPECT_LT(glm::length(m.front.specular - c.specular), 1e-9 * (1.0 + glm::length(c.specular))) << c.why;
        expectNear(m.front.ambient, glm::dvec3(m.front.diffuse), c.why);
        expectNear(m.front.emission, {0.1, 0.2, 0.3}, c.why);
        EXPECT_NEAR(m.front.shininess, c.shininess, 1e-9 * c.shininess) << c.why;
        EXPECT_TRUE(m.ambientFollowsDiffuse) << c.why;
        EXPECT_FALSE(m.back);
    }
}

// A material without pbrMetallicRoughness takes glTF's defaults (base 1, metallic 1,
// roughness 1): before the mapping above, that was diffuse 0 with specular 1 at shininess 0,
// a constant white silhouette.
TEST(GltfScene, AMaterialWithNoFactorsIsAMatteLightSurface) {
    auto s = loadMaterial({{"name", "plain"}});
    ASSERT_TRUE(s) << s.error().describe();
    const Material& m = s->materials[0];
    EXPECT_EQ(glm::dvec3(m.front.diffuse), glm::dvec3(1.0));
    EXPECT_EQ(m.front.specular, glm::dvec3(0.0));
    EXPECT_GE(m.front.shininess, 1.0);
}

TEST(GltfScene, LanternPhongMaterialsTakeGlDefaultsAndBackSides) {
    auto s = loadMaterial({{"extensions",
                            {{"LANTERN_materials_phong",
                              {{"diffuse", {0.1, 0.2, 0.3}},
                               {"shininess", 200.0},
                               {"back", {{"emission", {0.5, 0.5, 0.5}}, {"diffuse", {1, 0, 0, 0.5}}}}}}}}});
    ASSERT_TRUE(s) << s.error().describe();
    const Material& m = s->materials[0];
    expectNear(m.front.ambient, {0.2, 0.2, 0.2}, "GL default ambient");
    EXPECT_EQ(m.front.diffuse, glm::dvec4(0.1, 0.2, 0.3, 1.0));  // RGB given: alpha 1
    expectNear(m.front.specular, {0, 0, 0}, "GL default specular");
    EXPECT_DOUBLE_EQ(m.front.shininess, 200.0);  // not limited to GL's 128
    EXPECT_FALSE(m.ambientFollowsDiffuse);
    ASSERT_TRUE(m.back);
    EXPECT_EQ(m.back->diffuse, glm::dvec4(1, 0, 0, 0.5));
    expectNear(m.back->emission, {0.5, 0.5, 0.5}, "back emission");
    expectNear(m.back->ambient, {0.2, 0.2, 0.2}, "back default ambient");
}

TEST(GltfScene, UnlitAlphaModesAndTheDefaultMaterial) {
    auto unlit = loadMaterial({{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.5, 0, 0.5}}, {"metallicFactor", 1.0}}},
                               {"alphaMode", "BLEND"},
                               {"extensions", {{"KHR_materials_unlit", json::object()}}}});
    ASSERT_TRUE(unlit) << unlit.error().describe();
    EXPECT_TRUE(unlit->materials[0].unlit);
    EXPECT_EQ(unlit->materials[0].front.diffuse, glm::dvec4(1, 0.5, 0, 0.5));  // base colour, not (1-metallic)
    EXPECT_EQ(unlit->materials[0].alphaMode, AlphaMode::Blend);

    auto mask = loadMaterial({{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"doubleSided", true}});
    ASSERT_TRUE(mask);
    EXPECT_EQ(mask->materials[0].alphaMode, AlphaMode::Mask);
    EXPECT_DOUBLE_EQ(mask->materials[0].alphaCutoff, 0.25);
    EXPECT_TRUE(mask->materials[0].doubleSided);

    GltfBuilder b;
    b.addTriangle();
    auto none = loadCapturing(b.write(testOutputDir(), "nomaterial"));
    ASSERT_TRUE(none.scene);
    EXPECT_EQ(none.scene->meshes[0].primitives[0].material, -1);  // GL's default material
}

TEST(GltfScene, BadMaterialValuesAreRefusedWithTheirPath) {
    const std::string ext = "materials[0].extensions.LANTERN_materials_phong";
    struct Case {
        json material;
        std::string object, fragment;
    };
    const Case cases[] = {
        {{{"extensions", {{"LANTERN_materials_phong", {{"shininess", -1}}}}}}, ext + ".shininess", "must be >= 0"},
        {{{"extensions", {{"LANTERN_materials_phong", {{"back", {{"shininess", -0.5}}}}}}}}, ext + ".back.shininess",
         "must be >= 0"},
        {{{"extensions", {{"LANTERN_materials_phong", {{"ambient", {1, 2}}}}}}}, ext + ".ambient",
         "array of 3 numbers"},
        {{{"extensions", {{"LANTERN_materials_phong", {{"diffuse", "red"}}}}}}, ext + ".diffuse", "array of 4"},
        {{{"extensions", {{"LANTERN_materials_phong", {{"shininess", "shiny"}}}}}}, ext + ".shininess",
         "must be a finite number"},
        {{{"pbrMetallicRoughness", {{"roughnessFactor", 1.5}}}}, "materials[0].pbrMetallicRoughness.roughnessFactor",
         "in [0, 1]"},
        {{{"alphaMode", "CUTOUT"}}, "materials[0].alphaMode", "not OPAQUE, MASK or BLEND"},
        {{{"alphaCutoff", -1}}, "materials[0].alphaCutoff", ">= 0"},
        {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}}}},
         "materials[0].pbrMetallicRoughness.baseColorTexture.index", "texture 2 does not exist"},
    };
    GltfBuilder b;
    b.addTriangle({{"material", 0}});
    for (const Case& c : cases) {
        b.doc["materials"] = json::array({c.material});
        EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "bad")), c.object, c.fragment))
            << c.material.dump();
    }
}

/// A 2x1 RGBA PNG: red, then blue at alpha 128 (encoded with zlib, checksums included).
std::vector<unsigned char> tinyPng() {
    return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
            0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0xf4, 0x22, 0x7f,
            0x8a, 0x00, 0x00, 0x00, 0x0e, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0x00,
            0x42, 0x0d, 0x00, 0x0f, 0x7a, 0x03, 0x7e, 0x77, 0xe9, 0x7f, 0x97, 0x00, 0x00, 0x00, 0x00, 0x49,
            0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

TEST(GltfScene, BaseColourTexturesDecodeToRgba8WithSamplerFlags) {
    const auto dir = testOutputDir();
    const auto png = tinyPng();
    GltfBuilder b;
    b.addTriangle({{"material", 0}, {"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}});
    b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(png)}}});
    b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 33071}}});
    b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    auto o = loadCapturing(b.write(dir, "textured"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    ASSERT_EQ(o.scene->textures.size(), 1u);
    const Texture& t = o.scene->textures[0];
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.height, 1);
    EXPECT_EQ(t.rgba8, (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 0, 255, 128}));
    EXPECT_TRUE(t.nearest);
    EXPECT_EQ(t.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(t.wrapT, TextureWrap::Repeat);  // absent: REPEAT
    EXPECT_EQ(o.scene->materials[0].baseColorTexture, 0);
    EXPECT_EQ(o.scene->meshes[0].primitives[0].texcoords.size(), 3u);

    // The same image from a buffer view (as in a GLB).
    GltfBuilder v = b;
    const int view = v.addView(png.data(), png.size());
    v.doc["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
    auto fromView = loadCapturing(v.write(dir, "view", GltfBuilder::Storage::Glb));
    ASSERT_TRUE(fromView.scene) << fromView.scene.error().describe();
    EXPECT_EQ(fromView.scene->textures.at(0).rgba8, t.rgba8);

    // An image that cannot be decoded, or is missing, is an error naming it once a material
    // uses it; unused, it costs nothing and only tinygltf's warning remains.
    GltfBuilder bad = b;
    bad.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64({1, 2, 3, 4, 5, 6})}}});
    EXPECT_TRUE(refusedWith(loadCapturing(bad.write(dir, "bad")), "images[0]", "is not an image Lantern reads"));
    bad.doc["images"] = json::array({{{"uri", "missing.png"}}});
    EXPECT_TRUE(refusedWith(loadCapturing(bad.write(dir, "missing")), "images[0].uri", "does not exist"));
    bad.doc["materials"] = json::array({json::object()});
    EXPECT_TRUE(loadCapturing(bad.write(dir, "unused")).scene);
    // A PNG header claiming 100000 x 100000 pixels is refused before decoding.
    std::vector<unsigned char> huge = png;
    for (int i = 0; i < 2; ++i) {
        const std::uint32_t side = 100000;
        for (int k = 0; k < 4; ++k) huge[16 + std::size_t(i * 4 + k)] = (side >> (24 - 8 * k)) & 0xFF;
    }
    bad.doc["materials"] = b.doc["materials"];
    bad.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(huge)}}});
    auto hugeResult = loadCapturing(bad.write(dir, "huge"));
    ASSERT_FALSE(hugeResult.scene);
    EXPECT_EQ(hugeResult.scene.error().object, "images[0]") << hugeResult.scene.error().describe();
}

// The extension's own example: offset (0, 1), rotation pi/2, scale 0.5 reads "only the lower
// left quadrant of the source image, rotated clockwise 90 degrees".
TEST(GltfScene, TextureTransformMatrixFollowsTheExtensionsExample) {
    const glm::dmat3 m = gltf::textureTransform({0.0, 1.0}, 1.57079632679489661923, {0.5, 0.5});
    auto at = [&](double u, double v) { return glm::dvec2(m * glm::dvec3(u, v, 1.0)); };
    const std::pair<glm::dvec2, glm::dvec2> corners[] = {
        {{0, 0}, {0.0, 1.0}}, {{1, 0}, {0.0, 0.5}}, {{0, 1}, {0.5, 1.0}}, {{1, 1}, {0.5, 0.5}}};
    for (const auto& [uv, expected] : corners)
        EXPECT_LT(glm::length(at(uv.x, uv.y) - expected), 1e-12) << uv.x << "," << uv.y;
}

TEST(GltfScene, TextureTransformIsReadWithItsTexCoordAndBadValuesRefused) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle({{"material", 0}, {"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}}}});
    b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    b.addFloats({5, 5, 6, 5, 5, 6}, "VEC2");
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(tinyPng())}}});
    b.doc["samplers"] = json::array({{{"wrapS", 33648}, {"wrapT", 33071}}});
    b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
    const json transform = {{"offset", {0.25, 0.5}}, {"rotation", 0.5}, {"scale", {2.0, 3.0}}, {"texCoord", 1}};
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}});
    auto o = loadCapturing(b.write(dir, "transformed"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_FALSE(o.warned("KHR_texture_transform")) << "supported, not ignored";
    const glm::dmat3 expected = gltf::textureTransform({0.25, 0.5}, 0.5, {2.0, 3.0});
    const glm::dmat3& got = o.scene->materials[0].baseColorUvTransform;
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(got[c] - expected[c]), 1e-12) << "column " << c;
    // The extension's texCoord (1) overrides the reference's (0).
    EXPECT_EQ(o.scene->meshes[0].primitives[0].texcoords.at(0), glm::vec2(5, 5));
    EXPECT_EQ(o.scene->textures.at(0).wrapS, TextureWrap::MirroredRepeat);
    EXPECT_EQ(o.scene->textures.at(0).wrapT, TextureWrap::ClampToEdge);

    const std::string obj = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform";
    const std::tuple<json, std::string, std::string> bad[] = {
        {{{"offset", {1.0}}}, obj + ".offset", "2"},
        {{{"rotation", "half"}}, obj + ".rotation", "number"},
        // The document-wide number checks see these first, naming the element.
        {{{"scale", {1e31, 1.0}}}, obj + ".scale[0]", "1e30"},
        {{{"texCoord", -1}}, obj + ".texCoord", "0 or more"},
    };
    for (const auto& [value, object, fragment] : bad) {
        GltfBuilder c = b;
        c.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = value;
        EXPECT_TRUE(refusedWith(loadCapturing(c.write(dir, "bad")), object, fragment)) << value.dump();
    }
}

// A 1x1 RGBA PNG (0, 128, 255, 255), encoded with zlib.
std::vector<unsigned char> onePixelPng() {
    return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00,
            0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00,
            0x00, 0x00, 0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60, 0x68, 0xf8, 0xff, 0x1f, 0x00, 0x04,
            0x82, 0x02, 0x7f, 0xe7, 0xd8, 0x5a, 0x6c, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42,
            0x60, 0x82};
}

TEST(GltfScene, MetallicRoughnessTexturesScaleTheFactorsByTheirMean) {
    // One texel: G (roughness) 128, B (metallic) 255 -> metallic 1.0, roughness 128/255.
    GltfBuilder b;
    b.addTriangle({{"material", 0}});
    b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(onePixelPng())}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0.5}, {"metallicRoughnessTexture", {{"index", 0}}}}}}});
    auto o = loadCapturing(b.write(testOutputDir(), "mr"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Material& m = o.scene->materials[0];
    const double metallic = 0.5 * 1.0, roughness = 1.0 * 128.0 / 255.0;
    const double f0 = 0.04 * (1 - metallic) + 0.5 * metallic, w = roughness * roughness;
    expectNear(glm::dvec3(m.front.diffuse), glm::dvec3(0.5 * (1 - metallic) + f0 * w * metallic), "diffuse");
    EXPECT_NEAR(m.front.shininess, 2.0 / std::pow(roughness, 4) - 2.0, 1e-9);
    // Kept as linear data for phong's per-texel mapping, from the unscaled factors.
    ASSERT_EQ(o.scene->textures.size(), 1u);
    EXPECT_FALSE(o.scene->textures[0].srgb);
    EXPECT_EQ(m.metallicRoughnessMap.texture, 0);
    ASSERT_TRUE(m.pbr);
    EXPECT_EQ(m.pbr->metallic, 0.5);
    EXPECT_EQ(m.pbr->roughness, 1.0);
}

TEST(GltfScene, NormalOcclusionAndEmissiveTexturesAreReadAsMapsWithTheirEncoding) {
    GltfBuilder b;
    b.addTriangle({{"material", 0}});
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(onePixelPng())}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    // Texture 0 is the emissive map (colour) and the normal and occlusion maps (data); the
    // occlusion map carries a transform.
    b.doc["materials"] = json::array({{
        {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
        {"occlusionTexture", {{"index", 0}, {"strength", 0.25},
                              {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
        {"emissiveTexture", {{"index", 0}}},
        {"emissiveFactor", {1, 1, 1}}}});
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    auto o = loadCapturing(b.write(testOutputDir(), "maps"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Material& m = o.scene->materials[0];
    ASSERT_EQ(o.scene->textures.size(), 2u) << "one linear and one sRGB copy";
    EXPECT_EQ(m.normalMap.texture, m.occlusionMap.texture);
    EXPECT_FALSE(o.scene->textures[std::size_t(m.normalMap.texture)].srgb);
    EXPECT_TRUE(o.scene->textures[std::size_t(m.emissiveMap.texture)].srgb);
    EXPECT_EQ(m.normalScale, 0.5);
    EXPECT_EQ(m.occlusionStrength, 0.25);
    EXPECT_EQ(m.occlusionMap.uvTransform[2][0], 0.5);
    EXPECT_EQ(m.normalMap.uvTransform, glm::dmat3(1.0));
    EXPECT_FALSE(o.scene->meshes[0].primitives[0].texcoords.empty()) << "TEXCOORD_0 read for the maps";

    // A map on another TEXCOORD set reads the primitive's second set (with a warning where the
    // primitive has none); a third set is left out with a warning; a strength outside [0, 1]
    // is refused with its path.
    b.doc["materials"][0]["emissiveTexture"]["texCoord"] = 1;
    auto other = loadCapturing(b.write(testOutputDir(), "maps_set1"));
    ASSERT_TRUE(other.scene) << other.scene.error().describe();
    EXPECT_GE(other.scene->materials[0].emissiveMap.texture, 0);
    EXPECT_TRUE(other.scene->materials[0].emissiveMap.secondSet);
    EXPECT_FALSE(other.scene->materials[0].occlusionMap.secondSet);
    EXPECT_TRUE(other.warned("no TEXCOORD_1 for the material's maps that read it")) << other.allWarnings();
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = b.addFloats({1, 1, 0, 1, 1, 0}, "VEC2");
    auto second = loadCapturing(b.write(testOutputDir(), "maps_set1_given"));
    ASSERT_TRUE(second.scene) << second.scene.error().describe();
    EXPECT_EQ(second.scene->meshes[0].primitives[0].texcoords1,
              (std::vector<glm::vec2>{{1, 1}, {0, 1}, {1, 0}}));
    EXPECT_EQ(second.scene->meshes[0].primitives[0].texcoords.at(1), glm::vec2(1, 0));
    // The second set is the first other one met (metallic-roughness, normal, occlusion,
    // emissive): occlusion's TEXCOORD_2 here, so the emissive map's TEXCOORD_1 is a third.
    b.doc["materials"][0]["occlusionTexture"]["texCoord"] = 2;
    auto third = loadCapturing(b.write(testOutputDir(), "maps_set2"));
    ASSERT_TRUE(third.scene) << third.scene.error().describe();
    EXPECT_TRUE(third.scene->materials[0].occlusionMap.secondSet);
    EXPECT_EQ(third.scene->materials[0].emissiveMap.texture, -1);
    EXPECT_TRUE(third.warned("reads TEXCOORD_1, a third set beside the material's TEXCOORD_0 and "
                             "TEXCOORD_2")) << third.allWarnings();
    b.doc["materials"][0]["occlusionTexture"]["texCoord"] = 0;
    b.doc["materials"][0]["occlusionTexture"]["strength"] = 2.0;
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "maps_bad")),
                            "materials[0].occlusionTexture.strength", "[0, 1]"));
}

// TANGENT is read for a normal-mapped material (its own or a variant's), not otherwise, and
// the fidelity report says a morphed primitive's tangents give way to derivatives.
TEST(GltfScene, TangentsAreReadForANormalMappedMaterial) {
    GltfBuilder b;
    b.addTriangle({{"material", 0}});
    json& prim = b.doc["meshes"][0]["primitives"][0];
    prim["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    prim["attributes"]["TANGENT"] = b.addFloats({1, 0, 0, 1, 0, 1, 0, -1, -0.6f, 0.8f, 0, 1}, "VEC4");
    b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + GltfBuilder::base64(onePixelPng())}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}}}}, json::object()});
    auto o = loadCapturing(b.write(testOutputDir(), "tangents"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const auto& t = o.scene->meshes[0].primitives[0].tangents;
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[1], glm::vec4(0, 1, 0, -1));
    EXPECT_EQ(t[2], glm::vec4(-0.6f, 0.8f, 0, 1));
    auto keyed = [](const Scene& s, const char* key) -> const FeatureUse* {
        for (const FeatureUse& f : s.features)
            if (f.key == key) return &f;
        return nullptr;
    };
    const FeatureUse* used = keyed(*o.scene, "tangents");
    ASSERT_TRUE(used);
    EXPECT_EQ(used->fidelity, Fidelity::Supported);
    EXPECT_EQ(used->objects, std::vector<std::string>{"meshes[0].primitives[0].attributes.TANGENT"});

    // A morphed primitive's tangents stay (the deformation pass does not move them, so the
    // renderer takes the frame from derivatives): approximated.
    b.doc["meshes"][0]["primitives"][0]["targets"] =
        json::array({{{"POSITION", b.addFloats({0, 0, 0.1f, 0, 0, 0, 0, 0, 0}, "VEC3")}}});
    auto m = loadCapturing(b.write(testOutputDir(), "tangents_morphed"));
    ASSERT_TRUE(m.scene) << m.scene.error().describe();
    ASSERT_TRUE(keyed(*m.scene, "tangents"));
    EXPECT_EQ(keyed(*m.scene, "tangents")->fidelity, Fidelity::Approximated);
    EXPECT_EQ(keyed(*m.scene, "tangents")->rule, "derivative-frame-when-deformed");
    b.doc["meshes"][0]["primitives"][0].erase("targets");

    // Without a normal map nothing reads them: they are not kept.
    b.doc["meshes"][0]["primitives"][0]["material"] = 1;
    auto plain = loadCapturing(b.write(testOutputDir(), "tangents_unused"));
    ASSERT_TRUE(plain.scene) << plain.scene.error().describe();
    EXPECT_TRUE(plain.scene->meshes[0].primitives[0].tangents.empty());
    EXPECT_FALSE(keyed(*plain.scene, "tangents"));

    // A TANGENT that is not a VEC4 of floats is refused with its path.
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] =
        b.addFloats({1, 0, 0, 0, 1, 0, 1, 0, 0}, "VEC3");
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "tangents_vec3")),
                            "meshes[0].primitives[0].attributes.TANGENT", "expected VEC4"));
}

// --- Lights ---------------------------------------------------------------------------------

Result<Scene> loadLights(const json& lights, const std::string& name = "lights") {
    GltfBuilder b;
    b.addTriangle();
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    for (std::size_t i = 0; i < lights.size(); ++i)
        b.addNode({{"translation", {double(i), 2.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
    return loadCapturing(b.write(testOutputDir(), name)).scene;
}

TEST(GltfScene, PunctualLightsMapToGltfFalloffOrToGlWithTheExtension) {
    auto s = loadLights(json::array(
        {{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 4.0}, {"range", 10.0}},
         {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}},
         {{"type", "directional"}, {"intensity", 2.0}},
         {{"type", "spot"},
          {"spot", json::object()},
          {"extensions",
           {{"LANTERN_lights_phong",
             {{"ambient", {0.1, 0.1, 0.1}},
              {"diffuse", {0.9, 0.8, 0.7}},
              {"specular", {0.5, 0.5, 0.5}},
              {"attenuation", {1.0, 0.5, 0.25}},
              {"spotExponent", 16.0},
              {"spotCutoffDeg", 30.0}}}}}},
         {{"type", "point"}, {"extensions", {{"LANTERN_lights_phong", json::object()}}}}}));
    ASSERT_TRUE(s) << s.error().describe();
    ASSERT_EQ(s->lights.size(), 5u);
    const Light& point = s->lights[0];
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_EQ(point.falloff, LightFalloff::Gltf);
    expectNear(point.diffuse, {4, 2, 1}, "diffuse = color * intensity");
    expectNear(point.specular, {4, 2, 1}, "specular = color * intensity");
    expectNear(point.ambient, {0, 0, 0}, "ambient 0");
    EXPECT_DOUBLE_EQ(point.range, 10.0);
    const Light& spot = s->lights[1];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_TRUE(std::isinf(spot.range));  // no range: unlimited
    EXPECT_DOUBLE_EQ(spot.innerConeAngle, 0.1);
    EXPECT_DOUBLE_EQ(spot.outerConeAngle, 0.5);
    expectNear(spot.diffuse, {1, 1, 1}, "default colour white, intensity 1");
    expectNear(s->lights[2].diffuse, {2, 2, 2}, "directional");
    const Light& gl = s->lights[3];
    EXPECT_EQ(gl.falloff, LightFalloff::Gl);
    expectNear(gl.ambient, {0.1, 0.1, 0.1}, "GL ambient");
    expectNear(gl.diffuse, {0.9, 0.8, 0.7}, "GL diffuse");
    expectNear(gl.attenuation, {1.0, 0.5, 0.25}, "attenuation");
    EXPECT_DOUBLE_EQ(gl.spotExponent, 16.0);
    EXPECT_DOUBLE_EQ(gl.spotCutoffDeg, 30.0);
    const Light& glDefaults = s->lights[4];
    EXPECT_EQ(glDefaults.falloff, LightFalloff::Gl);
    expectNear(glDefaults.attenuation, {1, 0, 0}, "GL default attenuation");
    expectNear(glDefaults.diffuse, {1, 1, 1}, "GL default diffuse");
    EXPECT_DOUBLE_EQ(glDefaults.spotCutoffDeg, 180.0);
    // Each light is placed by its node.
    EXPECT_EQ(s->nodes[1].light, 0);
    EXPECT_EQ(s->nodes[5].light, 4);
}

// LANTERN_lights_shadow: present, the light casts shadows unless castShadows is false; a value
// that is not a boolean is refused with its path.
TEST(GltfScene, LightsCastShadowsWithTheExtension) {
    auto shadow = [](json value) {
        return json{{"type", "point"}, {"extensions", {{"LANTERN_lights_shadow", value}}}};
    };
    auto s = loadLights(json::array({shadow(json::object()), shadow({{"castShadows", false}}),
                                     shadow({{"castShadows", true}}), {{"type", "directional"}}}));
    ASSERT_TRUE(s) << s.error().describe();
    ASSERT_EQ(s->lights.size(), 4u);
    EXPECT_TRUE(s->lights[0].castShadows);
    EXPECT_FALSE(s->lights[1].castShadows);
    EXPECT_TRUE(s->lights[2].castShadows);
    EXPECT_FALSE(s->lights[3].castShadows) << "no extension: no shadows";
    GltfBuilder b;
    b.addTriangle();
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({shadow({{"castShadows", 1}})});
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "bad-shadow")),
                            "extensions.KHR_lights_punctual.lights[0].extensions.LANTERN_lights_shadow.castShadows",
                            "must be true or false"));
}

TEST(GltfScene, BadLightValuesAreRefusedWithTheReason) {
    const std::string ext = "extensions.KHR_lights_punctual.lights[0].extensions.LANTERN_lights_phong";
    struct Case {
        json light;
        std::string object, fragment;
    };
    auto phong = [](json values) {
        return json{{"type", "spot"}, {"spot", json::object()}, {"extensions", {{"LANTERN_lights_phong", values}}}};
    };
    const Case cases[] = {
        {phong({{"spotCutoffDeg", 95.0}}), ext + ".spotCutoffDeg", "outside [0, 90] and not 180"},
        {phong({{"spotCutoffDeg", -0.1}}), ext + ".spotCutoffDeg", "not 180 (GL's no-cone value)"},
        {phong({{"spotCutoffDeg", 90.0001}}), ext + ".spotCutoffDeg", "outside [0, 90]"},
        {phong({{"attenuation", {0, 0, 0}}}), ext + ".attenuation", "all zero"},
        {phong({{"attenuation", {1, -0.5, 0}}}), ext + ".attenuation", "must be >= 0"},
        {phong({{"spotExponent", -1}}), ext + ".spotExponent", "must be >= 0"},
        {{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}}}},
         "extensions.KHR_lights_punctual.lights[0].spot", "innerConeAngle"},
        {{{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}}, "extensions.KHR_lights_punctual.lights[0].spot",
         "<= pi/2"},
        {{{"type", "area"}}, "extensions.KHR_lights_punctual.lights[0].type", "not directional, point or spot"},
        {{{"type", "point"}, {"intensity", -1}}, "extensions.KHR_lights_punctual.lights[0].intensity", ">= 0"},
        {{{"type", "point"}, {"range", -1}}, "extensions.KHR_lights_punctual.lights[0].range", "> 0"},
        {{{"type", "point"}, {"color", {1, 1}}}, "extensions.KHR_lights_punctual.lights[0].color", "3 finite"},
    };
    for (const Case& c : cases) {
        GltfBuilder b;
        b.addTriangle();
        b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({c.light});
        b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "bad")), c.object, c.fragment))
            << c.light.dump();
    }
    // The accepted edge values: 0, 90 and 180 degrees.
    for (double cutoff : {0.0, 90.0, 180.0})
        EXPECT_TRUE(loadLights(json::array({phong({{"spotCutoffDeg", cutoff}})}))) << cutoff;
}

// --- Cameras ----------------------------------------------------------------------------------

Result<Scene> loadCamera(const json& camera, const std::string& name = "camera") {
    GltfBuilder b;
    b.addTriangle();
    b.doc["cameras"] = json::array({camera});
    b.addNode({{"camera", 0}, {"translation", {0, 0, 5}}});
    return loadCapturing(b.write(testOutputDir(), name)).scene;
}

TEST(GltfScene, CamerasMapEveryForm) {
    auto finite = loadCamera({{"type", "perspective"},
                              {"perspective", {{"yfov", 0.8}, {"znear", 0.5}, {"zfar", 50.0}, {"aspectRatio", 1.5}}}});
    ASSERT_TRUE(finite) << finite.error().describe();
    const Projection& p = finite->cameras[0].projection;
    EXPECT_EQ(p.kind, ProjectionKind::Perspective);
    EXPECT_DOUBLE_EQ(p.yfov, 0.8);
    EXPECT_DOUBLE_EQ(p.aspect, 1.5);
    EXPECT_DOUBLE_EQ(p.znear, 0.5);
    EXPECT_DOUBLE_EQ(p.zfar, 50.0);

    auto infinite = loadCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.5}}}});
    ASSERT_TRUE(infinite);
    EXPECT_TRUE(std::isinf(infinite->cameras[0].projection.zfar));  // glTF: no zfar is infinite
    EXPECT_DOUBLE_EQ(infinite->cameras[0].projection.aspect, 0.0);  // the viewport's aspect

    auto ortho = loadCamera({{"type", "orthographic"},
                             {"orthographic", {{"xmag", 2.0}, {"ymag", 1.5}, {"znear", 0.0}, {"zfar", 20.0}}}});
    ASSERT_TRUE(ortho);
    const Projection& o = ortho->cameras[0].projection;
    EXPECT_EQ(o.kind, ProjectionKind::Orthographic);
    EXPECT_EQ(std::vector<double>({o.left, o.right, o.bottom, o.top, o.znear, o.zfar}),
              std::vector<double>({-2.0, 2.0, -1.5, 1.5, 0.0, 20.0}));

    const json base = {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.5}}}};
    json frustum = base;
    frustum["extensions"]["LANTERN_camera"] = {
        {"frustum", {{"left", -1}, {"right", 2}, {"bottom", -0.5}, {"top", 1}, {"near", 1}, {"far", 100}}},
        {"lookAt", {{"eye", {0, 0, 5}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}}}}};
    auto f = loadCamera(frustum);
    ASSERT_TRUE(f) << f.error().describe();
    const Projection& fp = f->cameras[0].projection;
    EXPECT_EQ(fp.kind, ProjectionKind::Frustum);
    EXPECT_EQ(std::vector<double>({fp.left, fp.right, fp.bottom, fp.top, fp.znear, fp.zfar}),
              std::vector<double>({-1, 2, -0.5, 1, 1, 100}));
    ASSERT_TRUE(f->cameras[0].lookAt);
    EXPECT_EQ(f->cameras[0].lookAt->eye, glm::dvec3(0, 0, 5));

    json farless = base;
    farless["extensions"]["LANTERN_camera"] = {
        {"frustum", {{"left", -1}, {"right", 1}, {"bottom", -1}, {"top", 1}, {"near", 1}}}};
    auto fl = loadCamera(farless);
    ASSERT_TRUE(fl) << fl.error().describe();
    EXPECT_TRUE(std::isinf(fl->cameras[0].projection.zfar));

    json glOrtho = base;
    glOrtho["extensions"]["LANTERN_camera"] = {
        {"ortho", {{"left", -2}, {"right", 2}, {"bottom", -2}, {"top", 2}, {"near", -10}, {"far", 10}}}};
    auto go = loadCamera(glOrtho);
    ASSERT_TRUE(go) << go.error().describe();
    EXPECT_EQ(go->cameras[0].projection.kind, ProjectionKind::Orthographic);
    EXPECT_DOUBLE_EQ(go->cameras[0].projection.znear, -10.0);  // glOrtho: near may be negative
}

TEST(GltfScene, BadCamerasAreRefusedWithTheirPath) {
    const json base = {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.5}}}};
    auto with = [&](json lantern) {
        json c = base;
        c["extensions"]["LANTERN_camera"] = lantern;
        return c;
    };
    const json box = {{"left", -1}, {"right", 1}, {"bottom", -1}, {"top", 1}, {"near", 1}, {"far", 10}};
    struct Case {
        json camera;
        std::string object, fragment;
    };
    const std::string ext = "cameras[0].extensions.LANTERN_camera";
    const Case cases[] = {
        {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 2.0}, {"zfar", 1.0}}}},
         "cameras[0].perspective.zfar", "> znear"},
        {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.0}}}}, "cameras[0].perspective.znear",
         "> 0"},
        {{{"type", "perspective"}, {"perspective", {{"yfov", 3.2}, {"znear", 1.0}}}}, "cameras[0].perspective.yfov",
         "(0, pi)"},
        {{{"type", "orthographic"}, {"orthographic", {{"xmag", 0.0}, {"ymag", 1.0}, {"znear", 0.0}, {"zfar", 1.0}}}},
         "cameras[0].orthographic.xmag", "non-zero"},
        {with({{"frustum", box}, {"ortho", box}}), ext, "at most one"},
        {with({{"frustum", {{"left", -1}, {"right", 1}, {"bottom", -1}, {"top", 1}, {"near", 0}}}}),
         ext + ".frustum", "near"},
        {with({{"ortho", {{"left", -1}, {"right", 1}, {"bottom", -1}, {"top", 1}, {"near", 1}}}}), ext + ".ortho.far",
         "is missing"},
        {with({{"lookAt", {{"eye", {0, 0, 5}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}}}}), ext + ".lookAt",
         "parallel"},
        {with({{"lookAt", {{"eye", {0, 0, 5}}, {"target", {0, 0, 0}}, {"up", {0, 0, 0}}}}}), ext + ".lookAt", "up"},
    };
    for (const Case& c : cases) {
        GltfBuilder b;
        b.addTriangle();
        b.doc["cameras"] = json::array({c.camera});
        auto o = loadCapturing(b.write(testOutputDir(), "bad"));
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.camera.dump();
    }
}

// --- Scenes and nodes -------------------------------------------------------------------------

TEST(GltfScene, LightingScenesAndNodeTransforms) {
    GltfBuilder b;
    const int tri = b.addTriangle();
    b.doc["nodes"][tri]["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
    b.addNode({{"mesh", 0}, {"translation", {1, 0, 0}}, {"rotation", {0, 0, 2, 0}}, {"scale", {1, 2, 3}}});
    b.doc["scenes"].push_back({{"name", "second"},
                               {"nodes", {1}},
                               {"extensions",
                                {{"LANTERN_lighting",
                                  {{"globalAmbient", {0, 0.1, 0.2}},
                                   {"localViewer", true},
                                   {"twoSided", true},
                                   {"shading", "gouraud"},
                                   {"specular", "phong"}}}}}});
    b.doc["scenes"][0]["nodes"] = {0};
    b.doc["scene"] = 1;
    auto o = loadCapturing(b.write(testOutputDir(), "scenes"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Scene& s = *o.scene;
    EXPECT_EQ(s.defaultRoot, 1);
    ASSERT_EQ(s.roots.size(), 2u);
    EXPECT_FALSE(s.roots[0].lighting);
    ASSERT_TRUE(s.roots[1].lighting);
    const LightingModel& l = *s.roots[1].lighting;
    EXPECT_EQ(l.globalAmbient, glm::dvec3(0, 0.1, 0.2));
    EXPECT_TRUE(l.localViewer);
    EXPECT_EQ(l.twoSided, true);
    EXPECT_EQ(l.shading, ShadingMode::Gouraud);
    EXPECT_EQ(l.specular, SpecularModel::Phong);
    ASSERT_TRUE(s.nodes[0].matrix);
    EXPECT_EQ((*s.nodes[0].matrix)[3], glm::dvec4(1, 2, 3, 1));  // column-major, as glTF
    EXPECT_EQ(s.nodes[1].rotation, glm::dquat(0, 0, 0, 1));      // (0,0,2,0) normalised
    EXPECT_TRUE(o.warned("nodes[1].rotation: quaternion length 2")) << o.allWarnings();
    EXPECT_EQ(s.nodes[1].scale, glm::dvec3(1, 2, 3));

    b.doc["scenes"][1]["extensions"]["LANTERN_lighting"]["shading"] = "toon";
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "toon")),
                            "scenes[1].extensions.LANTERN_lighting.shading", "not flat, gouraud or phong"));
    b.doc["scenes"][1]["extensions"]["LANTERN_lighting"] = {{"globalAmbient", {0, 0}}};
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(testOutputDir(), "ambient")),
                            "scenes[1].extensions.LANTERN_lighting.globalAmbient", "array of 3"));
}

TEST(GltfScene, ExplainSceneNeedsNoDevice) {
    GltfBuilder b;
    b.addTriangle({{"material", 0}});
    b.doc["materials"] = json::array({{{"alphaMode", "BLEND"}}});
    auto o = loadCapturing(b.write(testOutputDir(), "explain"));
    ASSERT_TRUE(o.scene);
    auto report = explainScene(*o.scene, RenderOptions{}, 0.0);
    ASSERT_TRUE(report) << report.error().describe();
    auto has = [&](const std::string& f) {
        return std::find(report->features.begin(), report->features.end(), f) != report->features.end();
    };
    EXPECT_TRUE(has("light:gl-default (headlight, directional)"));
    EXPECT_TRUE(has("alpha-blend"));
    EXPECT_EQ(report->variants.size(), 1u);
    RenderOptions badRoot;
    badRoot.root = 3;
    EXPECT_FALSE(explainScene(*o.scene, badRoot, 0.0));
}

} // namespace

// KHR_materials_variants: the variants are listed, the file's own materials are drawn unless a
// variant is asked for (LoadOptions::variant, --variant), a variant that does not list a
// primitive leaves it its own material, and bad names and indices are refused with the object.
TEST(GltfScene, MaterialVariantsAreSelectedByName) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    b.addTriangle();
    b.doc["materials"] = json::array({json{{"name", "plain"}}, json{{"name", "red"}}, json{{"name", "blue"}}});
    b.doc["extensionsUsed"] = {"KHR_materials_variants"};
    b.doc["extensions"]["KHR_materials_variants"]["variants"] =
        json::array({json{{"name", "Red"}}, json{{"name", "Blue"}}, json{{"name", "Plain"}}});
    json& p0 = b.doc["meshes"][0]["primitives"][0];
    p0["material"] = 0;
    p0["extensions"]["KHR_materials_variants"]["mappings"] =
        json::array({json{{"material", 1}, {"variants", {0}}}, json{{"material", 2}, {"variants", {1}}}});
    b.doc["meshes"][1]["primitives"][0]["material"] = 0;  // listed in no variant
    const auto path = b.write(dir, "variants");

    auto plain = loadCapturing(path);
    ASSERT_TRUE(plain.scene) << plain.scene.error().describe();
    EXPECT_EQ(plain.scene->variants, (std::vector<std::string>{"Red", "Blue", "Plain"}));
    EXPECT_EQ(plain.scene->meshes[0].primitives[0].material, 0);
    EXPECT_EQ(plain.scene->activeVariant, -1);

    LoadOptions options;
    options.variant = "Blue";
    auto blue = loadScene(path.string(), options);
    ASSERT_TRUE(blue) << blue.error().describe();
    EXPECT_EQ(blue->meshes[0].primitives[0].material, 2);
    EXPECT_EQ(blue->meshes[1].primitives[0].material, 0);
    EXPECT_EQ(blue->activeVariant, 1);
    ASSERT_TRUE(selectMaterialVariant(*blue, "Red"));
    EXPECT_EQ(blue->meshes[0].primitives[0].material, 1);
    ASSERT_TRUE(selectMaterialVariant(*blue, "Plain"));  // lists no primitive: their own
    EXPECT_EQ(blue->meshes[0].primitives[0].material, 0);
    ASSERT_TRUE(selectMaterialVariant(*blue, ""));
    EXPECT_EQ(blue->meshes[0].primitives[0].material, 0);

    options.variant = "Green";
    auto green = loadScene(path.string(), options);
    ASSERT_FALSE(green);
    EXPECT_EQ(green.error().object, "--variant");
    EXPECT_NE(green.error().message.find("\"Red\", \"Blue\", \"Plain\""), std::string::npos)
        << green.error().describe();

    p0["extensions"]["KHR_materials_variants"]["mappings"][1]["variants"] = {3};
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "bad-variant")),
                            "meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[1].variants[0]",
                            "variant 3 does not exist"));
    p0["extensions"]["KHR_materials_variants"]["mappings"][1] = {{"material", 7}, {"variants", {1}}};
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "bad-material")),
                            "meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[1].material",
                            "material 7 does not exist"));
}

// EXT_mesh_gpu_instancing (gltfpack -mi marks it required): the node's mesh is drawn at each
// instance, in the node's space; quantized rotations read as KHR_mesh_quantization allows;
// attributes of different counts are refused with their path.
TEST(GltfScene, GpuInstancesAreDrawnAtEveryInstanceInTheNodesSpace) {
    GltfBuilder b;
    b.addTriangle();
    b.doc["nodes"][0]["translation"] = {0, 10, 0};
    const int t = b.addFloats({1, 0, 0, 2, 0, 0, 3, 0, 0}, "VEC3");
    // 0 and 90 degrees about Z, as normalized shorts (32767 = 1, 23170 = 0.7071).
    const int r = b.addAccessor(std::vector<std::int16_t>{0, 0, 0, 32767, 0, 0, 23170, 23170, 0, 0, 0, 32767},
                                "VEC4", 5122, true);
    const int s = b.addFloats({1, 1, 1, 2, 2, 2, 1, 1, 1}, "VEC3");
    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
        {"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}, {"_ID", t}};
    b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing", "KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing", "KHR_mesh_quantization"};
    const auto dir = testOutputDir();
    auto o = loadCapturing(b.write(dir, "instances"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Scene& sc = *o.scene;
    ASSERT_EQ(sc.nodes.size(), 4u);
    EXPECT_EQ(sc.nodes[0].mesh, -1);
    EXPECT_EQ(sc.nodes[0].children, (std::vector<int>{1, 2, 3}));
    const Pose pose = evaluatePose(sc, -1, 0.0);
    for (int k = 1; k <= 3; ++k) {
        EXPECT_EQ(sc.nodes[std::size_t(k)].mesh, 0);
        EXPECT_NEAR(pose.worldFromNode[std::size_t(k)][3][0], double(k), 1e-9);
        EXPECT_NEAR(pose.worldFromNode[std::size_t(k)][3][1], 10.0, 1e-9);
    }
    // Instance 1: scale 2 and 90 degrees about Z (+X turned to +Y); instance 2 neither.
    EXPECT_NEAR(pose.worldFromNode[2][0][0], 0.0, 1e-4);
    EXPECT_NEAR(pose.worldFromNode[2][0][1], 2.0, 1e-4);
    EXPECT_NEAR(pose.worldFromNode[3][0][0], 1.0, 1e-4);
    bool noted = false;
    for (const FeatureUse& f : sc.features) noted |= f.key == "EXT_mesh_gpu_instancing";
    EXPECT_TRUE(noted);

    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] =
        b.addFloats({1, 1, 1, 2, 2, 2}, "VEC3");
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "bad")),
                            "nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.SCALE",
                            "has 2 instances where the other attributes have 3"));
}
