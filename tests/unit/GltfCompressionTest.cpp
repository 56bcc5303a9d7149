// Compressed and quantized geometry: a cube and a sphere written in every encoding of
// GltfEncode.h (KHR_mesh_quantization, EXT_meshopt_compression with each mode and filter,
// KHR_draco_mesh_compression edgebreaker and sequential), as .gltf and .glb, load with the
// geometry they were written from; quantized components read as glTF specifies; the sample
// models re-encoded load the same; the used-versus-required rule for extensions.
#include "GltfEncode.h"
#include "GltfTestSupport.h"

#include <meshoptimizer.h>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::Encoding;
using lantern::test::GltfBuilder;
using lantern::test::loadCapturing;
using lantern::test::refusedWith;
using lantern::test::TestMesh;
using lantern::test::testOutputDir;
using json = nlohmann::json;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123;

/// The scene's only mesh as a TestMesh in its node's coordinates (undoing quantization).
TestMesh loadedMesh(const Scene& s) {
    return test::meshOf(s.meshes.at(0).primitives.at(0), s.nodes.at(0).localTransform());
}

struct MeshCase {
    const char* name;
    TestMesh mesh;
};

TEST(GltfCompression, EveryEncodingLoadsTheGeometryItWasWrittenFrom) {
    const auto dir = testOutputDir();
    const MeshCase meshes[] = {{"cube", test::makeCube()}, {"sphere", test::makeSphere(12, 24, 3.0f)}};
    for (const MeshCase& m : meshes)
        for (Encoding e : test::kAllEncodings)
            for (auto storage : {GltfBuilder::Storage::DataUri, GltfBuilder::Storage::Glb}) {
                const std::string name = std::string(m.name) + "-" + test::encodingName(e) +
                                         (storage == GltfBuilder::Storage::Glb ? "-glb" : "");
                SCOPED_TRACE(name);
                GltfBuilder b;
                test::addEncodedMesh(b, m.mesh, e);
                auto o = loadCapturing(b.write(dir, name, storage));
                ASSERT_TRUE(o.scene) << o.scene.error().describe();
                EXPECT_TRUE(o.warnings->empty()) << o.allWarnings();
                const Primitive& p = o.scene->meshes.at(0).primitives.at(0);
                EXPECT_EQ(p.triangleCount(), m.mesh.indices.size() / 3);
                EXPECT_TRUE(test::sameGeometry(loadedMesh(*o.scene), m.mesh,
                                               test::toleranceOf(e, m.mesh)));
            }
}

// --- KHR_mesh_quantization ----------------------------------------------------------------

/// One attribute of a triangle stored as `componentType` (4-byte aligned elements).
struct QuantizedRead {
    const char* attribute;
    int componentType;
    bool normalized;
    std::vector<int> raw; ///< three elements
    std::vector<float> expected;
};

int addIntegers(GltfBuilder& b, const QuantizedRead& r) {
    const std::size_t components = r.raw.size() / 3;
    const std::size_t size = r.componentType == kByte || r.componentType == kUnsignedByte ? 1 : 2;
    const std::size_t stride = (components * size + 3) & ~std::size_t(3);
    std::vector<unsigned char> bytes(3 * stride, 0);
    for (std::size_t i = 0; i < r.raw.size(); ++i) {
        const auto v = std::uint16_t(std::int16_t(r.raw[i]));
        const std::size_t at = (i / components) * stride + (i % components) * size;
        bytes[at] = std::uint8_t(v & 0xFF);
        if (size == 2) bytes[at + 1] = std::uint8_t(v >> 8);
    }
    const int view = b.addView(bytes.data(), bytes.size(), stride);
    json a = {{"bufferView", view}, {"componentType", r.componentType}, {"count", 3},
              {"type", components == 3 ? "VEC3" : "VEC2"}};
    if (r.normalized) a["normalized"] = true;
    b.doc["accessors"].push_back(a);
    return int(b.doc["accessors"].size()) - 1;
}

TEST(GltfCompression, QuantizedComponentsReadAsIntegersOrNormalisedAsGltfSpecifies) {
    const auto dir = testOutputDir();
    const QuantizedRead rows[] = {
        {"POSITION", kByte, false, {-128, 0, 0, 127, 0, 0, 0, 100, 0}, {-128, 0, 0, 127, 0, 0, 0, 100, 0}},
        {"POSITION", kUnsignedByte, true, {0, 0, 0, 255, 0, 0, 0, 51, 0}, {0, 0, 0, 1, 0, 0, 0, 0.2f, 0}},
        {"POSITION", kShort, true, {-32768, 0, 0, 32767, 0, 0, 0, -32767, 0}, {-1, 0, 0, 1, 0, 0, 0, -1, 0}},
        {"POSITION", kUnsignedShort, false, {0, 0, 0, 65535, 0, 0, 0, 40000, 0}, {0, 0, 0, 65535, 0, 0, 0, 40000, 0}},
        {"NORMAL", kByte, true, {-128, 0, 0, 127, 0, 0, 0, 0, -127}, {-1, 0, 0, 1, 0, 0, 0, 0, -1}},
        {"NORMAL", kShort, true, {0, 16384, 0, 0, 32767, 0, 0, 0, 1}, {0, 16384 / 32767.0f, 0, 0, 1, 0, 0, 0, 1 / 32767.0f}},
        {"TEXCOORD_0", kByte, false, {-5, 7, 0, 0, 127, -128}, {-5, 7, 0, 0, 127, -128}},
        {"TEXCOORD_0", kShort, true, {32767, 0, -32767, 16384, 0, 0}, {1, 0, -1, 16384 / 32767.0f, 0, 0}},
        {"TEXCOORD_0", kUnsignedByte, false, {0, 255, 1, 2, 3, 4}, {0, 255, 1, 2, 3, 4}},
    };
    for (const QuantizedRead& r : rows) {
        SCOPED_TRACE(std::string(r.attribute) + " " + std::to_string(r.componentType) +
                     (r.normalized ? " normalized" : ""));
        GltfBuilder b;
        json attributes = {{r.attribute, addIntegers(b, r)}};
        if (std::string(r.attribute) != "POSITION")
            attributes["POSITION"] = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        b.addNode({{"mesh", b.addMesh({{"attributes", attributes}})}});
        test::declareExtension(b, "KHR_mesh_quantization", true);
        auto o = loadCapturing(b.write(dir, "quantized"));
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        const Primitive& p = o.scene->meshes.at(0).primitives.at(0);
        std::vector<float> got;
        for (int i = 0; i < 3; ++i) {
            if (std::string(r.attribute) == "POSITION")
                got.insert(got.end(), {p.positions[i].x, p.positions[i].y, p.positions[i].z});
            else if (std::string(r.attribute) == "NORMAL")
                got.insert(got.end(), {p.normals[i].x, p.normals[i].y, p.normals[i].z});
            else
                got.insert(got.end(), {p.texcoords.at(i).x, p.texcoords.at(i).y});
        }
        ASSERT_EQ(got.size(), r.expected.size());
        for (std::size_t i = 0; i < got.size(); ++i)
            EXPECT_NEAR(got[i], r.expected[i], 1e-6) << "component " << i;
    }
}

TEST(GltfCompression, QuantizedFormatsNeedTheExtensionAndFollowItsTable) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    const QuantizedRead shortPositions{"POSITION", kShort, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}, {}};
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", addIntegers(b, shortPositions)}}}})}});
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "undeclared")),
                            "meshes[0].primitives[0].attributes.POSITION",
                            "KHR_mesh_quantization allows it, but the file does not declare"));
    test::declareExtension(b, "KHR_mesh_quantization", false); // extensionsUsed is enough
    ASSERT_TRUE(loadCapturing(b.write(dir, "declared")).scene);

    // Normals must be normalized even with the extension; positions may not be UNSIGNED_INT.
    GltfBuilder n;
    const QuantizedRead byteNormals{"NORMAL", kByte, false, {0, 0, 1, 0, 0, 1, 0, 0, 1}, {}};
    json attributes = {{"POSITION", n.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3")},
                       {"NORMAL", addIntegers(n, byteNormals)}};
    n.addNode({{"mesh", n.addMesh({{"attributes", attributes}})}});
    test::declareExtension(n, "KHR_mesh_quantization", true);
    EXPECT_TRUE(refusedWith(loadCapturing(n.write(dir, "byte-normals")),
                            "meshes[0].primitives[0].attributes.NORMAL",
                            "expected VEC3 of FLOAT, normalized BYTE, normalized SHORT"));
}

// --- EXT_meshopt_compression --------------------------------------------------------------

TEST(GltfCompression, MeshoptFallbackBufferWithDataIsIgnoredForTheDecodedViews) {
    const auto dir = testOutputDir();
    const TestMesh cube = test::makeCube();
    GltfBuilder b;
    test::addEncodedMesh(b, cube, Encoding::MeshoptQuantized);
    // An uncompressed fallback of the right size but all 0xFF: the decoded data must win.
    json& fallback = b.extraBuffers.back();
    const std::size_t length = fallback["byteLength"];
    fallback["uri"] = "data:application/octet-stream;base64," +
                      GltfBuilder::base64(std::vector<unsigned char>(length, 0xFF));
    b.doc["extensionsRequired"] = json::array();
    auto o = loadCapturing(b.write(dir, "with-fallback"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(test::sameGeometry(loadedMesh(*o.scene), cube,
                                   test::toleranceOf(Encoding::MeshoptQuantized, cube)));
}

/// The data every meshopt view of `b` decodes to, laid out as the views say, decoded here with
/// meshoptimizer (independently of the loader): what an uncompressed fallback buffer holds.
std::vector<unsigned char> meshoptFallbackData(const GltfBuilder& b, std::size_t length) {
    std::vector<unsigned char> out(length, 0);
    for (const json& view : b.doc["bufferViews"]) {
        if (!view.contains("extensions")) continue;
        const json& e = view["extensions"]["EXT_meshopt_compression"];
        const std::size_t count = e["count"], stride = e["byteStride"];
        const unsigned char* src = b.bin.data() + std::size_t(e.value("byteOffset", 0));
        const std::size_t srcLength = e["byteLength"];
        unsigned char* dst = out.data() + std::size_t(view.value("byteOffset", 0));
        const std::string mode = e["mode"], filter = e.value("filter", "NONE");
        int rc = 0;
        if (mode == "ATTRIBUTES")
            rc = meshopt_decodeVertexBuffer(dst, count, stride, src, srcLength);
        else if (mode == "TRIANGLES")
            rc = meshopt_decodeIndexBuffer(dst, count, stride, src, srcLength);
        else
            rc = meshopt_decodeIndexSequence(dst, count, stride, src, srcLength);
        EXPECT_EQ(rc, 0) << view.dump();
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(dst, count, stride);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(dst, count, stride);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(dst, count, stride);
    }
    return out;
}

TEST(GltfCompression, MeshoptOnlyUsedFallsBackWithAWarningWhenAStreamCannotBeDecoded) {
    const auto dir = testOutputDir();
    const TestMesh sphere = test::makeSphere(6, 12);
    for (Encoding e : {Encoding::MeshoptQuantized, Encoding::MeshoptFloat}) {
        SCOPED_TRACE(test::encodingName(e));
        GltfBuilder b;
        test::addEncodedMesh(b, sphere, e);
        json& fallback = b.extraBuffers.back();
        fallback["uri"] = "data:application/octet-stream;base64," +
                          GltfBuilder::base64(meshoptFallbackData(b, fallback["byteLength"]));
        // Every stream's version byte made one meshoptimizer 0.18 does not know; one view's
        // mode made one the extension does not have.
        json& views = b.doc["bufferViews"];
        for (const json& view : views)
            b.bin[std::size_t(view["extensions"]["EXT_meshopt_compression"].value("byteOffset", 0))] = 0xF5;
        views[1]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
        b.doc["extensionsUsed"] = json::array({"EXT_meshopt_compression"});
        b.doc["extensionsRequired"] = json::array();
        if (e == Encoding::MeshoptQuantized) {
            b.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
            b.doc["extensionsRequired"].push_back("KHR_mesh_quantization");
        }
        auto o = loadCapturing(b.write(dir, "fallback-used-" + test::encodingName(e)));
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        EXPECT_TRUE(test::sameGeometry(loadedMesh(*o.scene), sphere, test::toleranceOf(e, sphere)));
        for (std::size_t v = 0; v < views.size(); ++v)
            EXPECT_TRUE(o.warned("bufferViews[" + std::to_string(v) +
                                 "].extensions.EXT_meshopt_compression"))
                << o.allWarnings();
        EXPECT_TRUE(o.warned("encoding version meshoptimizer 0.18 does not decode; "
                             "EXT_meshopt_compression is not required, so the view's "
                             "uncompressed fallback data in buffers[1] is used"))
            << o.allWarnings();
        EXPECT_TRUE(o.warned("\"STRIPS\" is not ATTRIBUTES")) << o.allWarnings();

        // Required: no fallback; the broken rule, then the undecodable stream, refused by name.
        b.doc["extensionsRequired"].push_back("EXT_meshopt_compression");
        const std::string name = "fallback-required-" + test::encodingName(e);
        EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, name)),
                                "bufferViews[1].extensions.EXT_meshopt_compression.mode",
                                "\"STRIPS\" is not ATTRIBUTES"));
        views[1]["extensions"]["EXT_meshopt_compression"]["mode"] = "ATTRIBUTES";
        EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, name)),
                                "bufferViews[0].extensions.EXT_meshopt_compression",
                                "encoding version meshoptimizer 0.18 does not decode"));
    }
}

TEST(GltfCompression, DracoOnlyUsedFallsBackWithAWarningWhenItsStreamCannotBeDecoded) {
    const auto dir = testOutputDir();
    const TestMesh cube = test::makeCube();
    GltfBuilder b;
    test::addEncodedMesh(b, cube, Encoding::Draco);
    // The uncompressed fallback: the cube's own data behind the primitive's accessors (Draco
    // keeps the cube's 24 points and 12 triangles, so the counts agree).
    json& accessors = b.doc["accessors"];
    ASSERT_EQ(accessors[0]["count"], cube.vertexCount());
    ASSERT_EQ(accessors[3]["count"], cube.indices.size());
    accessors[0]["bufferView"] = b.addView(cube.positions.data(), 4 * cube.positions.size());
    accessors[1]["bufferView"] = b.addView(cube.normals.data(), 4 * cube.normals.size());
    accessors[2]["bufferView"] = b.addView(cube.texcoords.data(), 4 * cube.texcoords.size());
    accessors[3]["bufferView"] = b.addView(cube.indices.data(), 4 * cube.indices.size());
    const std::size_t stream = b.doc["bufferViews"][0]["byteOffset"];
    b.bin[stream] = 'X'; // no "DRACO" magic
    b.doc["extensionsRequired"] = json::array();
    auto o = loadCapturing(b.write(dir, "draco-used"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(test::sameGeometry(loadedMesh(*o.scene), cube,
                                   test::toleranceOf(Encoding::Float, cube)));
    EXPECT_TRUE(o.warned("meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: the data "
                         "is not a Draco stream (no \"DRACO\" header); KHR_draco_mesh_compression "
                         "is not required, so the primitive's uncompressed accessors are read"))
        << o.allWarnings();

    // Required, or an accessor without data: refused.
    b.doc["extensionsRequired"] = json::array({"KHR_draco_mesh_compression"});
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "draco-required")),
                            "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression",
                            "is not a Draco stream"));
    b.doc["extensionsRequired"] = json::array();
    accessors[1].erase("bufferView");
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "draco-no-fallback")),
                            "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression",
                            "is not a Draco stream"));
}

TEST(GltfCompression, MeshoptQuaternionFilterDecodesAnimatedRotations) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    std::vector<glm::dquat> rotations;
    std::vector<float> xyzw;
    for (int k = 0; k < 5; ++k) {
        const glm::dquat q = glm::angleAxis(0.7 * k, glm::normalize(glm::dvec3(1, 2 + k, 3)));
        rotations.push_back(q);
        xyzw.insert(xyzw.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    }
    std::vector<std::int16_t> encoded(xyzw.size());
    meshopt_encodeFilterQuat(encoded.data(), rotations.size(), 8, 12, xyzw.data());
    const auto compressed = test::meshoptVertices(encoded.data(), rotations.size(), 8);
    const std::size_t offset = test::appendBytes(b, compressed);
    b.extraBuffers.push_back({{"byteLength", 8 * rotations.size()},
                              {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    b.doc["bufferViews"].push_back(
        {{"buffer", 1}, {"byteLength", 8 * rotations.size()}, {"byteStride", 8},
         {"extensions", {{"EXT_meshopt_compression",
                          {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", compressed.size()},
                           {"byteStride", 8}, {"count", rotations.size()}, {"mode", "ATTRIBUTES"},
                           {"filter", "QUATERNION"}}}}}});
    b.doc["accessors"].push_back({{"bufferView", int(b.doc["bufferViews"].size()) - 1},
                                  {"componentType", kShort}, {"normalized", true},
                                  {"count", rotations.size()}, {"type", "VEC4"}});
    const int output = int(b.doc["accessors"].size()) - 1;
    const int input = b.addFloats({0, 1, 2, 3, 4}, "SCALAR");
    const json sampler = {{"input", input}, {"output", output}};
    const json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}};
    b.doc["animations"] = json::array(
        {{{"samplers", json::array({sampler})}, {"channels", json::array({channel})}}});
    test::declareExtension(b, "EXT_meshopt_compression", true);
    auto o = loadCapturing(b.write(dir, "quaternions", GltfBuilder::Storage::Glb));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const auto& values = o.scene->animations.at(0).samplers.at(0).values;
    ASSERT_EQ(values.size(), rotations.size());
    for (std::size_t k = 0; k < values.size(); ++k) {
        const glm::dvec4 q(rotations[k].x, rotations[k].y, rotations[k].z, rotations[k].w);
        // 12-bit components; q and -q are the same rotation (the filter keeps the largest > 0).
        const double error = std::min(glm::length(values[k] - q), glm::length(values[k] + q));
        EXPECT_LT(error, 2e-3) << "key " << k;
    }
}

// --- Extensions: required versus used ---------------------------------------------------

TEST(GltfCompression, UnsupportedExtensionsAreRefusedWhenRequiredAndWarnedWhenOnlyUsed) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    for (const char* supported : {"KHR_mesh_quantization", "EXT_meshopt_compression",
                                  "KHR_meshopt_compression", "KHR_draco_mesh_compression"})
        test::declareExtension(b, supported, true);
    auto o = loadCapturing(b.write(dir, "supported"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(o.warnings->empty()) << o.allWarnings();

    test::declareExtension(b, "EXT_lights_image_based", false);
    test::declareExtension(b, "KHR_materials_anisotropy", false);
    o = loadCapturing(b.write(dir, "used"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(o.warned("extensionsUsed: ignored (not supported): EXT_lights_image_based, "
                         "KHR_materials_anisotropy"))
        << o.allWarnings();

    b.doc["extensionsRequired"].push_back("KHR_materials_anisotropy");
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "required")), "extensionsRequired[4]",
                            "extension KHR_materials_anisotropy is required by the file but not "
                            "supported"));
}

// --- The sample models, re-encoded ----------------------------------------------------------

TEST(GltfCompression, SampleModelsReencodedLoadTheSameGeometry) {
    const auto samples = test::sharedDir() / "assets" / "gltf-samples";
    if (!std::filesystem::is_directory(samples))
        GTEST_SKIP() << "the sample models are not there (" << samples << ")";
    const auto dir = testOutputDir();
    const char* models[] = {"Duck/glTF-Binary/Duck.glb", "Suzanne/glTF/Suzanne.gltf",
                            "BoxInterleaved/glTF-Binary/BoxInterleaved.glb",
                            "OrientationTest/glTF-Binary/OrientationTest.glb"};
    for (const char* model : models) {
        auto original = loadCapturing(samples / model);
        ASSERT_TRUE(original.scene) << model << ": " << original.scene.error().describe();
        for (std::size_t m = 0; m < original.scene->meshes.size(); ++m)
            for (std::size_t p = 0; p < original.scene->meshes[m].primitives.size(); ++p) {
                const TestMesh mesh = test::meshOf(original.scene->meshes[m].primitives[p]);
                for (Encoding e : {Encoding::Draco, Encoding::MeshoptQuantized, Encoding::MeshoptFloat}) {
                    SCOPED_TRACE(std::string(model) + " mesh " + std::to_string(m) + " primitive " +
                                 std::to_string(p) + " " + test::encodingName(e));
                    GltfBuilder b;
                    test::addEncodedMesh(b, mesh, e);
                    auto o = loadCapturing(b.write(dir, "sample", GltfBuilder::Storage::Glb));
                    ASSERT_TRUE(o.scene) << o.scene.error().describe();
                    EXPECT_TRUE(test::sameGeometry(loadedMesh(*o.scene), mesh, test::toleranceOf(e, mesh)));
                }
            }
    }
}

} // namespace
