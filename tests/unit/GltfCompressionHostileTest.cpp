// Hostile compressed data: truncated and corrupted meshopt and Draco streams, counts that lie,
// sizes beyond the byte limit, filters on the wrong type or stride, references that go nowhere.
// Each is refused with the file, the glTF object and the reason on one line (and by `lantern
// info` with exit status 1), before anything is allocated for the sizes it claims.
#include "GltfEncode.h"
#include "GltfTestSupport.h"

#include <gtest/gtest.h>

#include <functional>

namespace {

using namespace lantern;
using lantern::test::Encoding;
using lantern::test::GltfBuilder;
using lantern::test::loadCapturing;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using json = nlohmann::json;

constexpr int kShort = 5122, kUnsignedByte = 5121;
const char* const kMeshopt = "EXT_meshopt_compression";
const std::string kDraco = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";

/// The meshopt extension of view `v`.
json& ext(GltfBuilder& b, int v) {
    return b.doc["bufferViews"][std::size_t(v)]["extensions"][kMeshopt];
}
std::string extPath(int v) {
    return "bufferViews[" + std::to_string(v) + "].extensions." + kMeshopt;
}
/// The byte offset in the binary buffer of view `v`'s compressed stream.
std::size_t streamOffset(GltfBuilder& b, int v) {
    return ext(b, v)["byteOffset"];
}
/// Changes view `v`'s stride and count together, with room in the fallback buffer.
void relayout(GltfBuilder& b, int v, std::size_t stride, std::size_t count) {
    ext(b, v)["byteStride"] = stride;
    ext(b, v)["count"] = count;
    json& view = b.doc["bufferViews"][std::size_t(v)];
    view["byteLength"] = stride * count;
    if (view.contains("byteStride")) view["byteStride"] = stride;
    b.extraBuffers.back()["byteLength"] = std::size_t(1) << 20;
}
/// The Draco stream (view 0 of a Draco file) rebuilt with `edit`.
void editDraco(GltfBuilder& b, const std::function<void(std::vector<unsigned char>&)>& edit) {
    json& view = b.doc["bufferViews"][0];
    const std::size_t offset = view["byteOffset"], length = view["byteLength"];
    std::vector<unsigned char> stream(b.bin.begin() + std::ptrdiff_t(offset),
                                      b.bin.begin() + std::ptrdiff_t(offset + length));
    edit(stream);
    view["byteOffset"] = test::appendBytes(b, stream);
    view["byteLength"] = stream.size();
}
std::vector<unsigned char> varint(std::uint32_t v) {
    std::vector<unsigned char> out;
    do {
        out.push_back(std::uint8_t((v & 0x7F) | (v > 0x7F ? 0x80 : 0)));
        v >>= 7;
    } while (v);
    return out;
}
/// A sequential Draco stream's face count replaced (header: 11 bytes, then varint faces).
void setSequentialFaces(std::vector<unsigned char>& s, std::uint32_t faces) {
    const auto v = varint(faces);
    s.erase(s.begin() + 11); // the cube's 12 faces: one byte
    s.insert(s.begin() + 11, v.begin(), v.end());
}

struct HostileCase {
    const char* name;
    Encoding base; ///< the cube in this encoding, then `edit`
    std::function<void(GltfBuilder&)> edit;
    std::string object; ///< empty: any object (the refusal may come from several checks)
    std::string fragment;
};

const HostileCase kCases[] = {
    // --- meshopt: streams -----------------------------------------------------------------
    {"meshopt-truncated", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["byteLength"] = int(ext(b, 0)["byteLength"]) - 8; },
     extPath(0), "the compressed data"},
    {"meshopt-unknown-version", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { b.bin[streamOffset(b, 0)] = 0xA5; }, extPath(0), "encoding version"},
    {"meshopt-garbage-index-stream", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) {
         for (std::size_t i = 1; i < std::size_t(ext(b, 3)["byteLength"]); ++i)
             b.bin[streamOffset(b, 3) + i] = std::uint8_t(0x5A + 31 * i);
     },
     "", ""},
    {"meshopt-count-lies", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["count"] = 25; }, extPath(0), "is not the bufferView's byteLength"},
    // 200 vertices, not the cube's 24: the stream's group headers are laid out for 32 vertices
    // (two groups of 16, one header byte) and 200 need four header bytes. (A count up to 64
    // reads the same bytes, header bits of absent groups being zero: meshoptimizer decodes it,
    // rightly, to the 24 vertices and zeros, which no check could refuse.)
    {"meshopt-count-and-length-lie", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { relayout(b, 0, 8, 200); }, extPath(0), "the compressed data"},
    {"meshopt-huge-count", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) {
         relayout(b, 0, 8, 2000000000);
         b.extraBuffers.back()["byteLength"] = 16000000000ull;
     },
     extPath(0), "decoding the compressed view would need 16000000000 bytes, more than the"},
    {"meshopt-offset-beyond-int", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["byteOffset"] = 4294967304ull; }, extPath(0) + ".byteOffset",
     "4294967304 is outside [0, 2147483647]"},
    {"meshopt-source-outside-buffer", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["byteOffset"] = 1000000; }, extPath(0), "exceeds the"},
    {"meshopt-source-is-fallback", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["buffer"] = 1; }, extPath(0) + ".buffer",
     "compressed data cannot come from it"},
    // --- meshopt: layouts, modes and filters ----------------------------------------------
    {"meshopt-attribute-stride-6", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) {
         relayout(b, 0, 6, 24);
         b.doc["bufferViews"][0].erase("byteStride");
     },
     extPath(0) + ".byteStride", "is not a multiple of 4 in [4, 256]"},
    {"meshopt-octahedral-stride-12", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { relayout(b, 1, 12, 24); }, extPath(1) + ".byteStride",
     "does not suit the OCTAHEDRAL filter"},
    {"meshopt-quaternion-stride-4", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 1)["filter"] = "QUATERNION"; }, extPath(1) + ".byteStride",
     "does not suit the QUATERNION filter"},
    {"meshopt-exponential-read-as-short", Encoding::MeshoptFloat,
     [](GltfBuilder& b) {
         b.doc["accessors"][1]["componentType"] = kShort;
         b.doc["accessors"][1]["normalized"] = true;
     },
     "accessors[1]", "decoded by the EXPONENTIAL filter with byteStride 12, as SHORT (expected FLOAT)"},
    {"meshopt-octahedral-read-as-float", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) {
         b.doc["accessors"][1]["componentType"] = 5126;
         b.doc["accessors"][1].erase("normalized");
         relayout(b, 1, 8, 24); // FLOAT VEC3 needs 12 bytes: keep the accessor inside the view
         b.doc["accessors"][1]["type"] = "VEC2";
     },
     "accessors[1]", "as FLOAT (expected SHORT)"},
    {"meshopt-filter-on-indices", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 3)["filter"] = "OCTAHEDRAL"; }, extPath(3) + ".filter",
     "on index data"},
    {"meshopt-triangles-not-multiple-of-3", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { relayout(b, 3, 2, 35); }, extPath(3) + ".count",
     "35 is not a multiple of 3"},
    {"meshopt-unknown-mode", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { ext(b, 0)["mode"] = "STRIPS"; }, extPath(0) + ".mode",
     "\"STRIPS\" is not ATTRIBUTES, TRIANGLES or INDICES"},
    {"meshopt-khr-color-filter", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) {
         json e = ext(b, 2);
         e["filter"] = "COLOR";
         b.doc["bufferViews"][2]["extensions"] = {{"KHR_meshopt_compression", e}};
     },
     "bufferViews[2].extensions.KHR_meshopt_compression.filter", "\"COLOR\" is not NONE"},
    // --- meshopt: the fallback buffer ----------------------------------------------------
    {"meshopt-plain-view-into-fallback", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { b.doc["bufferViews"][2].erase("extensions"); }, "bufferViews[2]",
     "a meshopt fallback buffer without data, but is not compressed"},
    {"meshopt-view-beyond-fallback", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { b.extraBuffers.back()["byteLength"] = 10; }, "bufferViews[0]",
     "exceeds the byteLength 10 of buffers[1]"},
    {"meshopt-fallback-not-marked", Encoding::MeshoptQuantized,
     [](GltfBuilder& b) { b.extraBuffers.back().erase("extensions"); }, "buffers[1]",
     "has no uri"},
    // --- Draco: streams ---------------------------------------------------------------------
    {"draco-truncated", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s.resize(s.size() / 2); }); }, kDraco,
     "the Draco data cannot be decoded"},
    {"draco-header-only", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s.resize(12); }); }, kDraco,
     "ends inside its connectivity header"},
    {"draco-not-draco", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s[0] = 'X'; }); }, kDraco,
     "is not a Draco stream"},
    {"draco-unknown-version", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s[5] = 3; }); }, kDraco,
     "bitstream version 3.2 is not supported"},
    {"draco-point-cloud", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s[7] = 0; }); }, kDraco,
     "holds a point cloud, not a mesh"},
    {"draco-metadata-flag-on-garbage", Encoding::Draco,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { s[10] |= 0x80; }); }, "", ""},
    // --- Draco: counts that lie -------------------------------------------------------------
    {"draco-index-count-lies", Encoding::Draco,
     [](GltfBuilder& b) { b.doc["accessors"][3]["count"] = 39; }, kDraco,
     "has 12 triangles (36 indices) but accessors[3] (indices) has count 39"},
    {"draco-point-count-lies-sequential", Encoding::DracoSequential,
     [](GltfBuilder& b) {
         for (int a = 0; a < 3; ++a) b.doc["accessors"][a]["count"] = 25;
     },
     kDraco, "points but accessors[0] (POSITION) has count 25"},
    {"draco-point-count-lies-edgebreaker", Encoding::Draco,
     [](GltfBuilder& b) {
         for (int a = 0; a < 3; ++a) b.doc["accessors"][a]["count"] = 25;
     },
     kDraco, "the decoded mesh has 24 points but accessors[0] (POSITION) has count 25"},
    {"draco-huge-face-count", Encoding::DracoSequential,
     [](GltfBuilder& b) { editDraco(b, [](auto& s) { setSequentialFaces(s, 0x7FFFFFF0u); }); },
     kDraco, "the Draco stream has 2147483632 triangles"},
    {"draco-huge-face-count-and-accessor", Encoding::DracoSequential,
     [](GltfBuilder& b) {
         editDraco(b, [](auto& s) { setSequentialFaces(s, 0x7FFFFFF0u); });
         b.doc["accessors"][3]["count"] = 3ull * 0x7FFFFFF0u;
     },
     kDraco, "more than the"},
    // --- Draco: references and types ------------------------------------------------------
    {"draco-attribute-id-missing", Encoding::Draco,
     [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
              ["attributes"]["NORMAL"] = 99;
     },
     "meshes[0].primitives[0].attributes.NORMAL", "attribute id 99 is not in the Draco data"},
    {"draco-attribute-not-in-primitive", Encoding::Draco,
     [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
              ["attributes"]["TEXCOORD_1"] = 2;
     },
     kDraco + ".attributes.TEXCOORD_1", "the primitive has no TEXCOORD_1 attribute"},
    {"draco-components-mismatch", Encoding::Draco,
     [](GltfBuilder& b) { b.doc["accessors"][2]["type"] = "VEC3"; },
     "meshes[0].primitives[0].attributes.TEXCOORD_0", "has 2 components but its accessor is VEC3"},
    {"draco-index-type-too-small", Encoding::DracoSequential,
     [](GltfBuilder& b) { b.doc["accessors"][3]["componentType"] = kUnsignedByte; }, "", ""},
    {"draco-lines-mode", Encoding::Draco,
     [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 1; }, kDraco,
     "mode must be TRIANGLES or TRIANGLE_STRIP"},
    {"draco-view-missing", Encoding::Draco,
     [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
              ["bufferView"] = 99;
     },
     kDraco + ".bufferView", "bufferView 99 does not exist"},
    {"draco-no-indices-accessor", Encoding::Draco,
     [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0].erase("indices"); }, kDraco,
     "triangles for a primitive without indices"},
    {"draco-accessor-from-two-streams", Encoding::Draco,
     [](GltfBuilder& b) {
         json prim = b.doc["meshes"][0]["primitives"][0];
         const json& view = b.doc["bufferViews"][0];
         b.doc["bufferViews"].push_back(view);
         prim["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 1;
         b.doc["meshes"][0]["primitives"].push_back(prim);
     },
     "meshes[0].primitives[1].extensions.KHR_draco_mesh_compression",
     "accessors[0] (POSITION) is also filled from another Draco stream"},
};

/// The cube of a case, edited, written as .gltf.
std::filesystem::path writeCase(const HostileCase& c) {
    GltfBuilder b;
    // The index-type case needs more than 255 points; the others the 24-vertex cube.
    const test::TestMesh mesh = std::string(c.name) == "draco-index-type-too-small"
                                    ? test::makeSphere(12, 24)
                                    : test::makeCube();
    test::addEncodedMesh(b, mesh, c.base);
    c.edit(b);
    return b.write(testOutputDir(), c.name);
}

TEST(GltfCompressionHostile, EveryCaseIsRefusedWithFileObjectAndReason) {
    for (const HostileCase& c : kCases) {
        SCOPED_TRACE(c.name);
        const auto o = loadCapturing(writeCase(c));
        if (!c.object.empty()) {
            EXPECT_TRUE(refusedWith(o, c.object, c.fragment));
            continue;
        }
        ASSERT_FALSE(o.scene) << "loaded";
        EXPECT_NE(o.scene.error().file.find(c.name), std::string::npos) << o.scene.error().describe();
        EXPECT_FALSE(o.scene.error().object.empty()) << o.scene.error().describe();
        EXPECT_EQ(o.scene.error().describe().find('\n'), std::string::npos);
    }
}

TEST(GltfCompressionHostile, TheCommandExitsWith1NamingFileAndObject) {
    for (const char* name : {"meshopt-truncated", "draco-huge-face-count-and-accessor"}) {
        SCOPED_TRACE(name);
        const HostileCase* c = nullptr;
        for (const HostileCase& k : kCases)
            if (std::string(k.name) == name) c = &k;
        ASSERT_TRUE(c);
        const auto path = writeCase(*c);
        const auto r = test::runLantern({"info", path.string()});
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("lantern: error: " + path.string() + ": " + c->object + ": "),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << r.err;
    }
}

TEST(GltfCompressionHostile, DecodedDataCountsAgainstTheByteLimit) {
    // A sphere whose decoded data (about 900 KB) exceeds a 500 KB limit that its file (and
    // the parsed JSON and models, some tens of KB) fits.
    const test::TestMesh sphere = test::makeSphere(96, 192);
    for (Encoding e : {Encoding::MeshoptQuantized, Encoding::Draco}) {
        SCOPED_TRACE(test::encodingName(e));
        GltfBuilder b;
        test::addEncodedMesh(b, sphere, e);
        const auto path = b.write(testOutputDir(), "limit-" + test::encodingName(e),
                                  GltfBuilder::Storage::Glb);
        ASSERT_LT(std::filesystem::file_size(path), 500000u);
        const auto o = loadCapturing(path, 500000);
        ASSERT_FALSE(o.scene);
        // The decoding step is refused (not a later one), against the load's whole budget.
        EXPECT_NE(o.scene.error().message.find(e == Encoding::Draco ? "decoding the Draco stream"
                                                                    : "decoding the compressed view"),
                  std::string::npos)
            << o.scene.error().describe();
        EXPECT_NE(o.scene.error().message.find("(--max-size, 500000 bytes in all)"),
                  std::string::npos)
            << o.scene.error().describe();
        EXPECT_TRUE(loadCapturing(path, 4000000).scene);
    }
}

TEST(GltfCompressionHostile, PrimitivesSharingOneDracoStreamDecodeItOnce) {
    GltfBuilder b;
    test::addEncodedMesh(b, test::makeCube(), Encoding::Draco);
    b.doc["meshes"][0]["primitives"].push_back(b.doc["meshes"][0]["primitives"][0]);
    const auto o = loadCapturing(b.write(testOutputDir(), "shared-stream"));
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    ASSERT_EQ(o.scene->meshes[0].primitives.size(), 2u);
    EXPECT_EQ(o.scene->meshes[0].primitives[1].positions, o.scene->meshes[0].primitives[0].positions);
}

} // namespace
