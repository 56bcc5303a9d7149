// Instanced draws (shaders/include/instance.glsl, render/DrawLists.cpp): the nodes that place
// one primitive with the same material and winding (EXT_mesh_gpu_instancing's instances, or
// any nodes that share a mesh) are drawn by one draw with an instance each. These tests hold
// that the picture is the one the separate draws make, bit for bit, in every shading mode and
// for every transform a node may have (scaled, sheared, mirrored); that only the draws that
// may be merged are (not blended, flat, deformed, id-reading or overlay frames); and that a
// scene without shared meshes has the pipeline variants it had before.
#include "GltfTestBuilder.h"
#include "LightingCompare.h"

#include "gpu/SceneBuffers.h"
#include "render/DrawLists.h"
#include "render/FrameRender.h"

#include <gtest/gtest.h>
#include <lantern/Io.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstring>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

// Every instanced draw of `list` split back into one draw per instance with the same
// pipeline less SC_INSTANCED: what the frame would draw without instancing.
void splitInstances(gpu::DrawList& list) {
    for (gpu::ViewCommands& v : list.views) {
        std::vector<gpu::DrawCommand> split;
        for (const gpu::DrawCommand& d : v.draws) {
            if (d.pipeline.constants[LANTERN_SC_INSTANCED] == 0) {
                split.push_back(d);
                continue;
            }
            for (std::uint32_t k = 0; k < d.instanceCount; ++k) {
                gpu::DrawCommand one = d;
                one.pipeline.constants[LANTERN_SC_INSTANCED] = 0;
                one.firstInstance = 0;
                one.instanceCount = 1;
                const gpu::InstanceData& i = list.instances[d.firstInstance + k];
                std::copy(std::begin(i.viewFromModel), std::end(i.viewFromModel), one.block.viewFromModel);
                std::copy(std::begin(i.normalMatrix), std::end(i.normalMatrix), one.block.normalMatrix);
                split.push_back(one);
            }
        }
        v.draws = std::move(split);
    }
    list.instances.clear();
}

std::size_t instancedDraws(const gpu::DrawList& list) {
    std::size_t n = 0;
    for (const gpu::ViewCommands& v : list.views)
        for (const gpu::DrawCommand& d : v.draws) n += d.pipeline.constants[LANTERN_SC_INSTANCED];
    return n;
}

class Instancing : public GpuTest {
protected:
    // A sphere (node 0) and a cube, then `copies` more nodes placing the sphere's mesh: moved,
    // scaled unevenly, sheared, and one mirrored (its triangles wind the other way).
    static Scene spheres(int copies, const Material& material = plastic()) {
        LitScene s;
        s.objects.push_back({makeSphere(0.35, 16, 8), material, test::translation({-1.2, 0.8, 0.0})});
        s.objects.push_back({makeCube(0.5), plastic(), test::translation({1.2, -0.9, -0.5})});
        Light point = test::makeLight(LightType::Point);
        point.attenuation = {1.0, 0.05, 0.01};
        s.lights.push_back({point, test::translation({1.0, 1.5, 3.0})});
        s.lookAt = LookAt{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
        Scene scene = s.build();
        for (int i = 0; i < copies; ++i) {
            glm::dmat4 m = test::translation({-1.2 + 0.8 * (i % 4), -0.4 + 0.8 * (i / 4), -0.3 * i});
            if (i == 1) m = glm::scale(m, glm::dvec3(1.6, 0.7, 1.0));
            if (i == 2) m[1][0] = 0.4;  // shear x by y
            if (i == 3) m = glm::scale(m, glm::dvec3(-1.0, 1.0, 1.0));
            Node n;
            n.name = "copy " + std::to_string(i);
            n.mesh = 0;
            n.matrix = m;
            scene.roots[0].nodes.push_back(int(scene.nodes.size()));
            scene.nodes.push_back(n);
        }
        return scene;
    }

    static Material plastic() {
        return test::phongMaterial({0.2, 0.1, 0.05}, {0.8, 0.5, 0.3, 1.0}, {0.9, 0.9, 0.9}, 30.0);
    }

    static gpu::DrawList drawList(const Scene& scene, const RenderOptions& o) {
        auto f = frame::buildFrame(scene, o, 0.0);
        EXPECT_TRUE(f) << f.error().describe();
        return render::buildDrawList(scene, *f, o);
    }

    // The frame as drawn (instanced where it may be), or with every instance drawn alone.
    Image render(const Scene& scene, const RenderOptions& o, bool separate, std::size_t* draws = nullptr) {
        m_scene = scene;
        auto buffers = device().upload(std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &m_scene));
        EXPECT_TRUE(buffers) << buffers.error().describe();
        if (!buffers) return {};
        render::FrameEdits edits;
        if (separate) edits.list = splitInstances;
        FrameStats stats;
        auto f = render::renderFrame(device(), *buffers, m_scene, o, 0.0, stats, edits);
        EXPECT_TRUE(f) << f.error().describe();
        if (!f) return {};
        if (draws) *draws = f->readback.draws;
        return std::move(f->readback.image);
    }

    Scene m_scene;
};

TEST_F(Instancing, SharedMeshNodesAreOneDrawAndThePictureIsTheSeparateDraws) {
    const Scene scene = spheres(7);
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud}) {
        SCOPED_TRACE(mode == ShadingMode::Phong ? "phong" : "gouraud");
        const RenderOptions o = test::optionsFor(96, 80, mode);
        // The sphere at node 0 and six copies in one draw; the mirrored copy (clockwise front
        // faces) and the cube alone.
        const gpu::DrawList list = drawList(scene, o);
        ASSERT_EQ(list.views.size(), 1u);
        EXPECT_EQ(list.views[0].draws.size(), 3u);
        EXPECT_EQ(instancedDraws(list), 1u);
        EXPECT_EQ(list.instances.size(), 7u);
        std::size_t together = 0, apart = 0;
        const Image merged = render(scene, o, false, &together);
        const Image separate = render(scene, o, true, &apart);
        EXPECT_EQ(together, 3u);
        EXPECT_EQ(apart, 9u);
        RenderOptions off = o;  // --no-instancing
        off.instancing = false;
        std::size_t unmerged = 0;
        const Image plain = render(scene, off, false, &unmerged);
        EXPECT_EQ(unmerged, 9u);
        ASSERT_EQ(plain.rgba.size(), merged.rgba.size());
        EXPECT_EQ(std::memcmp(merged.rgba.data(), plain.rgba.data(), merged.rgba.size() * sizeof(float)), 0)
            << "--no-instancing changed the picture";
        ASSERT_EQ(merged.rgba.size(), separate.rgba.size());
        EXPECT_EQ(std::memcmp(merged.rgba.data(), separate.rgba.data(), merged.rgba.size() * sizeof(float)), 0)
            << "the instanced draw changed the picture";
        // Every copy is drawn: nine objects' worth of lit pixels, not three.
        std::size_t lit = 0;
        for (std::size_t i = 3; i < merged.rgba.size(); i += 4) lit += merged.rgba[i] > 0.0f;
        EXPECT_GT(lit, 1000u);
    }
}

TEST_F(Instancing, OnlyDrawsThatMayBeMergedAre) {
    const Scene scene = spheres(7);
    // Flat shading lights each draw's triangles in its own pass: one draw per node.
    EXPECT_EQ(instancedDraws(drawList(scene, test::optionsFor(64, 64, ShadingMode::Flat))), 0u);
    // Frames that read ids back (probe, id planes, Cryptomatte) or draw overlays keep a draw
    // per node, so each id names its node and each overlay follows its transform.
    RenderOptions ids = test::optionsFor(64, 64, ShadingMode::Phong);
    ids.aovs.instance = true;
    EXPECT_EQ(drawList(scene, ids).views[0].draws.size(), 9u);
    RenderOptions depth = test::optionsFor(64, 64, ShadingMode::Phong);
    depth.aovs.depth = true;  // no id: instanced
    EXPECT_EQ(instancedDraws(drawList(scene, depth)), 1u);
    RenderOptions wire = test::optionsFor(64, 64, ShadingMode::Phong);
    wire.wireframe = true;
    EXPECT_EQ(drawList(scene, wire).views[0].draws.size(), 9u);
    // Blended draws keep their own far-to-near places.
    Material glass = plastic();
    glass.front.diffuse.a = 0.5;
    glass.alphaMode = AlphaMode::Blend;
    const gpu::DrawList blended = drawList(spheres(7, glass), test::optionsFor(64, 64, ShadingMode::Phong));
    EXPECT_EQ(instancedDraws(blended), 0u);
    EXPECT_EQ(blended.views[0].draws.size(), 9u);
}

TEST_F(Instancing, AScenePaysForItOnlyWhereItSharesAMesh) {
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto variants = [&](const Scene& s) {
        auto report = render::explain(s, o, 0.0);
        EXPECT_TRUE(report) << report.error().describe();
        std::string all;
        for (const std::string& v : report->variants) all += v + "\n";
        return all;
    };
    const std::string alone = variants(spheres(0)), shared = variants(spheres(7));
    EXPECT_EQ(alone.find("instanced"), std::string::npos) << alone;
    EXPECT_NE(shared.find("instanced"), std::string::npos) << shared;
    const gpu::DrawList list = drawList(spheres(0), o);
    EXPECT_TRUE(list.instances.empty());
    for (const gpu::DrawCommand& d : list.views[0].draws) EXPECT_EQ(d.instanceCount, 1u);
}

// EXT_mesh_gpu_instancing, as gltfpack -mi writes it (the extension required): the node's
// instances are one draw, and the picture is the one --no-instancing draws.
TEST_F(Instancing, GpuInstancingExtensionIsOneDraw) {
    test::GltfBuilder b;
    b.addTriangle();
    const int t = b.addFloats({-1.5, 0, 0, 0, 0, 0, 1.5, 0, 0, 0, 1.5, 0}, "VEC3");
    b.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"TRANSLATION", t}};
    b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    b.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    auto scene = loadScene(b.write(test::testOutputDir(), "gpu-instances").string());
    ASSERT_TRUE(scene) << scene.error().describe();
    const RenderOptions o = test::optionsFor(96, 80, ShadingMode::Phong);
    const gpu::DrawList list = drawList(*scene, o);
    ASSERT_EQ(list.views[0].draws.size(), 1u);
    EXPECT_EQ(list.views[0].draws[0].instanceCount, 4u);
    RenderOptions off = o;
    off.instancing = false;
    std::size_t together = 0, apart = 0;
    const Image merged = render(*scene, o, false, &together), plain = render(*scene, off, false, &apart);
    EXPECT_EQ(together, 1u);
    EXPECT_EQ(apart, 4u);
    ASSERT_EQ(merged.rgba.size(), plain.rgba.size());
    EXPECT_EQ(std::memcmp(merged.rgba.data(), plain.rgba.data(), merged.rgba.size() * sizeof(float)), 0);
    std::size_t lit = 0;
    for (std::size_t i = 3; i < merged.rgba.size(); i += 4) lit += merged.rgba[i] > 0.0f;
    EXPECT_GT(lit, 200u);
}

// Two views: each has its own instanced draw with its own instances (view-relative transforms),
// and the picture is still the separate draws'.
TEST_F(Instancing, EveryViewHasItsOwnInstances) {
    Scene scene = spheres(5);
    RenderOptions o = test::optionsFor(128, 64, ShadingMode::Phong);
    o.views = {View{0, 0, 64, 64, o.camera}, View{64, 0, 64, 64, o.camera}};
    o.views[1].camera.lookAt = LookAt{{3, 1, 4}, {0, 0, 0}, {0, 1, 0}};
    const gpu::DrawList list = drawList(scene, o);
    ASSERT_EQ(list.views.size(), 2u);
    EXPECT_EQ(instancedDraws(list), 2u);
    EXPECT_EQ(list.instances.size(), 10u);
    const Image merged = render(scene, o, false), separate = render(scene, o, true);
    ASSERT_EQ(merged.rgba.size(), separate.rgba.size());
    EXPECT_EQ(std::memcmp(merged.rgba.data(), separate.rgba.data(), merged.rgba.size() * sizeof(float)), 0);
}

} // namespace
