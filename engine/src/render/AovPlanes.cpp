// The id planes and world normals of a frame, from its draw ids (render/AovPlanes.h).
#include "render/AovPlanes.h"

#include <glm/mat3x3.hpp>
#include <glm/geometric.hpp>

namespace lantern::render {
namespace {

// What one draw index stands for.
struct DrawIds {
    std::uint32_t node = kNoId, mesh = kNoId, primitive = kNoId, material = kNoId;
    std::uint32_t semantic = 0;
    std::size_t view = 0;
};

std::vector<DrawIds> drawTable(const Scene& scene, const frame::Frame& frame) {
    const std::vector<std::uint32_t> semantics = nodeSemantics(scene);
    std::vector<DrawIds> table(frame.drawCount());
    for (std::size_t vi = 0; vi < frame.views.size(); ++vi)
        for (const frame::Draw& d : frame.views[vi].draws) {
            if (d.index >= table.size()) continue;
            // Frame materials are the scene's, then the default: its index is the count.
            table[d.index] = {d.node, d.mesh, d.primitive, d.material, semantics[d.node], vi};
        }
    return table;
}

// World from eye for normals: n_eye = M^-T n_world for M = viewFromWorld's 3x3, so
// n_world is M^T n_eye, renormalised (exact for the rigid cameras Lantern makes).
std::vector<glm::dmat3> worldFromEyeNormals(const frame::Frame& frame) {
    std::vector<glm::dmat3> out;
    for (const frame::View& v : frame.views)
        out.push_back(glm::transpose(glm::dmat3(v.camera.viewFromWorld)));
    return out;
}

// The world-space normal of each pixel from its eye normal and its draw's view (0: nothing).
void worldNormals(const std::vector<DrawIds>& table, const std::vector<glm::dmat3>& worldFromEye,
                  gpu::FrameReadback& r) {
    Image& img = r.image;
    const std::size_t pixels = img.pixelCount();
    img.worldNormal.assign(pixels * 3, 0.0f);
    if (img.normal.size() != pixels * 3) return;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint32_t id = r.ids[i * 2];
        if (id == 0 || id > table.size()) continue;  // the background
        const float* n = img.normal.data() + i * 3;
        const glm::dvec3 w = worldFromEye[table[id - 1].view] * glm::dvec3(n[0], n[1], n[2]);
        const double len = glm::length(w);
        if (!(len > 0.0)) continue;
        for (int c = 0; c < 3; ++c) img.worldNormal[i * 3 + std::size_t(c)] = float(w[c] / len);
    }
}

// One id plane: per pixel, the column's value for the pixel's draw id (column[0] is the
// background's). Ids beyond the table cannot come from the GPU; they read as the background.
void fillIds(const std::vector<std::uint32_t>& ids, const std::vector<std::uint32_t>& column,
             std::vector<std::uint32_t>& plane) {
    const std::size_t pixels = ids.size() / 2;
    plane.resize(pixels);
    const std::uint32_t last = std::uint32_t(column.size() - 1);
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint32_t id = ids[i * 2];
        plane[i] = column[id <= last ? id : 0u];
    }
}

} // namespace

std::vector<std::uint32_t> nodeSemantics(const Scene& scene) {
    const std::size_t n = scene.nodes.size();
    std::vector<int> parent(n, -1);
    for (std::size_t i = 0; i < n; ++i)
        for (int c : scene.nodes[i].children)
            if (c >= 0 && std::size_t(c) < n) parent[std::size_t(c)] = int(i);
    std::vector<std::uint32_t> out(n, 0);
    std::vector<bool> done(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        // Up to the first node that sets one (or is resolved), then back down the chain.
        std::vector<std::size_t> chain;
        int at = int(i);
        while (at >= 0 && !done[std::size_t(at)] && !scene.nodes[std::size_t(at)].semantic &&
               chain.size() <= n) {
            chain.push_back(std::size_t(at));
            at = parent[std::size_t(at)];
        }
        std::uint32_t value = 0;
        if (at >= 0) {
            const Node& top = scene.nodes[std::size_t(at)];
            value = done[std::size_t(at)] ? out[std::size_t(at)] : *top.semantic;
            out[std::size_t(at)] = value;
            done[std::size_t(at)] = true;
        }
        for (std::size_t c : chain) out[c] = value, done[c] = true;
    }
    return out;
}

void resolveAovPlanes(const Scene& scene, const frame::Frame& frame, const AovSet& aovs,
                      gpu::FrameReadback& r) {
    Image& img = r.image;
    const std::size_t pixels = img.pixelCount();
    if (!aovs.anyId() || r.ids.size() != pixels * 2) return;
    const std::vector<DrawIds> table = drawTable(scene, frame);
    // The table as one column per plane, the background first.
    auto column = [&](std::uint32_t background, std::uint32_t DrawIds::*field) {
        std::vector<std::uint32_t> c{background};
        for (const DrawIds& d : table) c.push_back(d.*field);
        return c;
    };
    if (aovs.instance) fillIds(r.ids, column(kNoId, &DrawIds::node), img.instance);
    if (aovs.primitive) fillIds(r.ids, column(kNoId, &DrawIds::mesh), img.mesh);
    if (aovs.primitive) fillIds(r.ids, column(kNoId, &DrawIds::primitive), img.primitive);
    if (aovs.material) fillIds(r.ids, column(kNoId, &DrawIds::material), img.material);
    if (aovs.semantic) fillIds(r.ids, column(0, &DrawIds::semantic), img.semantic);
    if (aovs.worldNormal) worldNormals(table, worldFromEyeNormals(frame), r);
    if (!aovs.normal) img.normal = {};
}

} // namespace lantern::render
