// The glTF loader's data path: .gltf with embedded and external buffers and .glb load alike;
// external files stay inside the scene's folder; sizes are bounded; accessors (interleaved,
// normalised, sparse) read as glTF defines them; every bounds, index and count rule is refused
// with the object path; strips and fans become lists; missing normals are angle-weighted.
#include "GltfTestSupport.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace {

using namespace lantern;
using lantern::test::GltfBuilder;
using lantern::test::loadCapturing;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using json = nlohmann::json;

constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123;

const Primitive& firstPrimitive(const Scene& s) { return s.meshes.at(0).primitives.at(0); }

// --- Containers and files -------------------------------------------------------------------

TEST(GltfLoader, EmbeddedExternalAndBinaryStorageLoadTheSame) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle({{"indices", b.addIndices({0, 1, 2})}});
    for (auto storage : {GltfBuilder::Storage::DataUri, GltfBuilder::Storage::External,
                         GltfBuilder::Storage::Glb}) {
        const auto path = b.write(dir, "tri" + std::to_string(int(storage)), storage);
        auto o = loadCapturing(path);
        ASSERT_TRUE(o.scene) << path << ": " << o.scene.error().describe();
        const Primitive& p = firstPrimitive(*o.scene);
        EXPECT_EQ(p.positions.size(), 3u);
        EXPECT_EQ(p.positions[1], glm::vec3(1, 0, 0));
        EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 1, 2}));
        EXPECT_EQ(o.scene->sourcePath, path.string());
        EXPECT_TRUE(o.warnings->empty()) << o.allWarnings();
    }
}

TEST(GltfLoader, ExternalFilesMayLieInSubfoldersButNotOutside) {
    const auto dir = testOutputDir();
    std::filesystem::create_directories(dir / "scene" / "data");
    GltfBuilder b;
    b.addTriangle();
    GltfBuilder::writeBytes(dir / "scene" / "data" / "tri.bin", b.bin);
    GltfBuilder::writeBytes(dir / "outside.bin", b.bin);
    struct Case {
        std::string uri;
        bool accepted;
        std::string fragment;  ///< why it is refused
    };
    const Case cases[] = {
        {"data/tri.bin", true, ""},
        {"data/./tri.bin", true, ""},
        {"data%2Ftri.bin", true, ""},  // percent-encoded separator: still inside
        {"../outside.bin", false, "\"..\""},
        {"data/../../outside.bin", false, "\"..\""},
        {"%2E%2E/outside.bin", false, "\"..\""},  // encoded ".." decodes to ".."
        {"..\\outside.bin", false, "\"..\""},
        {(dir / "outside.bin").string(), false, "absolute path"},
        {"file:///etc/passwd", false, "scheme"},
        {"http://example.com/tri.bin", false, "scheme"},
        {"data/missing.bin", false, "does not exist"},
    };
    for (const Case& c : cases) {
        json doc = b.doc;
        doc["buffers"] = json::array({{{"byteLength", b.bin.size()}, {"uri", c.uri}}});
        const auto path = dir / "scene" / "t.gltf";
        const std::string text = doc.dump();
        GltfBuilder::writeBytes(path, std::vector<unsigned char>(text.begin(), text.end()));
        auto o = loadCapturing(path);
        if (c.accepted) {
            EXPECT_TRUE(o.scene) << c.uri << ": " << o.scene.error().describe();
        } else {
            EXPECT_TRUE(refusedWith(o, "buffers[0].uri", c.fragment)) << c.uri;
        }
    }
}

TEST(GltfLoader, SizesAreBoundedByMaxSize) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    b.addFloats(std::vector<float>(30000, 1.0f), "VEC3");  // makes the .bin larger than the .gltf
    const auto external = b.write(dir, "ext", GltfBuilder::Storage::External);
    const auto gltfSize = std::filesystem::file_size(external);
    ASSERT_LT(gltfSize, 4000u);
    auto file = loadCapturing(external, gltfSize - 1);
    ASSERT_FALSE(file.scene);
    EXPECT_NE(file.scene.error().message.find("more than --max-size"), std::string::npos)
        << file.scene.error().describe();
    EXPECT_TRUE(refusedWith(loadCapturing(external, 40000), "buffers[0].uri", "more than --max-size"));
    // --max-size is also the load's total budget: the 120 KB buffer plus what its accessors
    // decode to (another 120 KB of floats) and the parsed JSON (tens of KB) fit 400000 bytes,
    // not 200000.
    EXPECT_TRUE(refusedWith(loadCapturing(external, 200000), "accessors[1]", "budget"));
    EXPECT_TRUE(loadCapturing(external, 400000).scene);

    // An accessor without a buffer view is zeros the loader would allocate: bounded too.
    GltfBuilder big;
    big.doc["accessors"] = json::array({{{"componentType", kFloat}, {"count", 1u << 30}, {"type", "VEC3"}}});
    big.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", 0}}}}})}}});
    big.addNode({{"mesh", 0}});
    EXPECT_TRUE(refusedWith(loadCapturing(big.write(dir, "zeros")), "accessors[0]", "--max-size"));
}

TEST(GltfLoader, GlbUnknownChunksAfterTheBinChunkAreIgnored) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    const auto path = b.write(dir, "tri", GltfBuilder::Storage::Glb);
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(std::filesystem::file_size(path));
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    const unsigned char extra[] = {4, 0, 0, 0, 'X', 'T', 'R', 'A', 1, 2, 3, 4};
    bytes.insert(bytes.end(), std::begin(extra), std::end(extra));
    const std::uint32_t length = std::uint32_t(bytes.size());
    for (int i = 0; i < 4; ++i) bytes[8 + std::size_t(i)] = (length >> (8 * i)) & 0xFF;
    GltfBuilder::writeBytes(path, bytes);
    auto o = loadCapturing(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(o.warned("unknown chunk type \"XTRA\" ignored")) << o.allWarnings();
}

TEST(GltfLoader, DeeplyNestedJsonIsRefusedBeforeParsing) {
    const auto dir = testOutputDir();
    std::string text = R"({"asset":{"version":"2.0"},"extras":)";
    text += std::string(100000, '[') + std::string(100000, ']') + "}";
    const auto path = dir / "deep.gltf";
    GltfBuilder::writeBytes(path, std::vector<unsigned char>(text.begin(), text.end()));
    EXPECT_TRUE(refusedWith(loadCapturing(path), "JSON", "nested more than"));
}

TEST(GltfLoader, UnsupportedRequiredExtensionsAreRefused) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    b.addTriangle();
    b.doc["extensionsUsed"] = {"EXT_lights_image_based", "KHR_materials_unlit"};
    b.doc["extensionsRequired"] = {"EXT_lights_image_based"};
    EXPECT_TRUE(refusedWith(loadCapturing(b.write(dir, "webp")), "extensionsRequired[0]",
                            "EXT_lights_image_based"));
    b.doc.erase("extensionsRequired");
    auto o = loadCapturing(b.write(dir, "used"));
    ASSERT_TRUE(o.scene);
    EXPECT_TRUE(o.warned("ignored (not supported): EXT_lights_image_based")) << o.allWarnings();
}

// --- Accessors ------------------------------------------------------------------------------

TEST(GltfLoader, InterleavedNormalisedAndSparseAccessorsReadAsGltfDefines) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    // POSITION and NORMAL interleaved in one 24-byte-stride view.
    const std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
    const int view = b.addView(interleaved.data(), interleaved.size() * 4, 24);
    b.doc["accessors"].push_back({{"bufferView", view}, {"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}});
    b.doc["accessors"].push_back(
        {{"bufferView", view}, {"byteOffset", 12}, {"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}});
    // Normalised colours: unsigned bytes (RGBA) map to /255.
    const int colors = b.addAccessor(std::vector<std::uint8_t>{255, 0, 51, 255, 0, 255, 0, 128, 0, 0, 255, 0},
                                     "VEC4", kUnsignedByte, true);
    // Normalised unsigned-short texture coordinates map to /65535.
    const int uv = b.addAccessor(std::vector<std::uint16_t>{0, 65535, 65535, 0, 32768, 32768}, "VEC2",
                                 kUnsignedShort, true);
    b.addNode({{"mesh", b.addMesh({{"attributes",
                                    {{"POSITION", 0}, {"NORMAL", 1}, {"COLOR_0", colors}, {"TEXCOORD_0", uv}}}})}});
    auto o = loadCapturing(b.write(dir, "interleaved"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Primitive& p = firstPrimitive(*o.scene);
    EXPECT_EQ(p.positions[2], glm::vec3(0, 1, 0));
    EXPECT_EQ(p.normals[1], glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(p.colors[0].z, 0.2f);
    EXPECT_FLOAT_EQ(p.colors[1].w, 128.0f / 255.0f);
    EXPECT_FLOAT_EQ(p.texcoords[0].y, 1.0f);
    EXPECT_FLOAT_EQ(p.texcoords[2].x, 32768.0f / 65535.0f);

    // Sparse: base positions from a view, three replaced; and one sparse accessor without a
    // base view (zeros, then the substitutions).
    GltfBuilder s;
    const int base = s.addFloats({0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0}, "VEC3");
    const std::vector<std::uint16_t> idx = {1, 3};
    const std::vector<float> values = {9, 9, 9, 7, 7, 7};
    const int idxView = s.addView(idx.data(), 4), valView = s.addView(values.data(), 24);
    json sparse = {{"count", 2},
                   {"indices", {{"bufferView", idxView}, {"componentType", kUnsignedShort}}},
                   {"values", {{"bufferView", valView}}}};
    s.doc["accessors"][base]["sparse"] = sparse;
    s.doc["accessors"].push_back({{"componentType", kFloat}, {"count", 4}, {"type", "VEC3"}, {"sparse", sparse}});
    const int zeros = int(s.doc["accessors"].size()) - 1;
    for (int accessor : {base, zeros})
        s.addNode({{"mesh", s.addMesh({{"attributes", {{"POSITION", accessor}}}, {"indices", s.addIndices({0, 1, 3})}})}});
    auto so = loadCapturing(s.write(dir, "sparse"));
    ASSERT_TRUE(so.scene) << so.scene.error().describe();
    const Primitive& withBase = so.scene->meshes[0].primitives[0];
    EXPECT_EQ(withBase.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(withBase.positions[1], glm::vec3(9, 9, 9));
    EXPECT_EQ(withBase.positions[2], glm::vec3(2, 0, 0));
    EXPECT_EQ(withBase.positions[3], glm::vec3(7, 7, 7));
    const Primitive& fromZeros = so.scene->meshes[1].primitives[0];
    EXPECT_EQ(fromZeros.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(fromZeros.positions[1], glm::vec3(9, 9, 9));
    EXPECT_EQ(fromZeros.positions[2], glm::vec3(0, 0, 0));
    EXPECT_EQ(fromZeros.positions[3], glm::vec3(7, 7, 7));
}

/// A file with one triangle mesh whose JSON `edit` breaks; expected: refusal at `object`.
struct BrokenCase {
    const char* what;
    std::function<void(GltfBuilder&)> edit;
    const char* object;
    const char* fragment;
};

TEST(GltfLoader, BoundsIndexAndCountViolationsAreRefusedWithTheObjectPath) {
    auto indexed = [](GltfBuilder& b, std::vector<std::uint16_t> indices) {
        b.addTriangle({{"indices", b.addIndices(indices)}});
    };
    const BrokenCase cases[] = {
        {"index past the vertex count", [&](GltfBuilder& b) { indexed(b, {0, 1, 57}); },
         "meshes[0].primitives[0].indices", "index 57 is out of range (vertex count 3"},
        {"accessor past its view",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["accessors"][0]["count"] = 4;
         },
         "accessors[0]", "run past the end of bufferViews[0]"},
        {"view past its buffer",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["bufferViews"][0]["byteLength"] = 4000;
         },
         "bufferViews[0]", "exceeds the 36 bytes of buffers[0]"},
        {"huge byteOffset (overflow)",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["accessors"][0]["byteOffset"] = 18446744073709551612ull;
         },
         "accessors[0].byteOffset", "more than the largest size"},
        {"stride smaller than the element",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["bufferViews"][0]["byteStride"] = 8;
         },
         "accessors[0]", "smaller than the element size 12"},
        {"misaligned offset",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["accessors"][0]["byteOffset"] = 2;
             b.doc["accessors"][0]["count"] = 2;
         },
         "accessors[0].byteOffset", "not aligned"},
        {"attribute counts differ",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
                 b.addFloats({0, 0, 1, 0, 0, 1}, "VEC3");
         },
         "meshes[0].primitives[0].attributes.POSITION", "has 3 elements but NORMAL has 2"},
        {"unresolved accessor",
         [](GltfBuilder& b) { b.addTriangle({{"attributes", {{"POSITION", 0}, {"NORMAL", 9}}}}); },
         "meshes[0].primitives[0].attributes.NORMAL", "accessor 9 does not exist"},
        {"position of the wrong type",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["accessors"][0]["type"] = "VEC2";
             b.doc["accessors"][0]["count"] = 4;
         },
         "meshes[0].primitives[0].attributes.POSITION", "expected VEC3 of FLOAT"},
        {"indices of floats",
         [](GltfBuilder& b) {
             b.addTriangle({{"indices", b.addFloats({0, 1, 2}, "SCALAR")}});
         },
         "meshes[0].primitives[0].indices", "expected SCALAR of UNSIGNED_BYTE"},
        {"normalized float",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["accessors"][0]["normalized"] = true;
         },
         "accessors[0].normalized", "only BYTE, UNSIGNED_BYTE"},
        {"NaN position",
         [](GltfBuilder& b) { b.addTriangle({{"attributes", {{"POSITION", b.addFloats({0, 0, 0, NAN, 0, 0, 0, 1, 0}, "VEC3")}}}}); },
         "accessors[0]", "element 1 component 0 is not a finite number (NaN"},
        {"sparse index out of range",
         [](GltfBuilder& b) {
             b.addTriangle();
             const std::vector<std::uint16_t> idx = {5};
             const std::vector<float> v = {1, 1, 1};
             const int iv = b.addView(idx.data(), 2), vv = b.addView(v.data(), 12);
             b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                               {"indices", {{"bufferView", iv}, {"componentType", kUnsignedShort}}},
                                               {"values", {{"bufferView", vv}}}};
         },
         "accessors[0].sparse.indices", "index 5 (entry 0) is out of range (count 3)"},
        {"sparse count above the accessor's",
         [](GltfBuilder& b) {
             b.addTriangle();
             const std::vector<std::uint16_t> idx = {0, 1, 2, 3};
             const int iv = b.addView(idx.data(), 8);
             b.doc["accessors"][0]["sparse"] = {{"count", 4},
                                               {"indices", {{"bufferView", iv}, {"componentType", kUnsignedShort}}},
                                               {"values", {{"bufferView", 0}}}};
         },
         "accessors[0].sparse.count", "outside [1, 3]"},
        {"primitive mode out of range", [](GltfBuilder& b) { b.addTriangle({{"mode", 9}}); },
         "meshes[0].primitives[0].mode", "not a glTF primitive mode"},
        {"primitive without attributes",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["meshes"][0]["primitives"].push_back(json::object());
         },
         "meshes[0].primitives[1].attributes", "is missing"},
        {"material that does not exist", [](GltfBuilder& b) { b.addTriangle({{"material", 3}}); },
         "meshes[0].primitives[0].material", "material 3 does not exist"},
        {"node cycle",
         [](GltfBuilder& b) {
             const int n = b.addTriangle();
             b.addNode({{"children", {n}}}, false);
             b.doc["nodes"][n]["children"] = {1};
         },
         "nodes[0]", "cycle"},
        {"default scene that does not exist",
         [](GltfBuilder& b) {
             b.addTriangle();
             b.doc["scene"] = 4;
         },
         "scene", "scene 4 does not exist"},
    };
    const auto dir = testOutputDir();
    for (const BrokenCase& c : cases) {
        GltfBuilder b;
        c.edit(b);
        auto o = loadCapturing(b.write(dir, "case"));
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.what;
    }
}

// --- Geometry -------------------------------------------------------------------------------

// Five vertices (0,0) (1,0) (0,1) (1,1) (0,2) drawn with `mode`, through the indices 4,3,2,1,0
// when `indexed`: the file, loaded.
test::LoadOutcome loadFiveVertices(int mode, bool indexed, const std::string& name) {
    GltfBuilder b;
    const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0}, "VEC3");
    json prim = {{"attributes", {{"POSITION", pos}}}, {"mode", mode}};
    if (indexed) prim["indices"] = b.addIndices({4, 3, 2, 1, 0});
    b.addNode({{"mesh", b.addMesh(prim)}});
    return loadCapturing(b.write(testOutputDir(), name));
}

TEST(GltfLoader, StripsAndFansBecomeListsWithTheirWinding) {
    // Five vertices: strip triangles (0,1,2) (1,3,2) (2,3,4); fan (1,2,0) (2,3,0) (3,4,0)
    // (glTF 2.0 section 3.7.2.1: strip p_i, p_{i+(1+i%2)}, p_{i+(2-i%2)}; fan p_{i+1}, p_{i+2}, p_0).
    struct Case {
        int mode;
        bool indexed;
        std::vector<std::uint32_t> expected;
    };
    const Case cases[] = {
        {5, false, {0, 1, 2, 1, 3, 2, 2, 3, 4}},
        {6, false, {1, 2, 0, 2, 3, 0, 3, 4, 0}},
        {5, true, {4, 3, 2, 3, 1, 2, 2, 1, 0}},  // indices 4,3,2,1,0 map through the sequence
        {6, true, {3, 2, 4, 2, 1, 4, 1, 0, 4}},
    };
    for (const Case& c : cases) {
        auto o = loadFiveVertices(c.mode, c.indexed, "strip");
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        EXPECT_EQ(firstPrimitive(*o.scene).indices, c.expected) << "mode " << c.mode << " indexed " << c.indexed;
    }
}

TEST(GltfLoader, PointAndLineModesBecomeListsAndPartialElementsAreDroppedWithAWarning) {
    // Five vertices. LINE_STRIP: (0,1) (1,2) (2,3) (3,4); LINE_LOOP adds (4,0), so the last
    // vertex of each line is GL's provoking vertex; LINES drops the fifth vertex.
    struct Case {
        int mode;
        bool indexed;
        Topology topology;
        std::vector<std::uint32_t> expected;  // empty: drawn in order without indices
        bool warnsPartial;
    };
    const Case cases[] = {
        {0, false, Topology::Points, {}, false},
        {0, true, Topology::Points, {4, 3, 2, 1, 0}, false},
        {1, false, Topology::Lines, {0, 1, 2, 3}, true},
        {1, true, Topology::Lines, {4, 3, 2, 1}, true},
        {3, false, Topology::Lines, {0, 1, 1, 2, 2, 3, 3, 4}, false},
        {3, true, Topology::Lines, {4, 3, 3, 2, 2, 1, 1, 0}, false},
        {2, false, Topology::Lines, {0, 1, 1, 2, 2, 3, 3, 4, 4, 0}, false},
        {2, true, Topology::Lines, {4, 3, 3, 2, 2, 1, 1, 0, 0, 4}, false},
        {4, false, Topology::Triangles, {0, 1, 2}, true},
    };
    for (const Case& c : cases) {
        auto o = loadFiveVertices(c.mode, c.indexed, "modes");
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        const Primitive& p = firstPrimitive(*o.scene);
        SCOPED_TRACE("mode " + std::to_string(c.mode) + (c.indexed ? " indexed" : ""));
        EXPECT_EQ(p.topology, c.topology);
        EXPECT_EQ(p.indices, c.expected);
        EXPECT_EQ(o.warned(" are ignored"), c.warnsPartial) << o.allWarnings();
        // Lines and points without normals are drawn unlit; triangles get computed normals.
        EXPECT_EQ(p.normals.empty(), c.topology != Topology::Triangles);
        EXPECT_EQ(p.unlitForWantOfNormals(), c.topology != Topology::Triangles);
        EXPECT_TRUE(o.scene->validate());
    }
}

TEST(GltfLoader, ModesWithoutAWholeElementAreSkippedWithAWarning) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    const int one = b.addFloats({0, 0, 0}, "VEC3");
    const int two = b.addFloats({0, 0, 0, 1, 0, 0}, "VEC3");
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", one}}}, {"mode", 1}})}});
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", one}}}, {"mode", 3}})}});
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", two}}}, {"mode", 4}})}});
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", two}}}, {"mode", 2}})}});
    auto o = loadCapturing(b.write(dir, "partial"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    for (int m = 0; m < 3; ++m) EXPECT_TRUE(o.scene->meshes[std::size_t(m)].primitives.empty()) << m;
    for (const char* what : {"LINES with 1 vertices draws nothing", "LINE_STRIP with 1 vertices",
                             "TRIANGLES with 2 vertices draws nothing"})
        EXPECT_TRUE(o.warned(what)) << what << "\n" << o.allWarnings();
    // A loop of two vertices is one line (not the same line twice).
    EXPECT_EQ(o.scene->meshes[3].primitives[0].indices, (std::vector<std::uint32_t>{0, 1}));
}

TEST(GltfLoader, MissingNormalsAreAngleWeightedOverSharedVertices) {
    const auto dir = testOutputDir();
    // Two triangles sharing the edge (0,0,0)-(0,1,0): A in the z=0 plane with a 90 degree angle
    // at the origin, B in the x=0 plane with a 45 degree angle there.
    GltfBuilder b;
    const int pos = b.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1, 1}, "VEC3");
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", b.addIndices({0, 2, 1, 0, 1, 3})}})}});
    // The same triangles unshared (non-indexed): every vertex gets its face normal.
    const int flat = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1}, "VEC3");
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", flat}}}})}});
    auto o = loadCapturing(b.write(dir, "normals"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const glm::dvec3 nA(0, 0, 1), nB(1, 0, 0);  // counter-clockwise faces
    const double pi = 3.14159265358979323846;
    // At the origin: A contributes its 90 degree angle, B its 45 degree angle.
    const glm::dvec3 atOrigin = glm::normalize(nA * (pi / 2) + nB * (pi / 4));
    // At (0,1,0): A's angle is 45 degrees, B's is 90 (between (0,-1,0) and (0,0,1)).
    const glm::dvec3 atTop = glm::normalize(nA * (pi / 4) + nB * (pi / 2));
    const Primitive& p = firstPrimitive(*o.scene);
    EXPECT_LT(glm::length(glm::dvec3(p.normals[0]) - atOrigin), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(p.normals[1]) - atTop), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(p.normals[2]) - nA), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(p.normals[3]) - nB), 1e-6);
    const Primitive& f = o.scene->meshes[1].primitives[0];
    for (int i = 0; i < 3; ++i) EXPECT_LT(glm::length(glm::dvec3(f.normals[std::size_t(i)]) - nA), 1e-6);
    for (int i = 3; i < 6; ++i) EXPECT_LT(glm::length(glm::dvec3(f.normals[std::size_t(i)]) - nB), 1e-6);
}

TEST(GltfLoader, SkinsAndMorphTargetsLoad) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    const int n = b.addTriangle();
    // A morph target (the positions themselves as displacements), default weight 0.5, a node
    // weight overriding it, and a skin of one joint with normalized UNSIGNED_BYTE weights.
    b.doc["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", 0}}});
    b.doc["meshes"][0]["weights"] = {0.5};
    b.doc["nodes"][n]["weights"] = {0.75};
    const int joints = b.addAccessor(std::vector<std::uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4", 5121);
    const int weights = b.addAccessor(std::vector<std::uint8_t>{255, 0, 0, 0, 51, 204, 0, 0, 102, 0, 153, 0}, "VEC4", 5121, true);
    b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = joints;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = weights;
    const int joint = b.addNode({{"translation", {0, 0, 2}}});
    const int ibm = b.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -2, 1}, "MAT4");
    b.doc["skins"] = json::array({{{"joints", {joint}}, {"inverseBindMatrices", ibm}, {"skeleton", joint}}});
    b.doc["nodes"][n]["skin"] = 0;
    auto o = loadCapturing(b.write(dir, "skin_morph"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_FALSE(o.warned("not supported")) << o.allWarnings();
    const Scene& s = *o.scene;
    const Primitive& p = firstPrimitive(s);
    ASSERT_EQ(p.targets.size(), 1u);
    EXPECT_EQ(p.targets[0].positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(s.meshes[0].weights, std::vector<double>{0.5});
    EXPECT_EQ(s.nodes[std::size_t(n)].weights, std::vector<double>{0.75});
    ASSERT_EQ(p.joints0.size(), 3u);
    EXPECT_FLOAT_EQ(p.weights0[1].x, 51.0f / 255.0f);
    EXPECT_FLOAT_EQ(p.weights0[2].z, 153.0f / 255.0f);
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].joints, std::vector<int>{joint});
    EXPECT_EQ(s.skins[0].skeleton, joint);
    EXPECT_DOUBLE_EQ(s.skins[0].inverseBind[0][3][2], -2.0);
    EXPECT_EQ(s.nodes[std::size_t(n)].skin, 0);
    // The joint at z = 2 with inverse bind z - 2 leaves the weighted vertices in place (scaled
    // by their weight sums): vertex 1 (1, 0, 0) with weights 0.2 + 0.8 = 1 plus the morph
    // displacement 0.75 * (1, 0, 0).
    const DeformedPrimitive d = deformPrimitive(s, evaluatePose(s, -1, 0.0), n, p);
    EXPECT_NEAR(d.positions[1].x, 1.75, 1e-6);
    EXPECT_NEAR(d.positions[1].z, 0.0, 1e-6);
    for (const std::string& w : *o.warnings) EXPECT_EQ(w.find(o.scene->sourcePath + ": "), 0u) << w;
}

TEST(GltfLoader, MorphWeightChannelsAndSecondInfluenceSetsLoad) {
    const auto dir = testOutputDir();
    GltfBuilder b;
    const int n = b.addTriangle();
    b.doc["meshes"][0]["primitives"][0]["targets"] =
        json::array({{{"POSITION", 0}}, {{"POSITION", 0}}});
    const int j0 = b.addAccessor(std::vector<std::uint16_t>(12, 0), "VEC4", 5123);
    const int j1 = b.addAccessor(std::vector<std::uint16_t>(12, 1), "VEC4", 5123);
    const int w0 = b.addFloats({0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0}, "VEC4");
    const int w1 = b.addFloats({0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0}, "VEC4");
    auto& attrs = b.doc["meshes"][0]["primitives"][0]["attributes"];
    attrs["JOINTS_0"] = j0;
    attrs["JOINTS_1"] = j1;
    attrs["WEIGHTS_0"] = w0;
    attrs["WEIGHTS_1"] = w1;
    const int a = b.addNode(json::object()), c = b.addNode(json::object());
    b.doc["skins"] = json::array({{{"joints", {a, c}}}});
    b.doc["nodes"][n]["skin"] = 0;
    // CUBICSPLINE weights: 2 keys x 3 groups x 2 targets.
    const int times = b.addFloats({0, 1}, "SCALAR");
    const int values = b.addFloats({0, 0, 0, 1, 2, 0, /* key 1 */ 0, 0, 1, 0, 0, 0}, "SCALAR");
    b.doc["animations"] = json::array({{{"samplers", json::array({{{"input", times}, {"output", values}, {"interpolation", "CUBICSPLINE"}}})},
                                        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", n}, {"path", "weights"}}}}})}}});
    auto o = loadCapturing(b.write(dir, "weights_channel"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Primitive& p = firstPrimitive(*o.scene);
    ASSERT_EQ(p.joints1.size(), 3u);
    EXPECT_EQ(p.joints1[0], glm::uvec4(1));
    ASSERT_EQ(o.scene->animations.size(), 1u);
    const Animation& an = o.scene->animations[0];
    ASSERT_EQ(an.channels.size(), 1u);
    EXPECT_EQ(an.channels[0].path, AnimationPath::Weights);
    EXPECT_EQ(an.samplers[0].weightCount, 2u);
    // Key 0: in-tangents (0, 0), values (0, 1), out-tangents (2, 0); key 1: in (0, 0), values
    // (1, 0). At s = 1/2 (h00 = h01 = 1/2, h10 = 1/8): target 0 = 1/8 * 2 + 1/2 * 1 = 0.75;
    // target 1 = 1/2 * 1 = 0.5.
    const Pose pose = evaluatePose(*o.scene, -1, 0.5);
    ASSERT_EQ(pose.morphWeights[std::size_t(n)].size(), 2u);
    EXPECT_NEAR(pose.morphWeights[std::size_t(n)][0], 0.75, 1e-12);
    EXPECT_NEAR(pose.morphWeights[std::size_t(n)][1], 0.5, 1e-12);
}

TEST(GltfLoader, BadSkinsAreRefusedWithTheObject) {
    const auto dir = testOutputDir();
    {
        GltfBuilder b;
        const int n = b.addTriangle();
        b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
            b.addAccessor(std::vector<std::uint8_t>{0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4", 5121);
        b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
            b.addFloats({0.5, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
        b.doc["skins"] = json::array({{{"joints", {n}}}});
        b.doc["nodes"][n]["skin"] = 0;
        auto o = loadCapturing(b.write(dir, "joint_oob"));
        EXPECT_TRUE(refusedWith(o, "meshes[0].primitives[0].joints", "joint 3 is out of range"));
    }
    {
        GltfBuilder b;
        const int n = b.addTriangle();
        b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
            b.addAccessor(std::vector<std::uint8_t>(12, 0), "VEC4", 5121);
        b.doc["skins"] = json::array({{{"joints", {n}}}});
        auto o = loadCapturing(b.write(dir, "joints_no_weights"));
        EXPECT_TRUE(refusedWith(o, "meshes[0].primitives[0].attributes.JOINTS_0", "has no matching WEIGHTS_0"));
    }
    {
        GltfBuilder b;
        b.addTriangle();
        b.doc["skins"] = json::array({{{"joints", {7}}}});
        auto o = loadCapturing(b.write(dir, "skin_joint_missing"));
        EXPECT_TRUE(refusedWith(o, "skins[0].joints[0]", "node 7 does not exist"));
    }
}

TEST(GltfLoader, EverySampleModelLoadsWithTheFilesCounts) {
    // The device-free half of tests/image/GltfSamplesTest.cpp, so that the sanitizer run of the
    // loader label reads every real asset too.
    const auto dir = lantern::test::sharedDir() / "assets" / "gltf-samples";
    if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "the shared assets are absent: " << dir;
    std::size_t files = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
        const std::string ext = e.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        ++files;
        SCOPED_TRACE(e.path().string());
        auto o = loadCapturing(e.path());
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        const json doc = lantern::test::fileJson(e.path());
        const SceneSummary s = summarize(*o.scene);
        EXPECT_EQ(s.nodes, doc.value("nodes", json::array()).size());
        EXPECT_EQ(s.primitives, lantern::test::primitivesIn(doc));
        EXPECT_EQ(s.animations, doc.value("animations", json::array()).size());
        EXPECT_EQ(s.cameras, doc.value("cameras", json::array()).size());
        EXPECT_EQ(s.materials, doc.value("materials", json::array()).size());
    }
    EXPECT_EQ(files, 24u);
}

} // namespace
