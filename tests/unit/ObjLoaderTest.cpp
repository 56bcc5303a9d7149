// OBJ and MTL through loadScene (no GPU): every face form, negative indices, polygons, lines
// and points, smoothing groups, objects and groups, vertex colours; every MTL key onto the
// classic material with no PBR step, the maps and their warnings; refusals with the file, the
// element and the line.
#include "MeshTestSupport.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace lantern;
using lantern::test::loadAny;
using lantern::test::refusedWith;
using lantern::test::testOutputDir;
using lantern::test::writeText;

const Primitive& prim(const Scene& s, std::size_t mesh = 0, std::size_t p = 0) {
    return s.meshes.at(mesh).primitives.at(p);
}

// The corner positions of a primitive's triangles, in order.
std::vector<glm::vec3> corners(const Primitive& p) {
    std::vector<glm::vec3> out;
    for (std::uint32_t i : p.indices) out.push_back(p.positions[i]);
    return out;
}

// Twice the signed area of triangle t of `c` seen from +Z.
float cross2(const std::vector<glm::vec3>& c, std::size_t t) {
    const glm::vec3 a = c[3 * t], b = c[3 * t + 1], d = c[3 * t + 2];
    return (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
}

TEST(ObjLoader, EveryFaceFormReadsItsAttributes) {
    const auto path = writeText(testOutputDir() / "forms.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                "vt 0 0\nvt 1 0\nvt 0 0.25\n"
                                "vn 0 0 1\n"
                                "f 1/1/1 2/2/1 3/3/1\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Primitive& p = prim(*o.scene);
    EXPECT_EQ(p.topology, Topology::Triangles);
    ASSERT_EQ(p.positions.size(), 3u);
    EXPECT_EQ(corners(p), (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    // OBJ's v grows upwards, Lantern's textures are read top row first: v' = 1 - v.
    ASSERT_EQ(p.texcoords.size(), 3u);
    EXPECT_EQ(p.texcoords[p.indices[2]], glm::vec2(0.0f, 0.75f));
    EXPECT_EQ(p.normals[p.indices[1]], glm::vec3(0, 0, 1));
    EXPECT_TRUE(p.colors.empty());
    EXPECT_EQ(p.material, -1);
    EXPECT_TRUE(o.warnings->empty()) << o.allWarnings();

    // Without vt and vn: no texture coordinates, normals computed (faceted: smoothing is off).
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    auto bare = loadAny(path);
    ASSERT_TRUE(bare.scene) << bare.scene.error().describe();
    EXPECT_TRUE(prim(*bare.scene).texcoords.empty());
    for (const glm::vec3& n : prim(*bare.scene).normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
    // v//vn and v/vt forms.
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 1/1 3/1 2/1\n");
    auto mixed = loadAny(path);
    ASSERT_TRUE(mixed.scene) << mixed.scene.error().describe();
    EXPECT_EQ(prim(*mixed.scene).triangleCount(), 2u);
    EXPECT_EQ(prim(*mixed.scene).normals[prim(*mixed.scene).indices[0]], glm::vec3(0, 0, -1));
}

TEST(ObjLoader, NegativeIndicesCountBackFromTheVerticesReadSoFar) {
    const auto path = writeText(testOutputDir() / "neg.obj",
                                "v 9 9 9\nv 0 0 0\nv 2 0 0\nv 0 2 0\nf -3 -2 -1\nv 5 5 5\nf -4 -3 -2\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const std::vector<glm::vec3> c = corners(prim(*o.scene));
    ASSERT_EQ(c.size(), 6u);
    EXPECT_EQ(c[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(c[2], glm::vec3(0, 2, 0));
    EXPECT_EQ(c[3], glm::vec3(0, 0, 0)) << "-4 after the fifth vertex is the second";
}

TEST(ObjLoader, PolygonsOfAnyDegreeAreTriangulatedInsideTheirOutline) {
    // A concave L (6 corners, area 3) and a convex 40-gon: the triangles must tile the outline:
    // all turn the polygon's way and their areas add up to its area.
    std::string text = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n";
    for (int i = 0; i < 40; ++i)
        text += "v " + std::to_string(10 + std::cos(i * 0.15707963267948966)) + " " +
                std::to_string(std::sin(i * 0.15707963267948966)) + " 0\n";
    text += "f";
    for (int i = 7; i <= 46; ++i) text += " " + std::to_string(i);
    const auto path = writeText(testOutputDir() / "poly.obj", text + "\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const std::vector<glm::vec3> c = corners(prim(*o.scene));
    ASSERT_EQ(c.size(), 3u * (4 + 38));
    float lArea = 0.0f, circle = 0.0f;
    for (std::size_t t = 0; t < c.size() / 3; ++t) {
        EXPECT_GE(cross2(c, t), 0.0f) << "triangle " << t << " turns against its polygon";
        (t < 4 ? lArea : circle) += 0.5f * cross2(c, t);
    }
    EXPECT_NEAR(lArea, 3.0f, 1e-5f) << "the L's triangles cover it exactly once";
    EXPECT_NEAR(circle, 20.0f * std::sin(0.15707963267948966), 1e-3f);
}

TEST(ObjLoader, AQuadSplitsAlongItsShorterDiagonal) {
    const auto path = writeText(testOutputDir() / "quad.obj",
                                "v 0 0 0\nv 4 0 0\nv 5 1 0\nv 1 1 0\nf 1 2 3 4\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const std::vector<glm::vec3> c = corners(prim(*o.scene));
    ASSERT_EQ(c.size(), 6u);
    // Diagonal 2-4 ((4,0)-(1,1), length 3.2) is shorter than 1-3 ((0,0)-(5,1), 5.1): both
    // triangles have both its ends.
    for (std::size_t t = 0; t < 2; ++t) {
        const std::vector<glm::vec3> tri(c.begin() + 3 * t, c.begin() + 3 * t + 3);
        EXPECT_NE(std::find(tri.begin(), tri.end(), glm::vec3(4, 0, 0)), tri.end()) << t;
        EXPECT_NE(std::find(tri.begin(), tri.end(), glm::vec3(1, 1, 0)), tri.end()) << t;
        EXPECT_GT(cross2(c, t), 0.0f);
    }
}

TEST(ObjLoader, LinesAndPointsArePrimitivesOfTheirObjectDrawnUnlit) {
    const auto path = writeText(testOutputDir() / "lp.obj",
                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no wire\n"
                                "l 1 2 3 4\np 1 3\nusemtl other\np -1\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    ASSERT_EQ(o.scene->meshes.size(), 1u);
    EXPECT_EQ(o.scene->meshes[0].name, "wire");
    EXPECT_EQ(o.scene->nodes.at(0).name, "wire");
    const Primitive& lines = prim(*o.scene, 0, 0);
    EXPECT_EQ(lines.topology, Topology::Lines);
    EXPECT_EQ(lines.elementCount(), 3u) << "a polyline of 4 corners is 3 segments";
    EXPECT_TRUE(lines.unlitForWantOfNormals());
    const Primitive& points = prim(*o.scene, 0, 1);
    EXPECT_EQ(points.topology, Topology::Points);
    EXPECT_EQ(points.elementCount(), 2u);
    EXPECT_EQ(prim(*o.scene, 0, 2).elementCount(), 1u) << "p after usemtl: a run of its own";
    EXPECT_EQ(prim(*o.scene, 0, 2).positions.at(0), glm::vec3(0, 1, 0));
}

TEST(ObjLoader, SmoothingGroupsDecideWhichFacesShareANormal) {
    // Two faces folded at the X axis: with smoothing off each keeps its face normal; in one group
    // the shared edge's corners are welded and their normal is the two faces' mean; vn wins.
    const std::string geometry = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    const auto path = testOutputDir() / "smooth.obj";
    writeText(path, geometry + "s off\nf 1 2 3\nf 2 1 4\n");
    auto off = loadAny(path);
    ASSERT_TRUE(off.scene) << off.scene.error().describe();
    EXPECT_EQ(prim(*off.scene).positions.size(), 6u);
    EXPECT_EQ(prim(*off.scene).normals[prim(*off.scene).indices[0]], glm::vec3(0, 0, 1));
    EXPECT_EQ(prim(*off.scene).normals[prim(*off.scene).indices[3]], glm::vec3(0, 1, 0));

    writeText(path, geometry + "s 1\nf 1 2 3\nf 2 1 4\n");
    auto on = loadAny(path);
    ASSERT_TRUE(on.scene) << on.scene.error().describe();
    const Primitive& p = prim(*on.scene);
    EXPECT_EQ(p.positions.size(), 4u);
    const glm::vec3 edge = p.normals[p.indices[0]];
    EXPECT_NEAR(edge.y, edge.z, 1e-6f);
    EXPECT_NEAR(glm::length(edge), 1.0f, 1e-6f);

    writeText(path, geometry + "s 1\nf 1 2 3\ns 2\nf 2 1 4\n");
    auto two = loadAny(path);
    ASSERT_TRUE(two.scene) << two.scene.error().describe();
    EXPECT_EQ(prim(*two.scene).positions.size(), 6u) << "two groups weld nothing";

    writeText(path, geometry + "vn 1 0 0\ns 1\nf 1//1 2//1 3//1\n");
    auto given = loadAny(path);
    ASSERT_TRUE(given.scene) << given.scene.error().describe();
    for (const glm::vec3& n : prim(*given.scene).normals) EXPECT_EQ(n, glm::vec3(1, 0, 0));
}

TEST(ObjLoader, ObjectsBecomeNodesAndMaterialsPrimitives) {
    const auto dir = testOutputDir();
    writeText(dir / "m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n");
    const auto path = writeText(dir / "objects.obj",
                                "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                "o first\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nf 1 2 3\n"
                                "g second part\nusemtl a\nf 3 2 1\nv 1 1 1 0.5 0.25 1\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    ASSERT_EQ(o.scene->nodes.size(), 2u);
    EXPECT_EQ(o.scene->nodes[0].name, "first");
    EXPECT_EQ(o.scene->nodes[1].name, "second part");
    ASSERT_EQ(o.scene->meshes[0].primitives.size(), 2u);
    EXPECT_EQ(prim(*o.scene, 0, 0).material, 0);
    EXPECT_EQ(prim(*o.scene, 0, 1).material, 1);
    EXPECT_EQ(prim(*o.scene, 0, 1).triangleCount(), 2u);
    EXPECT_EQ(prim(*o.scene, 1, 0).material, 0);
    EXPECT_EQ(o.scene->roots.at(0).nodes, (std::vector<int>{0, 1}));
    EXPECT_TRUE(prim(*o.scene).colors.empty()) << "colours only when every v line has them";

    writeText(path, "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n");
    auto coloured = loadAny(path);
    ASSERT_TRUE(coloured.scene) << coloured.scene.error().describe();
    const Primitive& c = prim(*coloured.scene);
    ASSERT_EQ(c.colors.size(), 3u);
    EXPECT_EQ(c.colors[c.indices[2]], glm::vec4(0, 0, 0.5f, 1));
}

TEST(ObjLoader, MtlColoursMapOntoTheClassicMaterialWithoutAPbrStep) {
    const auto dir = testOutputDir();
    writeText(dir / "keys.mtl",
              "newmtl full\nKa 0.125 0.25 0.5\nKd 0.5 0.25 0.75\nKs 0.75 0.5 0.25\nKe 0.25 0 0.125\n"
              "Ns 37.5\nd 1\nillum 2\n"
              "newmtl clear\nKd 1 1 1\nTr 0.25\nillum 2\n"
              "newmtl flat\nKd 0.5 0.5 0.5\nKs 1 1 1\nillum 1\n"
              "newmtl colour\nKd 0.25 0.5 1\nillum 0\n"
              "newmtl plain\nKd 0.5 0.5 0.5\nKs 0.25 0.25 0.25\n");
    const auto path = writeText(dir / "keys.obj", "mtllib keys.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                  "usemtl full\nf 1 2 3\nusemtl clear\nf 1 2 3\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    ASSERT_EQ(o.scene->materials.size(), 5u);
    const Material& full = o.scene->materials[0];
    EXPECT_EQ(full.name, "full");
    EXPECT_EQ(full.front.ambient, glm::dvec3(0.125, 0.25, 0.5));
    EXPECT_EQ(full.front.diffuse, glm::dvec4(0.5, 0.25, 0.75, 1.0));
    EXPECT_EQ(full.front.specular, glm::dvec3(0.75, 0.5, 0.25));
    EXPECT_EQ(full.front.emission, glm::dvec3(0.25, 0.0, 0.125));
    EXPECT_EQ(full.front.shininess, 37.5);
    EXPECT_FALSE(full.unlit);
    EXPECT_FALSE(full.pbr) << "no PBR step";
    EXPECT_FALSE(full.ambientFollowsDiffuse);
    EXPECT_EQ(full.alphaMode, AlphaMode::Opaque);
    const Material& clear = o.scene->materials[1];
    EXPECT_EQ(clear.front.diffuse.a, 0.75) << "Tr = 1 - d";
    EXPECT_EQ(clear.alphaMode, AlphaMode::Blend);
    EXPECT_EQ(o.scene->materials[2].front.specular, glm::dvec3(0.0)) << "illum 1: no specular";
    EXPECT_TRUE(o.scene->materials[3].unlit) << "illum 0: colour only";
    EXPECT_EQ(o.scene->materials[3].front.diffuse, glm::dvec4(0.25, 0.5, 1.0, 1.0));
    EXPECT_FALSE(o.scene->materials[4].unlit) << "no illum line: lit in full";
    EXPECT_EQ(o.scene->materials[4].front.specular, glm::dvec3(0.25));
}

TEST(ObjLoader, MtlMapsFillTheSlotsLanternHasAndNameTheOthers) {
    const auto dir = testOutputDir();
    const std::vector<unsigned char> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    test::writePng(dir / "colour.png", 2, 2, 3, rgb);
    test::writePng(dir / "normal.png", 2, 2, 3, std::vector<unsigned char>(12, 128));
    test::writePng(dir / "height.png", 2, 2, 1, {0, 64, 128, 255});
    test::writePng(dir / "mask.png", 2, 2, 1, {255, 128, 0, 255});
    test::writePng(dir / "alpha.png", 2, 2, 2, {9, 10, 9, 20, 9, 30, 9, 40});
    writeText(dir / "maps.mtl",
              "newmtl a\nKd 1 1 1\nmap_Kd colour.png\nmap_Ke -s 2 2 1 colour.png\n"
              "norm normal.png\nmap_Ks colour.png\nmap_d mask.png\n"
              "newmtl b\nKd 1 1 1\nbump height.png\nmap_d alpha.png\n"
              "newmtl c\nbump -bm 0.5 normal.png\nmap_Kd missing.png\n");
    const auto path = writeText(dir / "maps.obj", "mtllib maps.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    const Material& a = o.scene->materials.at(0);
    ASSERT_GE(a.baseColorTexture, 0);
    const Texture& base = o.scene->textures[std::size_t(a.baseColorTexture)];
    EXPECT_TRUE(base.srgb);
    EXPECT_EQ(base.width, 2);
    EXPECT_EQ(std::vector<std::uint8_t>(base.rgba8.begin(), base.rgba8.begin() + 8),
              (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 128})) << "map_d's grey is the alpha";
    EXPECT_EQ(a.alphaMode, AlphaMode::Blend);
    ASSERT_GE(a.emissiveMap.texture, 0);
    EXPECT_EQ(a.emissiveMap.uvTransform[0][0], 2.0) << "-s scales the coordinates";
    EXPECT_EQ(a.emissiveMap.uvTransform[2][1], -1.0) << "and moves them as OBJ's v points up";
    ASSERT_GE(a.normalMap.texture, 0);
    EXPECT_FALSE(o.scene->textures[std::size_t(a.normalMap.texture)].srgb) << "normal maps are data";
    EXPECT_TRUE(o.warned("materials \"a\": map_Ks not read")) << o.allWarnings();
    const Material& b = o.scene->materials.at(1);
    EXPECT_EQ(b.normalMap.texture, -1);
    EXPECT_TRUE(o.warned("grey height (bump) map")) << o.allWarnings();
    ASSERT_GE(b.baseColorTexture, 0) << "map_d alone: white with its alpha";
    const Texture& white = o.scene->textures[std::size_t(b.baseColorTexture)];
    EXPECT_EQ(std::vector<std::uint8_t>(white.rgba8.begin(), white.rgba8.begin() + 8),
              (std::vector<std::uint8_t>{255, 255, 255, 10, 255, 255, 255, 20})) << "its own alpha";
    const Material& c = o.scene->materials.at(2);
    EXPECT_GE(c.normalMap.texture, 0) << "bump holding an RGB image is read as a normal map";
    EXPECT_EQ(c.normalScale, 0.5);
    EXPECT_EQ(c.baseColorTexture, -1);
    EXPECT_TRUE(o.warned("\"missing.png\" does not exist")) << o.allWarnings();
    // The fidelity report (lantern info --json) names the format, the maps and the skipped ones.
    auto objectsOf = [&](std::string_view key) {
        for (const FeatureUse& f : o.scene->features)
            if (f.key == key) return f.objects;
        return std::vector<std::string>{"(not noted)"};
    };
    EXPECT_EQ(objectsOf("obj"), std::vector<std::string>{"maps.obj"});
    EXPECT_EQ(objectsOf("base-color-texture"),
              (std::vector<std::string>{"materials \"a\"", "materials \"b\""}));
    EXPECT_EQ(objectsOf("normal-texture"),
              (std::vector<std::string>{"materials \"a\"", "materials \"c\""}));
    EXPECT_EQ(objectsOf("emissive-texture"), std::vector<std::string>{"materials \"a\""});
    EXPECT_EQ(objectsOf("obj-skipped-maps"), std::vector<std::string>{"materials \"a\""});
    EXPECT_EQ(objectsOf("ply"), std::vector<std::string>{"(not noted)"});
}

TEST(ObjLoader, AMissingLibraryOrMaterialIsAWarningAndTheDefaultMaterial) {
    const auto path = writeText(testOutputDir() / "nomtl.obj",
                                "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl ghost\nf 1 2 3\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_EQ(prim(*o.scene).material, -1);
    EXPECT_TRUE(o.warned("mtllib \"absent.mtl\": does not exist")) << o.allWarnings();
    EXPECT_TRUE(o.warned("'ghost'")) << o.allWarnings();
}

TEST(ObjLoader, RefusalsNameTheFileTheElementAndTheLine) {
    struct Case {
        std::string text, object, fragment;
    };
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const Case cases[] = {
        {"v 0 0 0\nv nan 0 0\n", "vertex 2", "\"nan\" is not a finite number (line 2)"},
        {"v 0 0 inf\n", "vertex 1", "\"inf\""},
        {"v 0 0 1e999\nv 0 0 0\nv 0 0 0\nf 1 2 3\n", "vertex 1", "beyond float's range"},
        {tri + "vn 0 nan 1\n", "normal 1", "\"nan\""},
        {tri + "vt 0 -inf\n", "texture coordinate 1", "\"-inf\""},
        {tri + "f 1 2 4\n", "face 1", "outside the file's 3 vertices"},
        {tri + "f 1 2 3\nf 1 -4 3\n", "face 2", "outside"},
        {tri + "f 1 2 0\n", "face 1", "corner 3 \"0\""},
        {tri + "f 1 2 99999999999\n", "face 1", "2^31 - 1"},
        {tri + "f 1/5 2/1 3/1\nvt 0 0\n", "face 1", "texture coordinates"},
        {tri + "f 1 2 x\n", "face 1", "\"x\""},
        {tri + "l 1 7\n", "line element 1", "names vertex 7"},
        {tri + "p -4\n", "point element 1", "reaches before the first vertex"},
        {std::string("v 0 0 0\nv\0 1 1\n", 15), "", "NUL byte: an OBJ file is text (line 2)"},
    };
    for (const Case& c : cases) {
        const auto path = writeText(testOutputDir() / "bad.obj", c.text);
        auto o = loadAny(path);
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.text;
    }
}

TEST(ObjLoader, FacesWithFewerThanThreeCornersAreSkippedWithAWarning) {
    const auto path = writeText(testOutputDir() / "short.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1\nf 1 2 3\nf 1 1 1\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_EQ(prim(*o.scene).triangleCount(), 2u) << "degenerate triangles are kept";
    EXPECT_TRUE(o.warned("2 face(s) with fewer than 3 corners skipped")) << o.allWarnings();
}

TEST(ObjLoader, AFileWithNothingToDrawLoadsEmpty) {
    const auto path = writeText(testOutputDir() / "empty.obj", "# nothing\nv 0 0 0\n");
    auto o = loadAny(path);
    ASSERT_TRUE(o.scene) << o.scene.error().describe();
    EXPECT_TRUE(o.scene->meshes.empty());
    ASSERT_TRUE(nothingToDraw(*o.scene).has_value());
}

} // namespace
