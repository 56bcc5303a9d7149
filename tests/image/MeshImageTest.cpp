// Mesh formats in pictures (skipped without a Vulkan device): a textured sphere written as OBJ
// with an MTL and as glTF with the same classic material renders alike, which checks the
// texture coordinates' flip and the MTL mapping end to end; and an OBJ sphere's MTL colours
// render exactly as the same material built in code, both against the double-precision
// reference: the MTL's Ka, Kd, Ks, Ns reach the equation as they are, with no PBR step.
#include "LightingCompare.h"
#include "MeshTestSupport.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;
using lantern::test::writeText;

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

// The primitive as OBJ text: every vertex's v, vt (OBJ's v up) and vn share one index.
std::string objOf(const Primitive& p, const std::string& mtl) {
    std::string text = "mtllib " + mtl + "\no sphere\n";
    for (const glm::vec3& v : p.positions)
        text += "v " + number(v.x) + " " + number(v.y) + " " + number(v.z) + "\n";
    for (const glm::vec2& t : p.texcoords) text += "vt " + number(t.x) + " " + number(1.0f - t.y) + "\n";
    for (const glm::vec3& n : p.normals)
        text += "vn " + number(n.x) + " " + number(n.y) + " " + number(n.z) + "\n";
    text += "usemtl m\n";
    for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3) {
        text += "f";
        for (int k = 0; k < 3; ++k) {
            const std::string c = std::to_string(p.indices[i + std::size_t(k)] + 1);
            text += " " + c + "/" + c + "/" + c;
        }
        text += "\n";
    }
    return text;
}

// The same sphere as glTF: LANTERN_materials_phong with the MTL's colours, the texture by URI.
std::filesystem::path gltfOf(const Primitive& p, const std::filesystem::path& dir) {
    test::GltfBuilder b;
    std::vector<float> pos, nrm, uv;
    for (const glm::vec3& v : p.positions) pos.insert(pos.end(), {v.x, v.y, v.z});
    for (const glm::vec3& n : p.normals) nrm.insert(nrm.end(), {n.x, n.y, n.z});
    for (const glm::vec2& t : p.texcoords) uv.insert(uv.end(), {t.x, t.y});
    const nlohmann::json prim = {
        {"attributes", {{"POSITION", b.addFloats(pos, "VEC3")}, {"NORMAL", b.addFloats(nrm, "VEC3")},
                        {"TEXCOORD_0", b.addFloats(uv, "VEC2")}}},
        {"indices", b.addAccessor(p.indices, "SCALAR", 5125)},
        {"material", 0}};
    b.addNode({{"mesh", b.addMesh(prim)}});
    b.doc["extensionsUsed"] = {"LANTERN_materials_phong"};
    b.doc["images"] = {{{"uri", "checker.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                           {"extensions", {{"LANTERN_materials_phong",
                                            {{"ambient", {0.25, 0.25, 0.25}},
                                             {"diffuse", {0.75, 0.625, 0.5, 1.0}},
                                             {"specular", {0.5, 0.5, 0.5}},
                                             {"shininess", 64.0}}}}}}};
    return b.write(dir, "sphere");
}

const char* kMtl = "newmtl m\nKa 0.25 0.25 0.25\nKd 0.75 0.625 0.5\nKs 0.5 0.5 0.5\nNs 64\nillum 2\n";

class MeshImage : public GpuTest {};

TEST_F(MeshImage, AnObjAndTheSameGltfRenderAlike) {
    const auto dir = test::testOutputDir();
    // Red above, blue below, 4 texels tall: a flipped v would swap the sphere's hemispheres.
    std::vector<unsigned char> texture;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 2; ++x) texture.insert(texture.end(), {std::uint8_t(y < 2 ? 230 : 20), 40, std::uint8_t(y < 2 ? 20 : 230)});
    test::writePng(dir / "checker.png", 2, 4, 3, texture);
    const Primitive sphere = makeSphere(1.0, 32, 16);
    writeText(dir / "sphere.mtl", std::string(kMtl) + "map_Kd checker.png\n");
    const auto obj = writeText(dir / "sphere.obj", objOf(sphere, "sphere.mtl"));
    const auto gltf = gltfOf(sphere, dir);
    RenderOptions o;
    o.width = 160;
    o.height = 120;
    std::vector<Image> images;
    for (const auto& path : {obj, gltf}) {
        auto scene = loadScene(path.string());
        ASSERT_TRUE(scene) << scene.error().describe();
        ASSERT_EQ(scene->textures.size(), 1u) << path;
        ASSERT_EQ(scene->materials.at(0).baseColorTexture, 0) << path;
        auto image = renderer().render(*scene, o, 0.0);
        ASSERT_TRUE(image) << image.error().describe();
        images.push_back(std::move(*image));
    }
    double sum = 0.0, worst = 0.0;
    const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = std::abs(images[0].rgba[4 * i + std::size_t(c)] - images[1].rgba[4 * i + std::size_t(c)]);
            sum += d;
            worst = std::max(worst, d);
        }
    const double mean = sum / double(3 * pixels);
    EXPECT_LE(mean, 1.0 / 255) << "worst " << worst << "; "
                               << test::saveComparison(images[0], images[1], "mesh_obj_vs_gltf");
    EXPECT_GT(test::countCovered(images[0]), pixels / 10) << "the sphere is in view";
    std::printf("OBJ against glTF: mean %.3g, worst %.3g (of 1)\n", mean, worst);
}

TEST_F(MeshImage, MtlColoursRenderAsTheSameMaterialBuiltInCode) {
    const auto dir = test::testOutputDir();
    const Primitive sphere = makeSphere(1.0, 48, 24);
    writeText(dir / "s.mtl", kMtl);
    auto loaded = loadScene(writeText(dir / "s.obj", objOf(sphere, "s.mtl")).string());
    ASSERT_TRUE(loaded) << loaded.error().describe();
    const Material code = test::phongMaterial({0.25, 0.25, 0.25}, {0.75, 0.625, 0.5, 1.0},
                                              {0.5, 0.5, 0.5}, 64.0);
    const Material& mtl = loaded->materials.at(0);
    EXPECT_EQ(mtl.front.ambient, code.front.ambient);
    EXPECT_EQ(mtl.front.diffuse, code.front.diffuse);
    EXPECT_EQ(mtl.front.specular, code.front.specular);
    EXPECT_EQ(mtl.front.shininess, code.front.shininess);
    EXPECT_EQ(mtl.front.emission, code.front.emission);
    EXPECT_FALSE(mtl.pbr || mtl.ambientFollowsDiffuse || mtl.unlit);
    std::vector<Image> images;
    for (const Material* m : {&code, &mtl}) {
        LitScene s;
        s.objects.push_back({m == &code ? sphere : loaded->meshes.at(0).primitives.at(0), *m, glm::dmat4(1.0)});
        Light point = test::makeLight(LightType::Point);
        s.lights.push_back({point, test::translation({2.0, 2.0, 4.0})});
        const RenderOptions o = test::optionsFor(160, 120, ShadingMode::Phong);
        const test::ReferenceComparison c = test::compareWithReference(device(), s.build(), o);
        EXPECT_GT(c.compared, 3000u);
        EXPECT_LE(c.worst, 1.0 / 255) << c.describe(m == &code ? "mtl_code" : "mtl_obj");
        images.push_back(c.frame.readback.image);
    }
    EXPECT_LE(test::maxAbsDifference(images[0], images[1]), 1e-6f)
        << "the OBJ's sphere and material draw the very pixels of the code's";
}

} // namespace
