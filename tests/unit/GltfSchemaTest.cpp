// Numbers checked by their place in the glTF schema, not by their name: `target` is an
// integer in a buffer view and three numbers in LANTERN_camera's lookAt; every property of
// Lantern's and the supported KHR extensions takes its legal fractional, negative and large
// values, and integers keep their checks where the schema puts them.
#include "GltfTestSupport.h"
#include "io/gltf/GltfSchema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using namespace lantern;
using namespace lantern::test;
using gltf::NumberKind;
using gltf::numberKindAt;
using nlohmann::json;

TEST(GltfSchema, IntegerPlacesAreFoundByPositionNotByName) {
    // The same names, integers in one place and plain numbers in another.
    EXPECT_EQ(numberKindAt("bufferViews[].target"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("cameras[].extensions.LANTERN_camera.lookAt.target"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("cameras[].extensions.LANTERN_camera.lookAt.target[]"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("nodes[].mesh"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("nodes[].extensions.LANTERN_anything.mesh"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("accessors[].count"), NumberKind::Size);
    EXPECT_EQ(numberKindAt("accessors[].sparse.count"), NumberKind::Size);
    EXPECT_EQ(numberKindAt("extensions.KHR_lights_punctual.lights[].count"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("animations[].channels[].target.node"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("animations[].samplers[].input"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("meshes[].primitives[].attributes.TEXCOORD_1"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("meshes[].primitives[].targets[].POSITION"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("meshes[].weights[]"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("nodes[].children[]"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("nodes[].extensions.EXT_mesh_gpu_instancing.attributes.TRANSLATION"),
              NumberKind::Index);
    // Texture references anywhere in a material, extensions included, and only there.
    EXPECT_EQ(numberKindAt("materials[].pbrMetallicRoughness.baseColorTexture.index"),
              NumberKind::Index);
    EXPECT_EQ(numberKindAt("materials[].normalTexture.texCoord"), NumberKind::Index);
    EXPECT_EQ(numberKindAt("materials[].normalTexture.scale"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("materials[].extensions.KHR_materials_clearcoat.clearcoatTexture.index"),
              NumberKind::Index);
    EXPECT_EQ(numberKindAt("materials[].emissiveTexture.extensions.KHR_texture_transform.texCoord"),
              NumberKind::Index);
    EXPECT_EQ(numberKindAt("materials[].emissiveTexture.extensions.KHR_texture_transform.rotation"),
              NumberKind::Any);
    EXPECT_EQ(numberKindAt("materials[].extensions.LANTERN_materials_phong.shininess"),
              NumberKind::Any);
    EXPECT_EQ(numberKindAt("materials[].index"), NumberKind::Any);
    EXPECT_EQ(numberKindAt("textures[].extensions.EXT_texture_webp.source"), NumberKind::Index);
}

// A file with every extension Lantern reads, each property at a legal value its spec allows
// that is fractional, negative or large.
GltfBuilder everyPropertyAtItsExtremes() {
    GltfBuilder b;
    b.addTriangle();
    json& d = b.doc;
    d["extensionsUsed"] = {"KHR_lights_punctual", "LANTERN_lights_phong", "LANTERN_camera",
                           "LANTERN_lighting", "LANTERN_materials_phong",
                           "KHR_materials_emissive_strength", "KHR_texture_transform",
                           "FOO_unknown"};
    d["scenes"][0]["extensions"]["LANTERN_lighting"] = {
        {"globalAmbient", {-0.25, 0.5, 1e20}}, {"localViewer", true}, {"twoSided", true}};
    d["cameras"] = json::array({json{
        {"type", "perspective"},
        {"perspective", {{"yfov", 0.5}, {"znear", 1e-6}, {"zfar", 1e25}, {"aspectRatio", 1.75}}},
        {"extensions",
         {{"LANTERN_camera",
           {{"frustum",
             {{"left", -0.75}, {"right", 1e20}, {"bottom", -1e20}, {"top", 0.5}, {"near", 0.125},
              {"far", 1e25}}},
            {"lookAt",
             {{"eye", {-1e20, 2.5, 1e-20}}, {"target", {0, 0.3, -7.25}}, {"up", {0.1, -0.9, 0}}}}}}}},
    }});
    d["nodes"].push_back({{"camera", 0}});
    d["scenes"][0]["nodes"].push_back(1);
    d["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
        {json{{"type", "spot"},
              {"color", {0.5, 0.25, 1e3}},
              {"intensity", 1e20},
              {"range", 0.5},
              {"spot", {{"innerConeAngle", 0.125}, {"outerConeAngle", 1.5}}}},
         json{{"type", "point"},
              {"extensions",
               {{"LANTERN_lights_phong",
                 {{"ambient", {-0.5, 0.25, 1e6}},
                  {"diffuse", {0.5, -1, 2.5}},
                  {"specular", {1e20, 0, 0.5}},
                  {"attenuation", {0.5, 0.25, 1e-3}},
                  {"spotExponent", 0.5},
                  {"spotCutoffDeg", 45.5}}}}}}});
    d["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    d["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    d["scenes"][0]["nodes"].push_back(2);
    d["scenes"][0]["nodes"].push_back(3);
    d["materials"] = json::array({json{
        {"emissiveFactor", {0.5, 0.25, 1}},
        {"extensions",
         {{"LANTERN_materials_phong",
           {{"ambient", {-0.5, 0.25, 1e3}},
            {"diffuse", {0.5, 0.25, 2.5, 0.75}},
            {"specular", {1e6, 0.5, 0}},
            {"emission", {-0.125, 0, 0}},
            {"shininess", 1e6},
            {"back", {{"shininess", 0.5}, {"diffuse", {0.1, 0.2, 0.3, 0.4}}}}}},
          {"KHR_materials_emissive_strength", {{"emissiveStrength", 1e6}}}}}}});
    d["meshes"][0]["primitives"][0]["material"] = 0;
    // An extension Lantern does not read may hold anything at any name.
    d["nodes"][0]["extensions"]["FOO_unknown"] = {{"mesh", 0.5}, {"target", -3}, {"x", 1e300}};
    return b;
}

TEST(GltfSchema, EveryExtensionPropertyTakesItsLegalFractionalNegativeAndLargeValues) {
    GltfBuilder b = everyPropertyAtItsExtremes();
    auto o = loadCapturing(b.write(testOutputDir(), "extremes"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Scene& s = *o.scene;
    ASSERT_EQ(s.cameras.size(), 1u);
    ASSERT_TRUE(s.cameras[0].lookAt.has_value());
    // The regression: a lookAt target with a fractional coordinate was refused.
    EXPECT_DOUBLE_EQ(s.cameras[0].lookAt->target.y, 0.3);
    EXPECT_DOUBLE_EQ(s.cameras[0].lookAt->target.z, -7.25);
    EXPECT_DOUBLE_EQ(s.cameras[0].lookAt->eye.x, -1e20);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_DOUBLE_EQ(s.lights[0].range, 0.5);
    EXPECT_DOUBLE_EQ(s.lights[0].innerConeAngle, 0.125);
    EXPECT_DOUBLE_EQ(s.lights[1].attenuation.z, 1e-3);
    EXPECT_DOUBLE_EQ(s.lights[1].spotExponent, 0.5);
    EXPECT_DOUBLE_EQ(s.lights[1].ambient.x, -0.5);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_DOUBLE_EQ(s.materials[0].front.shininess, 1e6);
    EXPECT_DOUBLE_EQ(s.materials[0].front.ambient.x, -0.5);
    ASSERT_TRUE(s.materials[0].back.has_value());
    EXPECT_DOUBLE_EQ(s.materials[0].back->shininess, 0.5);
    ASSERT_TRUE(s.roots[0].lighting.has_value());
    EXPECT_DOUBLE_EQ(s.roots[0].lighting->globalAmbient.x, -0.25);
}

TEST(GltfSchema, IntegersKeepTheirChecksWhereTheSchemaPutsThem) {
    struct Case {
        const char* name;
        std::function<void(json&)> edit;
        const char* object;
        const char* fragment;
    };
    const std::vector<Case> cases = {
        {"bufferView target 0.5", [](json& d) { d["bufferViews"][0]["target"] = 34962.5; },
         "bufferViews[0].target", "not an integer"},
        {"textureInfo texCoord 0.5",
         [](json& d) {
             d["materials"] = json::array(
                 {json{{"extensions",
                        {{"KHR_materials_clearcoat", {{"clearcoatTexture", {{"index", 0}, {"texCoord", 0.5}}}}}}}}});
         },
         "materials[0].extensions.KHR_materials_clearcoat.clearcoatTexture.texCoord",
         "not an integer"},
        {"transform texCoord -1",
         [](json& d) {
             d["materials"] = json::array({json{
                 {"emissiveTexture",
                  {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", -1}}}}}}}}});
         },
         "materials[0].emissiveTexture.extensions.KHR_texture_transform.texCoord", "0 or more"},
        {"light index 1.5",
         [](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"] = {{"light", 1.5}}; },
         "nodes[0].extensions.KHR_lights_punctual.light", "not an integer"},
        {"sparse count -2",
         [](json& d) { d["accessors"][0]["sparse"] = {{"count", -2}}; },
         "accessors[0].sparse.count", "0 or more"},
        {"lookAt eye 1e300",
         [](json& d) {
             d["cameras"] = json::array({json{
                 {"type", "perspective"},
                 {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}},
                 {"extensions", {{"LANTERN_camera", {{"lookAt", {{"eye", {1e300, 0, 0}}}}}}}}}});
         },
         "cameras[0].extensions.LANTERN_camera.lookAt.eye[0]", "infinite"},
    };
    for (const auto& c : cases) {
        GltfBuilder b;
        b.addTriangle();
        c.edit(b.doc);
        auto o = loadCapturing(b.write(testOutputDir(), "case"));
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.name;
    }
}

} // namespace
