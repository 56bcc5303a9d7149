// PLY, STL and OFF through loadScene (no GPU): each encoding of each format gives the same
// geometry; colours, texture coordinates and normals as each format defines them; point
// clouds; refusals with the file, the element and the problem; the format known by content.
#include "MeshTestSupport.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <chrono>

namespace {

using namespace lantern;
using lantern::test::loadAny;
using lantern::test::putValue;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using lantern::test::writeBytes;
using lantern::test::writeText;

const Primitive& prim(const Scene& s) { return s.meshes.at(0).primitives.at(0); }

// --- PLY ------------------------------------------------------------------------------------

/// A PLY of a square (4 vertices, one quad) with uchar colours and (u, v), in `format`.
std::vector<unsigned char> squarePly(const std::string& format, const std::string& uv = "u v",
                                     const std::string& listTypes = "uchar int") {
    std::string head = "ply\nformat " + format + " 1.0\ncomment a square\nelement vertex 4\n"
                       "property float x\nproperty float y\nproperty float z\n"
                       "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    const auto space = uv.find(' ');
    head += "property float " + uv.substr(0, space) + "\nproperty float " + uv.substr(space + 1) +
            "\nelement face 1\nproperty list " + listTypes + " vertex_indices\nend_header\n";
    const float xyz[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    const unsigned char rgb[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {51, 102, 255}};
    const float tex[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<unsigned char> out(head.begin(), head.end());
    if (format == "ascii") {
        std::string body;
        for (int i = 0; i < 4; ++i)
            body += std::to_string(xyz[i][0]) + " " + std::to_string(xyz[i][1]) + " 0 " +
                    std::to_string(rgb[i][0]) + " " + std::to_string(rgb[i][1]) + " " +
                    std::to_string(rgb[i][2]) + " " + std::to_string(tex[i][0]) + " " +
                    std::to_string(tex[i][1]) + "\n";
        body += "4 0 1 2 3\n";
        out.insert(out.end(), body.begin(), body.end());
        return out;
    }
    const bool be = format == "binary_big_endian";
    for (int i = 0; i < 4; ++i) {
        for (float f : xyz[i]) putValue(out, f, be);
        for (unsigned char c : rgb[i]) out.push_back(c);
        for (float f : tex[i]) putValue(out, f, be);
    }
    if (listTypes == "uchar int") {
        out.push_back(4);
        for (int i = 0; i < 4; ++i) putValue(out, std::int32_t(i), be);
    } else {  // "ushort uint"
        putValue(out, std::uint16_t(4), be);
        for (int i = 0; i < 4; ++i) putValue(out, std::uint32_t(i), be);
    }
    return out;
}

TEST(PlyLoader, AsciiAndBothBinaryOrdersLoadTheSameSquare) {
    std::optional<Primitive> first;
    for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        SCOPED_TRACE(format);
        const auto path = testOutputDir() / ("square_" + format + ".ply");
        writeBytes(path, squarePly(format));
        auto o = loadAny(path);
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        const Primitive& p = prim(*o.scene);
        EXPECT_EQ(p.topology, Topology::Triangles);
        EXPECT_EQ(p.triangleCount(), 2u);
        ASSERT_EQ(p.positions.size(), 4u);
        EXPECT_EQ(p.positions[2], glm::vec3(2, 2, 0));
        EXPECT_EQ(p.colors[3], glm::vec4(0.2f, 0.4f, 1.0f, 1.0f)) << "uchar colours / 255";
        EXPECT_EQ(p.texcoords[3], glm::vec2(0.0f, 0.0f)) << "v grows upwards in PLY";
        EXPECT_EQ(p.normals[0], glm::vec3(0, 0, 1)) << "computed when the file has none";
        EXPECT_TRUE(o.warnings->empty()) << o.allWarnings();
        if (first) {
            EXPECT_EQ(p.indices, first->indices);
            EXPECT_EQ(p.texcoords, first->texcoords);
        }
        first = p;
    }
    const auto widePath = testOutputDir() / "wide.ply";
    writeBytes(widePath, squarePly("binary_big_endian", "u v", "ushort uint"));
    auto wide = loadAny(widePath);
    ASSERT_TRUE(wide.scene) << wide.scene.error().describe();
    ASSERT_TRUE(wide.scene) << wide.scene.error().describe();
    EXPECT_EQ(prim(*wide.scene).indices, first->indices) << "any list count and index type";
}

TEST(PlyLoader, EveryTextureCoordinateSpellingIsRead) {
    for (const std::string uv : {"u v", "s t", "texture_u texture_v", "texture_s texture_t"}) {
        const auto path = testOutputDir() / "uv.ply";
        writeBytes(path, squarePly("binary_little_endian", uv));
        auto o = loadAny(path);
        ASSERT_TRUE(o.scene) << uv << ": " << o.scene.error().describe();
        EXPECT_EQ(prim(*o.scene).texcoords.at(1), glm::vec2(1, 1)) << uv;
    }
}

TEST(PlyLoader, AFileWithoutFacesIsAPointCloudWithFloatColoursAndNormals) {
    const auto path = writeText(testOutputDir() / "cloud.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\n"
                                "property double x\nproperty double y\nproperty double z\n"
                                "property float nx\nproperty float ny\nproperty float nz\n"
                                "property float red\nproperty float green\nproperty float blue\n"
                                "property float alpha\nelement face 0\n"
                                "property list uchar int vertex_indices\nend_header\n"
                                "0 0 0 0 0 1 1 0 0 0.5\n1 0 0 0 0 1 0 1 0 1\n2 0 0 0 1 0 0 0 1 0.25\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Primitive& p = prim(*o.scene);
    EXPECT_EQ(p.topology, Topology::Points);
    EXPECT_EQ(p.elementCount(), 3u);
    EXPECT_EQ(p.colors[0], glm::vec4(1, 0, 0, 0.5f)) << "float colours as they are";
    EXPECT_EQ(p.normals[2], glm::vec3(0, 1, 0));
}

TEST(PlyLoader, FaceColoursAndOtherElements) {
    const auto path = writeText(testOutputDir() / "faces.ply",
                                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 2\n"
                                "property list uchar uint vertex_index\nproperty uchar red\n"
                                "property uchar green\nproperty uchar blue\n"
                                "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                                "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3 0 0 255\n0 1\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Primitive& p = prim(*o.scene);
    EXPECT_TRUE(p.indices.empty()) << "a face's colour makes its corners its own";
    ASSERT_EQ(p.colors.size(), 6u);
    EXPECT_EQ(p.colors[0], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(p.colors[5], glm::vec4(0, 0, 1, 1));
    EXPECT_TRUE(o.warned("edge")) << o.allWarnings();
}

TEST(PlyLoader, RefusalsNameTheElementAndComeBeforeAnyAllocation) {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
    struct Case {
        std::string text, object, fragment;
    };
    const Case cases[] = {
        {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "face 0", "corner 2 is 3, not a vertex index (0 to 3 - 1)"},
        {head + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "face 0", "not a vertex index"},
        {head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "vertex 1", "not finite"},
        {head + "0 0 0\n1 0 0\n0 1 0\n", "header", "element \"face\" claims 1 records"},
        {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1", "face 0", "the file ends inside it"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n0 0 0\n", "header", "no end_header"},
        {"ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n0 0 0\n", "header", "claims 1000000000000 records"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty int64 x\nend_header\n",
         "header", "unknown property type \"int64\""},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", "header",
         "some of x, y, z but not all"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\nend_header\n0\n", "header", "no x, y, z"},
        {"solid x\n", "header", "does not start with a \"ply\" line"},
    };
    for (const Case& c : cases) {
        const auto path = writeText(testOutputDir() / "bad.ply", c.text);
        const auto start = std::chrono::steady_clock::now();
        auto o = loadAny(path);
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.text;
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    }
}

// --- STL ------------------------------------------------------------------------------------

TEST(StlLoader, AsciiBinaryAndSolidHeadedBinaryLoadTheSameFlatFacets) {
    const auto dir = testOutputDir();
    writeText(dir / "a.stl", "solid part\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                             "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
                             " facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n"
                             "   vertex 0 0 1\n  endloop\n endfacet\nendsolid part\n");
    const std::vector<std::array<glm::vec3, 4>> facets = {
        {glm::vec3(0, 0, 1), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
        {glm::vec3(0, 0, 0), {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    writeBytes(dir / "b.stl", test::binaryStl("binary", facets));
    writeBytes(dir / "s.stl", test::binaryStl("solid but binary", facets));
    for (const char* name : {"a.stl", "b.stl", "s.stl"}) {
        SCOPED_TRACE(name);
        auto o = loadAny(dir / name);
        ASSERT_TRUE(o.scene) << o.scene.error().describe();
        const Primitive& p = prim(*o.scene);
        EXPECT_TRUE(p.indices.empty()) << "each facet its own three vertices";
        ASSERT_EQ(p.positions.size(), 6u);
        EXPECT_EQ(p.positions[5], glm::vec3(0, 0, 1));
        EXPECT_EQ(p.normals[0], glm::vec3(0, 0, 1));
        EXPECT_EQ(p.normals[3], glm::vec3(1, 0, 0)) << "a zero normal is recomputed";
        EXPECT_TRUE(o.warned("1 facet normal(s) were zero")) << o.allWarnings();
    }
    EXPECT_EQ(loadAny(dir / "a.stl").scene->meshes[0].name, "part");
    // The fidelity report names the format, and --up z when it is given.
    LoadOptions zUp;
    zUp.up = UpAxis::Z;
    auto turned = loadAny(dir / "b.stl", zUp);
    ASSERT_TRUE(turned.scene);
    std::vector<std::string> keys;
    for (const FeatureUse& f : turned.scene->features) keys.push_back(f.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"stl", "up-axis"}));
}

TEST(StlLoader, RefusalsNameTheFacet) {
    const auto dir = testOutputDir();
    const std::vector<std::array<glm::vec3, 4>> facets = {
        {glm::vec3(0, 0, 1), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
        {glm::vec3(0, 0, 1), {0, 0, 0}, {1, NAN, 0}, {0, 1, 0}}};
    writeBytes(dir / "nan.stl", test::binaryStl("x", facets));
    EXPECT_TRUE(refusedWith(loadAny(dir / "nan.stl"), "facet 1", "vertex 1 is not a finite number"));
    std::vector<unsigned char> cut = test::binaryStl("x", facets);
    cut.resize(cut.size() - 10);
    writeBytes(dir / "cut.stl", cut);
    EXPECT_TRUE(refusedWith(loadAny(dir / "cut.stl"), "", "neither a binary STL"));
    writeText(dir / "two.stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                               "endloop\nendfacet\nendsolid\n");
    EXPECT_TRUE(refusedWith(loadAny(dir / "two.stl"), "facet 0", "2 vertices; a facet needs 3"));
    writeText(dir / "word.stl", "solid\nfacet normal 0 0 one\n");
    EXPECT_TRUE(refusedWith(loadAny(dir / "word.stl"), "facet 0", "expected a number, got \"one\""));
}

// --- OFF ------------------------------------------------------------------------------------

TEST(OffLoader, HeadersColoursAndPolygons) {
    const auto dir = testOutputDir();
    writeText(dir / "plain.off", "OFF\n# a comment\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 2 0\n"
                                 "4 0 1 2 3\n3 3 2 4 255 0 0\n");
    auto plain = loadAny(dir / "plain.off");
    ASSERT_TRUE(plain.scene) << plain.scene.error().describe();
    const Primitive& p = prim(*plain.scene);
    EXPECT_EQ(p.triangleCount(), 3u);
    ASSERT_EQ(p.colors.size(), 9u) << "a coloured face: its corners its own";
    EXPECT_EQ(p.colors[0], glm::vec4(1)) << "faces without a colour are white";
    EXPECT_EQ(p.colors[6], glm::vec4(1, 0, 0, 1)) << "integers are 0-255";

    writeText(dir / "c.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 0.5 0 1\n0 1 0 0 0 1.0 0.5\n3 0 1 2\n");
    auto c = loadAny(dir / "c.off");
    ASSERT_TRUE(c.scene) << c.scene.error().describe();
    EXPECT_EQ(prim(*c.scene).colors[0], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(prim(*c.scene).colors[1], glm::vec4(0, 0.5f, 0, 1)) << "decimals are 0-1";
    EXPECT_EQ(prim(*c.scene).colors[2], glm::vec4(0, 0, 1, 0.5f));

    writeText(dir / "n.off", "NOFF 3 1 0\n0 0 0 0 0 -1\n1 0 0 0 0 -1\n0 1 0 0 0 -1\n3 0 1 2\n");
    auto n = loadAny(dir / "n.off");
    ASSERT_TRUE(n.scene) << n.scene.error().describe();
    EXPECT_EQ(prim(*n.scene).normals[1], glm::vec3(0, 0, -1)) << "the file's normals";

    writeText(dir / "points.off", "OFF\n2 0 0\n0 0 0\n1 1 1\n");
    auto pts = loadAny(dir / "points.off");
    ASSERT_TRUE(pts.scene) << pts.scene.error().describe();
    EXPECT_EQ(prim(*pts.scene).topology, Topology::Points);
}

TEST(OffLoader, RefusalsNameTheElement) {
    struct Case {
        std::string text, object, fragment;
    };
    const Case cases[] = {
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "face 0", "corner 2: \"3\" is not a vertex index"},
        {"OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "vertex 1", "not finite"},
        {"OFF\n1000000000000 1 0\n0 0 0\n", "header", "need more than the"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n", "face 0", "more than the rest of the file"},
        {"COFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n", "vertex 0", "outside 0-255"},
        {"4OFF\n", "header", "homogeneous"},
        {"OFF BINARY\n", "header", "OFF BINARY"},
        {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "face 1", "the file ends before it"},
    };
    for (const Case& c : cases) {
        const auto path = writeText(testOutputDir() / "bad.off", c.text);
        EXPECT_TRUE(refusedWith(loadAny(path), c.object, c.fragment)) << c.text;
    }
}

// --- Every format ---------------------------------------------------------------------------

TEST(MeshFormats, AFileWhoseNameSaysNothingIsKnownByItsFirstBytes) {
    const auto dir = testOutputDir();
    writeBytes(dir / "model.ply.part", squarePly("binary_little_endian"));
    writeText(dir / "model.off.part", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    writeText(dir / "model.stl.part", "solid\nendsolid\n");
    writeBytes(dir / "model.bin.part",
               test::binaryStl("solid x", {{glm::vec3(0, 0, 1), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}));
    for (const char* name : {"model.ply.part", "model.off.part", "model.stl.part", "model.bin.part"}) {
        auto o = loadAny(dir / name);
        EXPECT_TRUE(o.scene) << name << ": " << o.scene.error().describe();
    }
}

TEST(MeshFormats, UpZTurnsTheFileSoThatItsZPointsUp) {
    const auto path = testOutputDir() / "tall.stl";
    writeBytes(path, test::binaryStl("x", {{glm::vec3(0, 0, 1), {0, 0, 0}, {1, 0, 0}, {0, 0, 5}}}));
    for (UpAxis up : {UpAxis::Y, UpAxis::Z}) {
        LoadOptions o;
        o.up = up;
        auto loaded = loadAny(path, o);
        ASSERT_TRUE(loaded.scene) << loaded.scene.error().describe();
        const Bounds b = computeBounds(*loaded.scene, evaluatePose(*loaded.scene, -1, 0.0));
        if (up == UpAxis::Y) {
            EXPECT_EQ(b.max, glm::dvec3(1, 0, 5));
        } else {
            EXPECT_EQ(b.max, glm::dvec3(1, 5, 0)) << "+Z became +Y";
            EXPECT_EQ(b.min, glm::dvec3(0, 0, 0));
        }
    }
}

TEST(MeshFormats, TheBudgetRefusesWhatTheFileWouldHaveLanternHold) {
    const auto path = testOutputDir() / "budget.ply";
    writeBytes(path, squarePly("binary_little_endian"));
    LoadOptions small;
    small.maxBytes = 400;  // the file (about 330 bytes) fits, its vertices and faces do not
    auto o = loadAny(path, small);
    ASSERT_FALSE(o.scene);
    EXPECT_NE(o.scene.error().message.find("--max-size"), std::string::npos)
        << o.scene.error().describe();
}

} // namespace
