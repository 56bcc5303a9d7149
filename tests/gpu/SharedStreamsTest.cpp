// Streams that primitives share byte for byte (a file that shares an index or colour accessor
// between meshes) are held once on the device: the upload is smaller, every picture is the one
// the same scene draws with the streams apart, and moving one primitive's vertices moves only
// that primitive (positions and normals are never shared).
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <memory>

namespace {

using namespace lantern;

constexpr int kMeshes = 6;

// kMeshes spheres in a row, each its own mesh with its own positions and the same index list
// and colours; `apart`: each mesh has a vertex no triangle uses, of a colour of its own, and
// its list ends with a degenerate triangle of its own (no fragment), so that no two colour
// streams and no two lists are equal.
std::shared_ptr<Scene> row(bool apart) {
    test::SimpleScene simple;
    simple.primitive = makeSphere(0.3, 24, 16);
    simple.primitive.colors.assign(simple.primitive.positions.size(), glm::vec4(0.9f, 0.6f, 0.3f, 1.0f));
    simple.material.front.specular = glm::dvec3(0.5);
    simple.material.front.shininess = 40.0;
    simple.lights.push_back({Light{}, glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 3.0))});
    auto scene = std::make_shared<Scene>(simple.build());
    const Primitive sphere = scene->meshes[0].primitives[0];
    scene->meshes.clear();
    scene->nodes.erase(scene->nodes.begin());  // the object; the light is node 0 now
    scene->roots[0].nodes = {0};
    for (int m = 0; m < kMeshes; ++m) {
        Primitive p = sphere;
        for (glm::vec3& v : p.positions) v.x += 0.7f * float(m) - 1.75f;
        if (apart) {
            p.positions.push_back(glm::vec3(0.0f));
            p.normals.push_back(glm::vec3(0.0f, 0.0f, 1.0f));
            p.colors.push_back(glm::vec4(0.1f * float(m), 0.0f, 0.0f, 1.0f));
            if (!p.texcoords.empty()) p.texcoords.push_back(glm::vec2(0.0f));
            p.indices.insert(p.indices.end(), 3, std::uint32_t(m));
        }
        scene->meshes.push_back(Mesh{"sphere " + std::to_string(m), {p}, {}});
        Node n;
        n.name = "sphere " + std::to_string(m);
        n.mesh = m;
        scene->nodes.push_back(n);
        scene->roots[0].nodes.push_back(int(scene->nodes.size()) - 1);
    }
    return scene;
}

class SharedStreams : public test::GpuTest {
protected:
    static RenderOptions options(ShadingMode shading) {
        RenderOptions o;
        o.width = 96;
        o.height = 48;
        o.shading = shading;
        o.background = glm::vec4(0.0f);
        o.camera.lookAt = LookAt{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}};
        o.camera.projection = Projection::makeOrtho(-2.5, 2.5, -1.25, 1.25, 0.1, 100);
        return o;
    }
};

TEST_F(SharedStreams, AreHeldOnceAndDrawnAsIfApart) {
    const auto shared = row(false), apart = row(true);
    for (const auto& scene : {shared, apart}) {
        const auto valid = scene->validate();
        ASSERT_TRUE(valid) << valid.error().describe();
    }
    const std::size_t indexBytes = shared->meshes[0].primitives[0].indices.size() * 4;
    const std::size_t colorBytes = shared->meshes[0].primitives[0].colors.size() * 16;

    const std::uint64_t before = renderer().deviceMemoryBytes();
    auto preparedApart = renderer().prepare(apart);
    ASSERT_TRUE(preparedApart) << preparedApart.error().describe();
    const std::uint64_t apartBytes = renderer().deviceMemoryBytes() - before;
    auto preparedShared = renderer().prepare(shared);
    ASSERT_TRUE(preparedShared) << preparedShared.error().describe();
    const std::uint64_t sharedBytes = renderer().deviceMemoryBytes() - before - apartBytes;
    // Apart, each mesh holds its list and its colours; shared, one of each serves all.
    EXPECT_GE(apartBytes, sharedBytes + (kMeshes - 1) * (indexBytes + colorBytes))
        << "shared " << sharedBytes << " B, apart " << apartBytes << " B";

    for (ShadingMode shading : {ShadingMode::Gouraud, ShadingMode::Phong, ShadingMode::Flat}) {
        SCOPED_TRACE(int(shading));
        auto a = renderer().render(*preparedApart, options(shading), 0.0);
        auto s = renderer().render(*preparedShared, options(shading), 0.0);
        ASSERT_TRUE(a && s);
        EXPECT_GT(test::countCovered(*s), s->pixelCount() / 8);
        EXPECT_EQ(test::maxAbsDifference(*a, *s), 0.0f) << "the same picture";
    }

    // Moving the first sphere's vertices off the picture leaves the others where they were.
    auto full = renderer().render(*preparedShared, options(ShadingMode::Phong), 0.0);
    ASSERT_TRUE(full);
    for (glm::vec3& v : shared->meshes[0].primitives[0].positions) v.y += 100.0f;
    ASSERT_TRUE(renderer().updateVertices(*preparedShared, 0, 0));
    auto moved = renderer().render(*preparedShared, options(ShadingMode::Phong), 0.0);
    ASSERT_TRUE(moved);
    const std::size_t coveredFull = test::countCovered(*full), coveredMoved = test::countCovered(*moved);
    EXPECT_LT(coveredMoved, coveredFull) << "the first sphere left";
    EXPECT_GT(coveredMoved, coveredFull * (kMeshes - 2) / kMeshes) << "the other spheres stayed";
}

} // namespace
