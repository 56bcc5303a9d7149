// The fidelity report: docs/scene-format-support.md's table and fidelityKeys() name the same
// features; a file's features are noted with their status, rule and objects; `lantern info
// --json` and `lantern render --report` print them, the render's shading deciding what gouraud
// and flat approximate.
#include "GltfTestSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace {

using namespace lantern;
using namespace lantern::test;
using nlohmann::json;

std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The keys in the first column of the "At a glance" table.
std::set<std::string> docsKeys() {
    const std::string text = readText(sourceDir() / "docs" / "scene-format-support.md");
    const std::size_t start = text.find("| key | feature | status | how |");
    EXPECT_NE(start, std::string::npos);
    const std::size_t end = text.find("\n\n", start);
    std::istringstream rows(text.substr(start, end - start));
    std::set<std::string> keys;
    std::string line;
    static const std::regex row(R"(^\| `([^`]+)` \|)");
    while (std::getline(rows, line)) {
        std::smatch m;
        if (std::regex_search(line, m, row)) keys.insert(m[1]);
    }
    return keys;
}

TEST(Fidelity, EveryRowOfTheDocsTableIsAReportKey) {
    const std::set<std::string> documented = docsKeys();
    EXPECT_GT(documented.size(), 30u);
    std::set<std::string> keys;
    for (const FeatureUse& f : fidelityKeys()) keys.insert(f.key);
    for (const std::string& k : documented) EXPECT_TRUE(keys.count(k)) << "docs row without a key: " << k;
    for (const std::string& k : keys) EXPECT_TRUE(documented.count(k)) << "key without a docs row: " << k;
}

const FeatureUse* find(const Scene& s, const std::string& key) {
    for (const FeatureUse& f : s.features)
        if (f.key == key) return &f;
    return nullptr;
}

GltfBuilder manyFeatures() {
    GltfBuilder b;
    const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int uv1 = b.addFloats({1, 1, 0, 1, 1, 0}, "VEC2");
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}, {"TEXCOORD_1", uv1}}},
                                   {"material", 0}})}});
    b.doc["images"] = json::array({{{"uri", "white.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({json{
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
        {"occlusionTexture", {{"index", 0}, {"texCoord", 1}}},
        {"emissiveTexture", {{"index", 0}, {"texCoord", 2}}},
        {"emissiveFactor", {1, 1, 1}},
        {"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.5}}}}}}});
    b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "EXT_lights_image_based"};
    return b;
}

TEST(Fidelity, AFilesFeaturesAreNotedWithTheirStatusRuleAndObjects) {
    Image white(2, 2);
    std::fill(white.rgba.begin(), white.rgba.end(), 1.0f);
    const auto dir = testOutputDir();
    ASSERT_TRUE(writePng(dir / "white.png", white));
    auto o = loadCapturing(manyFeatures().write(dir, "many"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Scene& s = *o.scene;
    const FeatureUse* container = find(s, "container");
    ASSERT_TRUE(container);
    EXPECT_EQ(container->objects, std::vector<std::string>{".gltf"});
    const FeatureUse* pbr = find(s, "pbr-factors");
    ASSERT_TRUE(pbr);
    EXPECT_EQ(pbr->fidelity, Fidelity::Approximated);
    EXPECT_EQ(pbr->rule, "pbr-to-classic");
    EXPECT_EQ(pbr->objects, std::vector<std::string>{"materials[0]"});
    const FeatureUse* coat = find(s, "KHR_materials_clearcoat");
    ASSERT_TRUE(coat);
    EXPECT_EQ(coat->objects, std::vector<std::string>{"materials[0].extensions.KHR_materials_clearcoat"});
    // The occlusion map reads the second set; the emissive map a third, drawn with its mean.
    std::vector<const FeatureUse*> sets;
    for (const FeatureUse& f : s.features)
        if (f.key == "texcoord-sets") sets.push_back(&f);
    ASSERT_EQ(sets.size(), 2u);
    EXPECT_EQ(sets[0]->fidelity, Fidelity::Supported);
    EXPECT_EQ(sets[0]->objects, std::vector<std::string>{"materials[0].occlusionTexture"});
    EXPECT_EQ(sets[1]->fidelity, Fidelity::Approximated);
    EXPECT_EQ(sets[1]->rule, "map-mean-for-third-set");
    EXPECT_EQ(sets[1]->objects, std::vector<std::string>{"materials[0].emissiveTexture"});
    EXPECT_TRUE(s.materials[0].occlusionMap.secondSet);
    EXPECT_EQ(s.meshes[0].primitives[0].texcoords1.size(), 3u);
    const FeatureUse* other = find(s, "other-extension");
    ASSERT_TRUE(other);
    EXPECT_EQ(other->fidelity, Fidelity::Skipped);
    EXPECT_EQ(other->objects, std::vector<std::string>{"EXT_lights_image_based"});
    EXPECT_TRUE(find(s, "base-color-texture"));
    EXPECT_FALSE(find(s, "skins"));
    // The features come in the table's order.
    std::vector<std::size_t> ranks;
    for (const FeatureUse& f : s.features)
        for (std::size_t k = 0; k < fidelityKeys().size(); ++k)
            if (fidelityKeys()[k].key == f.key) ranks.push_back(k);
    EXPECT_TRUE(std::is_sorted(ranks.begin(), ranks.end()));
}

// A map on a third set keeps its texture's mean in the factor: Khronos' MultiUVTest drew a
// white cube when its emissive map on TEXCOORD_1 was dropped and its factor of 1 kept.
TEST(Fidelity, AMapOnAThirdSetLeavesItsMeanInTheFactor) {
    Image grey(2, 2);
    std::fill(grey.rgba.begin(), grey.rgba.end(), 0.25f);
    for (std::size_t i = 3; i < grey.rgba.size(); i += 4) grey.rgba[i] = 1.0f;
    const auto dir = testOutputDir();
    ASSERT_TRUE(writePng(dir / "white.png", grey));
    auto o = loadCapturing(manyFeatures().write(dir, "mean"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    // 0.25 linear written as sRGB 137 reads back as 0.2502.
    EXPECT_NEAR(o.scene->materials[0].front.emission.x, 0.25, 0.002);
    EXPECT_TRUE(o.warned("reads TEXCOORD_2, a third set beside the material's TEXCOORD_0 and "
                         "TEXCOORD_1")) << o.allWarnings();
}

TEST(Fidelity, InfoJsonAndRenderReportPrintThem) {
    Image white(2, 2);
    std::fill(white.rgba.begin(), white.rgba.end(), 1.0f);
    const auto dir = testOutputDir();
    ASSERT_TRUE(writePng(dir / "white.png", white));
    const auto scene = manyFeatures().write(dir, "many").string();
    const auto info = runLantern({"info", scene, "--json"});
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const json j = json::parse(info.out);
    EXPECT_EQ(j["counts"]["triangles"], 1);
    bool coat = false;
    for (const json& f : j["features"]) coat |= f["key"] == "KHR_materials_clearcoat" && f["status"] == "approximated";
    EXPECT_TRUE(coat) << info.out;
    const auto reportPath = dir / "reports" / "many.json";
    const auto r = runLantern({"render", scene, "--shading", "gouraud", "--dry-run", "--report",
                               reportPath.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json rep = json::parse(readText(reportPath));
    EXPECT_EQ(rep["shading"], "gouraud");
    bool mr = false;
    for (const json& f : rep["features"])
        if (f["key"] == "metallic-roughness-texture")
            mr = f["status"] == "approximated" && f["rule"] == "texture-mean-in-gouraud-and-flat";
    EXPECT_TRUE(mr) << rep.dump(1);
}

} // namespace
