// Exact data passes (docs/aovs.md): a glTF of known quads rendered with every AOV,
// each pixel checked against where its centre's ray meets the quads' plane: the id planes
// exactly (node, mesh, primitive, material, semantic from extras, the background's values),
// depth and range against the ray, range = depth |ray| / |z|, the world normal against the
// plane's and against the inverse view rotation of the eye normal, uv against the quad's
// corners; MSAA leaves the ids unblended; orthographic depth; the UINT channels through an EXR
// and the command line.
#include "GltfTestBuilder.h"
#include "TestSupport.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <map>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::GltfBuilder;
using nlohmann::json;

constexpr int kSize = 96;

// An axis-aligned quad in the z = 0 plane facing +Z, with normals and (optionally) TEXCOORD_0
// running from (0, 0) at (x0, y0) to (1, 1) at (x1, y1).
json quad(GltfBuilder& b, double x0, double x1, double y0, double y1, bool texcoords,
          int material) {
    const float X0 = float(x0), X1 = float(x1), Y0 = float(y0), Y1 = float(y1);
    json prim = {{"attributes",
                  {{"POSITION", b.addFloats({X0, Y0, 0, X1, Y0, 0, X1, Y1, 0, X0, Y1, 0}, "VEC3")},
                   {"NORMAL", b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}},
                 {"indices", b.addIndices({0, 1, 2, 0, 2, 3})}};
    if (texcoords) prim["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2");
    if (material >= 0) prim["material"] = material;
    return prim;
}

// What a pixel should hold: the ids of the quad its centre's ray meets (or the background).
struct Expected {
    std::uint32_t node = kNoId, mesh = kNoId, primitive = kNoId, material = kNoId, semantic = 0;
    glm::dvec2 uv{0.0};
    bool operator==(const Expected& o) const {
        return node == o.node && mesh == o.mesh && primitive == o.primitive;
    }
};

// The layout: quad A (mesh 0, material 0, node 0 with semantic 7, texture coordinates), the same
// mesh again above it (node 3, no semantic), and mesh 1 to the right: two primitives, the top
// with material 1, the bottom with none (the default material, index 2), on node 2 whose parent
// (node 1) has semantic 9.
std::filesystem::path writeLayout(const std::filesystem::path& dir) {
    GltfBuilder b;
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.2, 1.0}}}}},
         {{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.8, 0.2, 1.0}}}}}});
    const int meshA = b.addMesh(quad(b, -2.0, -0.25, -1.0, 1.0, true, 0));
    b.doc["meshes"].push_back({{"primitives", json::array({quad(b, 0.25, 2.0, 0.0, 1.0, false, 1),
                                                           quad(b, 0.25, 2.0, -1.0, 0.0, false, -1)})}});
    b.addNode({{"mesh", meshA}, {"extras", {{"semantic_id", 7}}}});
    b.addNode({{"children", {2}}, {"extras", {{"semantic_id", 9}, {"other", "kept"}}}});
    b.addNode({{"mesh", 1}}, false);
    b.addNode({{"mesh", meshA}, {"translation", {0.0, 2.5, 0.0}}});
    return b.write(dir, "layout");
}

Expected expectedAt(glm::dvec2 p) {
    Expected e;
    auto in = [&](double x0, double x1, double y0, double y1) {
        return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
    };
    if (in(-2.0, -0.25, -1.0, 1.0))
        e = {0, 0, 0, 0, 7, {(p.x + 2.0) / 1.75, (p.y + 1.0) / 2.0}};
    else if (in(-2.0, -0.25, 1.5, 3.5))
        e = {3, 0, 0, 0, 0, {(p.x + 2.0) / 1.75, (p.y - 1.5) / 2.0}};
    else if (in(0.25, 2.0, 0.0, 1.0))
        e = {2, 1, 0, 1, 9, {0.0, 0.0}};
    else if (in(0.25, 2.0, -1.0, 0.0))
        e = {2, 1, 1, 2, 9, {0.0, 0.0}};
    return e;
}

// The ray of pixel (x, y)'s centre in eye space, from the image's camera: two points on it.
struct EyeRay {
    glm::dvec3 a, b;
};
EyeRay eyeRay(const Image& image, int x, int y) {
    const glm::dmat4 viewFromClip = glm::inverse(image.camera->clipFromView);
    const double nx = 2.0 * (x + 0.5) / image.width - 1.0;
    const double ny = 2.0 * (y + 0.5) / image.height - 1.0;  // Vulkan clip space: y down
    auto at = [&](double z) {
        const glm::dvec4 p = viewFromClip * glm::dvec4(nx, ny, z, 1.0);
        return glm::dvec3(p) / p.w;
    };
    return {at(0.25), at(0.75)};
}

// Where pixel (x, y)'s ray meets the world plane z = 0, in world and in eye space.
struct Hit {
    glm::dvec3 world, eye;
};
Hit hitPlane(const Image& image, int x, int y) {
    const EyeRay r = eyeRay(image, x, y);
    const glm::dmat4 worldFromView = glm::inverse(image.camera->viewFromWorld);
    const glm::dvec3 a = glm::dvec3(worldFromView * glm::dvec4(r.a, 1.0));
    const glm::dvec3 b = glm::dvec3(worldFromView * glm::dvec4(r.b, 1.0));
    const double t = a.z / (a.z - b.z);
    const glm::dvec3 world = a + t * (b - a);
    return {world, glm::dvec3(image.camera->viewFromWorld * glm::dvec4(world, 1.0))};
}

// Whether pixel (x, y) and its eight neighbours expect the same surface (away from edges,
// where which triangle covers the centre is the rasteriser's rounding).
bool interior(const Image& image, int x, int y) {
    const Expected e = expectedAt(hitPlane(image, x, y).world);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= image.width || v >= image.height) return false;
            if (!(expectedAt(hitPlane(image, u, v).world) == e)) return false;
        }
    return true;
}

RenderOptions allAovs(bool orthographic = false) {
    RenderOptions o;
    o.width = o.height = kSize;
    o.background = glm::vec4(0.0f);
    for (const char* name : {"depth", "range", "normal", "world_normal", "uv", "instance",
                             "primitive", "material", "semantic"})
        EXPECT_TRUE(enableAov(o.aovs, name)) << name;
    o.camera.lookAt = LookAt{{2.5, 1.5, 5.5}, {0.0, 0.8, 0.0}, {0.0, 1.0, 0.0}};
    o.camera.projection = orthographic ? Projection::makeOrtho(-3.5, 3.5, -3.5, 3.5, 0.5, 20.0)
                                       : Projection::makePerspective(1.1, 1.0, 0.5, 20.0);
    return o;
}

class Aov : public GpuTest {
protected:
    Scene load() {
        auto s = loadScene(writeLayout(test::testOutputDir()).string());
        EXPECT_TRUE(s) << s.error().describe();
        return s ? std::move(*s) : Scene{};
    }
    Image render(const RenderOptions& o) {
        const Scene scene = load();
        auto image = renderer().render(scene, o, 0.0);
        EXPECT_TRUE(image) << image.error().describe();
        return image ? std::move(*image) : Image{};
    }
};

TEST(AovNames, EveryNameSwitchesOnItsPlaneAndOnlyThat) {
    AovSet all;
    int count = 0;
    for (const char* name : {"depth", "range", "normal", "world_normal", "uv", "instance",
                             "primitive", "material", "semantic"}) {
        AovSet one;
        ASSERT_TRUE(enableAov(one, name)) << name;
        EXPECT_TRUE(one.any()) << name;
        ASSERT_TRUE(enableAov(all, name));
        ++count;
    }
    AovSet none;
    EXPECT_FALSE(enableAov(none, "worldnormal"));
    EXPECT_FALSE(none.any());
    EXPECT_EQ(count, 9);
    EXPECT_TRUE(all.depth && all.range && all.normal && all.worldNormal && all.uv &&
                all.instance && all.primitive && all.material && all.semantic);
}

TEST_F(Aov, IdPlanesHoldTheExactIdsOfTheSurfaceAtEachPixel) {
    const Image image = render(allAovs());
    ASSERT_EQ(image.instance.size(), image.pixelCount());
    ASSERT_EQ(image.mesh.size(), image.pixelCount());
    ASSERT_EQ(image.primitive.size(), image.pixelCount());
    ASSERT_EQ(image.material.size(), image.pixelCount());
    ASSERT_EQ(image.semantic.size(), image.pixelCount());
    std::map<std::uint32_t, int> checkedPerNode;
    int wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!interior(image, x, y)) continue;
            const Expected e = expectedAt(hitPlane(image, x, y).world);
            const std::size_t i = std::size_t(y) * kSize + x;
            const bool ok = image.instance[i] == e.node && image.mesh[i] == e.mesh &&
                            image.primitive[i] == e.primitive &&
                            image.material[i] == e.material && image.semantic[i] == e.semantic;
            if (!ok && wrong++ < 5)
                ADD_FAILURE() << "pixel " << x << "," << y << ": node " << image.instance[i]
                              << " mesh " << image.mesh[i] << " primitive " << image.primitive[i]
                              << " material " << image.material[i] << " semantic "
                              << image.semantic[i] << ", expected node " << e.node << " mesh "
                              << e.mesh << " primitive " << e.primitive << " material "
                              << e.material << " semantic " << e.semantic;
            ++checkedPerNode[e.node + (e.node == 2 ? e.primitive : 0u) * 100u];
        }
    EXPECT_EQ(wrong, 0);
    // Every surface (and the background) was seen on many interior pixels.
    for (std::uint32_t key : {0u, 3u, 2u, 102u, kNoId})
        EXPECT_GT(checkedPerNode[key], 40) << "surface " << key;
}

TEST_F(Aov, DepthRangeNormalsAndUvMatchTheGeometry) {
    const Image image = render(allAovs());
    ASSERT_EQ(image.depth.size(), image.pixelCount());
    ASSERT_EQ(image.range.size(), image.pixelCount());
    ASSERT_EQ(image.worldNormal.size(), image.pixelCount() * 3);
    ASSERT_EQ(image.uv.size(), image.pixelCount() * 2);
    const glm::dmat3 eyeFromWorld(image.camera->viewFromWorld);
    int checked = 0, background = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!interior(image, x, y)) continue;
            const std::size_t i = std::size_t(y) * kSize + x;
            const Hit hit = hitPlane(image, x, y);
            const Expected e = expectedAt(hit.world);
            if (e.node == kNoId) {
                EXPECT_EQ(image.depth[i], FLT_MAX);
                EXPECT_EQ(image.range[i], FLT_MAX);
                EXPECT_EQ(image.worldNormal[i * 3 + 2], 0.0f);
                EXPECT_EQ(image.uv[i * 2], 0.0f);
                ++background;
                continue;
            }
            ++checked;
            const double depth = image.depth[i], range = image.range[i];
            EXPECT_NEAR(depth, -hit.eye.z, 1e-4 * -hit.eye.z) << x << "," << y;
            EXPECT_NEAR(range, glm::length(hit.eye), 1e-4 * glm::length(hit.eye)) << x << "," << y;
            // range = depth |ray| / |z| for the pixel centre's ray from the eye.
            const EyeRay r = eyeRay(image, x, y);
            const glm::dvec3 ray = r.b - r.a;
            EXPECT_NEAR(range, depth * glm::length(ray) / std::abs(ray.z), 2e-5 * range);
            const glm::dvec3 n(image.normal[i * 3], image.normal[i * 3 + 1], image.normal[i * 3 + 2]);
            const glm::dvec3 w(image.worldNormal[i * 3], image.worldNormal[i * 3 + 1],
                               image.worldNormal[i * 3 + 2]);
            EXPECT_NEAR(glm::length(glm::dvec3(0, 0, 1) - w), 0.0, 1e-5) << x << "," << y;
            EXPECT_NEAR(glm::length(glm::transpose(eyeFromWorld) * n - w), 0.0, 1e-6);
            EXPECT_GT(glm::length(n - w), 0.1);  // the camera is turned: the planes differ
            EXPECT_NEAR(image.uv[i * 2], e.uv.x, 1e-4) << x << "," << y;
            EXPECT_NEAR(image.uv[i * 2 + 1], e.uv.y, 1e-4) << x << "," << y;
        }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(background, 100);
}

TEST_F(Aov, OrthographicDepthIsTheDistanceAlongTheViewAxis) {
    const Image image = render(allAovs(true));
    ASSERT_EQ(image.depth.size(), image.pixelCount());
    int checked = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!interior(image, x, y)) continue;
            const Hit hit = hitPlane(image, x, y);
            if (expectedAt(hit.world).node == kNoId) continue;
            const std::size_t i = std::size_t(y) * kSize + x;
            // Parallel rays: depth is -z_eye of the hit, range its distance from the eye point.
            EXPECT_NEAR(image.depth[i], -hit.eye.z, 1e-4 * -hit.eye.z) << x << "," << y;
            EXPECT_NEAR(image.range[i], glm::length(hit.eye), 1e-4 * glm::length(hit.eye));
            EXPECT_EQ(image.instance[i], expectedAt(hit.world).node) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 1000);
}

TEST_F(Aov, MultisamplingBlendsTheColourButNeverTheIds) {
    RenderOptions o = allAovs();
    const Image single = render(o);
    o.msaa = 4;
    const Image msaa = render(o);
    ASSERT_EQ(msaa.instance.size(), msaa.pixelCount());
    int partial = 0, edgeIds = 0;
    for (std::size_t i = 0; i < msaa.pixelCount(); ++i) {
        const std::uint32_t id = msaa.instance[i];
        EXPECT_TRUE(id == kNoId || id == 0 || id == 2 || id == 3) << "pixel " << i << ": " << id;
        // The AOVs come from a single-sampled pass: the same pixels as without MSAA.
        EXPECT_EQ(id, single.instance[i]) << "pixel " << i;
        EXPECT_EQ(msaa.semantic[i], single.semantic[i]) << "pixel " << i;
        EXPECT_EQ(std::memcmp(&msaa.depth[i], &single.depth[i], 4), 0) << "pixel " << i;
        const float a = msaa.rgba[i * 4 + 3];
        if (a > 0.0f && a < 1.0f) {
            ++partial;  // an edge pixel: its colour blends a surface with the background
            edgeIds += id == kNoId || id == 0 || id == 2 || id == 3;
        }
    }
    EXPECT_GT(partial, 20);
    EXPECT_EQ(edgeIds, partial);
}

TEST_F(Aov, PlanesNotAskedForAreNotMade) {
    RenderOptions o = allAovs();
    o.aovs = {};
    o.aovs.semantic = true;
    const Image image = render(o);
    EXPECT_EQ(image.semantic.size(), image.pixelCount());
    EXPECT_TRUE(image.instance.empty() && image.mesh.empty() && image.material.empty());
    EXPECT_TRUE(image.depth.empty() && image.normal.empty() && image.range.empty() &&
                image.worldNormal.empty() && image.uv.empty());
}

TEST(AovLoad, ABadSemanticIdIsRefusedNamingTheNode) {
    for (const json& bad : {json(-1), json(1.5), json("car"), json(4294967295.0)}) {
        GltfBuilder b;
        b.addTriangle();
        b.doc["nodes"][0]["extras"] = {{"semantic_id", bad}};
        auto s = loadScene(b.write(test::testOutputDir(), "bad").string());
        ASSERT_FALSE(s) << bad.dump();
        EXPECT_NE(s.error().describe().find("nodes[0].extras.semantic_id"), std::string::npos)
            << s.error().describe();
    }
}

TEST(AovExr, IdAndDataPlanesSurviveAnExrBitForBit) {
    Image image(3, 2);
    const std::size_t n = image.pixelCount();
    for (std::size_t i = 0; i < n * 4; ++i) image.rgba[i] = float(i) * 0.25f;
    const std::vector<std::uint32_t> ids = {0, 1, 16777217u, 4294967294u, kNoId, 42};
    image.instance = image.mesh = image.primitive = image.material = image.semantic = ids;
    image.primitive[2] = 7;
    image.depth = {1.0f, FLT_MAX, 1e-30f, 3.0f, 0.1f, 5.5f};
    image.range = {1.5f, FLT_MAX, 2e-30f, 3.5f, 0.2f, 6.5f};
    for (std::size_t i = 0; i < n * 3; ++i) image.normal.push_back(float(i) / 17.0f);
    for (std::size_t i = 0; i < n * 3; ++i) image.worldNormal.push_back(-float(i) / 13.0f);
    for (std::size_t i = 0; i < n * 2; ++i) image.uv.push_back(float(i) / 3.0f);
    const auto path = test::testOutputDir() / "aovs.exr";
    ASSERT_TRUE(writeExr(path, image));
    auto back = readExr(path);
    ASSERT_TRUE(back) << back.error().describe();
    // 16777217 and 4294967294 have no float32: only UINT channels give them back.
    EXPECT_EQ(back->instance, ids);
    EXPECT_EQ(back->mesh, ids);
    EXPECT_EQ(back->primitive, image.primitive);
    EXPECT_EQ(back->material, ids);
    EXPECT_EQ(back->semantic, ids);
    EXPECT_EQ(back->depth, image.depth);
    EXPECT_EQ(back->range, image.range);
    EXPECT_EQ(back->normal, image.normal);
    EXPECT_EQ(back->worldNormal, image.worldNormal);
    EXPECT_EQ(back->uv, image.uv);
    // A plane of the wrong size is refused, naming it, and nothing is written.
    image.uv.pop_back();
    const auto refused = writeExr(test::testOutputDir() / "bad.exr", image);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().describe().find("uv plane"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(test::testOutputDir() / "bad.exr"));
}

TEST_F(Aov, TheCommandWritesTheChannelsAndRefusesUnknownNames) {
    const auto dir = test::testOutputDir();
    const auto scene = writeLayout(dir);
    const auto out = dir / "cli.exr";
    const auto r = test::runLantern({"render", scene.string(), "-o", out.string(), "--width",
                                     "64", "--height", "64", "--aov",
                                     "instance,primitive,material,semantic,depth,range,normal,"
                                     "world_normal,uv"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto image = readExr(out);
    ASSERT_TRUE(image) << image.error().describe();
    const std::size_t n = image->pixelCount();
    EXPECT_EQ(image->instance.size(), n);
    EXPECT_EQ(image->mesh.size(), n);
    EXPECT_EQ(image->primitive.size(), n);
    EXPECT_EQ(image->material.size(), n);
    EXPECT_EQ(image->semantic.size(), n);
    EXPECT_EQ(image->range.size(), n);
    EXPECT_EQ(image->worldNormal.size(), n * 3);
    EXPECT_EQ(image->uv.size(), n * 2);
    // The automatic camera sees every node: each id appears.
    for (std::uint32_t node : {0u, 2u, 3u, kNoId})
        EXPECT_NE(std::find(image->instance.begin(), image->instance.end(), node),
                  image->instance.end())
            << node;
    // A sequence (frames collected two in flight) writes the same planes in every frame.
    const auto seq = test::runLantern({"render", scene.string(), "-o", (dir / "f_#.exr").string(),
                                       "--frames", "0-1", "--width", "64", "--height", "64",
                                       "--aov", "instance,semantic"});
    ASSERT_EQ(seq.exitCode, 0) << seq.err;
    for (const char* name : {"f_0.exr", "f_1.exr"}) {
        auto frame = readExr(dir / name);
        ASSERT_TRUE(frame) << name;
        EXPECT_EQ(frame->instance, image->instance) << name;
        EXPECT_EQ(frame->semantic.size(), n) << name;
    }
    const auto bad = test::runLantern({"render", scene.string(), "-o", (dir / "x.exr").string(),
                                       "--aov", "depth,ids"});
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("unknown AOV \"ids\""), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
}

} // namespace
