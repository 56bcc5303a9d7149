// Files written by the compressors people use: gltfpack (EXT_meshopt_compression with
// KHR_mesh_quantization, Debian package gltfpack) and draco_transcoder (KHR_draco_mesh_compression,
// Debian package draco), run on the sample models; each output must load with the triangles of
// the original in world space. Skipped, saying why, when a tool or the samples are absent.
#include "GltfEncode.h"
#include "GltfTestSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace {

using namespace lantern;
using lantern::test::loadCapturing;
using lantern::test::TestMesh;

/// Every drawn triangle of the default scene, in world space, positions only (the tools change
/// normal and uv encodings, and gltfpack's uv dequantization needs KHR_texture_transform).
TestMesh worldTriangles(const Scene& scene) {
    TestMesh all;
    const Pose pose = evaluatePose(scene, -1, 0.0);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (!pose.visible[n] || scene.nodes[n].mesh < 0) continue;
        for (const Primitive& p : scene.meshes[std::size_t(scene.nodes[n].mesh)].primitives) {
            TestMesh m = test::meshOf(p, pose.worldFromNode[n]);
            const auto base = std::uint32_t(all.vertexCount());
            all.positions.insert(all.positions.end(), m.positions.begin(), m.positions.end());
            for (std::uint32_t i : m.indices)
                all.indices.push_back(base + i);
        }
    }
    all.normals.assign(all.positions.size(), 0.0f);
    all.texcoords.assign(all.vertexCount() * 2, 0.0f);
    return all;
}

double extent(const TestMesh& m) {
    float lo = 1e30f, hi = -1e30f;
    for (float v : m.positions) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    return double(hi - lo);
}

struct ToolCase {
    const char* tool;
    std::vector<std::string> options;
    int positionBits; ///< the tool's default position quantization
};

TEST(GltfCompressionTools, CompressorOutputLoadsWithTheOriginalTriangles) {
    const auto samples = test::sharedDir() / "assets" / "gltf-samples";
    if (!std::filesystem::is_directory(samples))
        GTEST_SKIP() << "the sample models are not there (" << samples << ")";
    const ToolCase tools[] = {{"gltfpack", {"-c"}, 14},
                              {"gltfpack", {"-cc"}, 14},
                              {"draco_transcoder", {}, 11}};
    const char* models[] = {"Duck/glTF-Binary/Duck.glb", "BoxInterleaved/glTF-Binary/BoxInterleaved.glb"};
    int ran = 0;
    for (const ToolCase& t : tools) {
        const std::string tool = test::findOnPath(t.tool);
        if (tool.empty()) continue;
        for (const char* model : models) {
            SCOPED_TRACE(std::string(t.tool) + " " + (t.options.empty() ? "" : t.options[0]) + " " + model);
            const auto output = test::testOutputDir() / (std::string(t.tool) + std::to_string(ran) + ".glb");
            std::vector<std::string> args = {tool, "-i", (samples / model).string(), "-o", output.string()};
            args.insert(args.end(), t.options.begin(), t.options.end());
            const auto r = test::runProcess(args, {}, 120.0);
            ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
            auto original = loadCapturing(samples / model);
            auto compressed = loadCapturing(output);
            ASSERT_TRUE(original.scene) << original.scene.error().describe();
            ASSERT_TRUE(compressed.scene) << compressed.scene.error().describe();
            const TestMesh expected = worldTriangles(*original.scene);
            // Half a quantization step per axis of the tool's grid over the largest extent.
            const double step = extent(expected) / ((1 << t.positionBits) - 1);
            EXPECT_TRUE(test::sameGeometry(worldTriangles(*compressed.scene), expected,
                                           {std::sqrt(3.0) * step + 1e-5, 1e30, 1e30}));
            ++ran;
        }
    }
    if (ran == 0)
        GTEST_SKIP() << "neither gltfpack nor draco_transcoder is installed (Debian packages "
                        "gltfpack, draco)";
}

} // namespace
