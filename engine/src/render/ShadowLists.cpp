// The frame's shadow maps packed for the GPU (frame/Shadows.cpp plans them, gpu/Shadows.cpp
// and gpu/Recorder.cpp draw them): each pass's frame block, the casters each pass draws, and
// what the lighting reads (shaders/include/shadows.glsl).
#include "render/DrawLists.h"

#include <glm/matrix.hpp>

#include <array>
#include <map>
#include <utility>

namespace lantern::render {
namespace {

static_assert(LANTERN_MAX_CASCADES == kMaxShadowCascades);

glm::dmat4 toDmat4(const float (&m)[16]) {
    glm::dmat4 r;
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) r[c][k] = double(m[c * 4 + k]);
    return r;
}

// The corners of a primitive's bounds in its model space, once per primitive and frame.
class CornerCache {
public:
    explicit CornerCache(const Scene& scene) : m_scene(scene) {}
    const std::array<glm::dvec3, 8>& corners(std::uint32_t mesh, std::uint32_t primitive) {
        auto [it, added] = m_corners.try_emplace({mesh, primitive});
        if (added) {
            Bounds b;
            for (const glm::vec3& p : m_scene.meshes[mesh].primitives[primitive].positions)
                b.extend(glm::dvec3(p));
            for (int k = 0; k < 8; ++k)
                it->second[std::size_t(k)] = glm::dvec3(k & 1 ? b.max.x : b.min.x,
                                                        k & 2 ? b.max.y : b.min.y,
                                                        k & 4 ? b.max.z : b.min.z);
        }
        return it->second;
    }

private:
    const Scene& m_scene;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::array<glm::dvec3, 8>> m_corners;
};

// Whether a box (corners through clipFromModel) lies wholly beyond one side of the map's
// square: then none of its triangles writes a texel of the map. Conservative by a hundred
// thousandth, so float rounding never culls a caster that reaches the map.
bool outsideMap(const glm::dmat4& clipFromModel, const std::array<glm::dvec3, 8>& corners) {
    int out[4] = {0, 0, 0, 0};
    for (const glm::dvec3& p : corners) {
        const glm::dvec4 c = clipFromModel * glm::dvec4(p, 1.0);
        const double slack = 1e-5 * (std::abs(c.x) + std::abs(c.y) + std::abs(c.w));
        out[0] += c.x > c.w + slack;
        out[1] += -c.x > c.w + slack;
        out[2] += c.y > c.w + slack;
        out[3] += -c.y > c.w + slack;
    }
    return out[0] == 8 || out[1] == 8 || out[2] == 8 || out[3] == 8;
}

// An alpha-masked draw that its mask removes everywhere (each side's alpha under the cutoff,
// with no texture or vertex colour to raise it): the scene pass draws none of it, so it casts
// nothing, as in the reference.
bool maskedAway(const frame::Frame& frame, const frame::Draw& d) {
    const Material& m = frame.materials[d.material];
    if (m.alphaMode != AlphaMode::Mask || d.texture >= 0 || d.hasColors) return false;
    const bool backToo = m.back.has_value() && (frame::twoSidedLighting(frame.lighting, m));
    return m.front.diffuse.a < m.alphaCutoff && (!backToo || m.back->diffuse.a < m.alphaCutoff);
}

// The first view's draws that cast (opaque triangles) and, with culling, can reach the map
// whose clip space from the first view's eye space is `clipFromView`: an instanced draw when
// any of its instances can. Deformed draws (their bounds move with the pose) always cast.
std::vector<std::uint32_t> passDraws(const frame::Frame& frame, const gpu::DrawList& list,
                                     const glm::dmat4& clipFromView, bool culling,
                                     CornerCache& cache) {
    std::vector<std::uint32_t> out;
    const std::vector<gpu::DrawCommand>& draws = list.views[0].draws;
    for (std::size_t i = 0; i < draws.size(); ++i) {
        const gpu::DrawCommand& d = draws[i];
        if (d.pipeline.blend || d.pipeline.topology != Topology::Triangles) continue;
        const frame::Draw* fd = frame.draw(d.block.drawIndex);
        if (fd && maskedAway(frame, *fd)) continue;
        bool reaches = !culling || !fd || fd->deformed;
        if (!reaches) {
            const auto& corners = cache.corners(fd->mesh, fd->primitive);
            if (d.pipeline.constants[LANTERN_SC_INSTANCED] == 0) {
                reaches = !outsideMap(clipFromView * toDmat4(d.block.viewFromModel), corners);
            } else {
                for (std::uint32_t k = 0; k < d.instanceCount && !reaches; ++k)
                    reaches = !outsideMap(
                        clipFromView * toDmat4(list.instances[d.firstInstance + k].viewFromModel),
                        corners);
            }
        }
        if (reaches) out.push_back(std::uint32_t(i));
    }
    return out;
}

} // namespace

void packShadows(const Scene& scene, const frame::Frame& frame, const RenderOptions& o,
                 gpu::DrawList& list) {
    const frame::Shadows& sh = frame.shadows;
    if (!sh.any()) return;
    gpu::ShadowCommands& c = list.shadows;
    c.resolution = std::uint32_t(o.shadows.resolution);
    c.slopeBias = -float(o.shadows.slopeBias);
    const glm::dmat4 firstWorldFromView = glm::inverse(frame.views[0].camera.viewFromWorld);
    CornerCache cache(scene);
    for (const frame::ShadowMap& m : sh.maps) {
        gpu::FrameBlock b = list.views[0].frame;
        const glm::dmat4 clipFromView = m.clipFromWorld * firstWorldFromView;
        b.clipFromView = toMat4(clipFromView);
        c.passes.push_back(b);
        c.passDraws.push_back(passDraws(frame, list, clipFromView, o.culling, cache));
    }
    const int kernel = o.shadows.filter == ShadowFilter::Hardware ? 1 : o.shadows.kernel;
    for (std::size_t vi = 0; vi < frame.views.size(); ++vi) {
        const glm::dmat4 worldFromView = glm::inverse(frame.views[vi].camera.viewFromWorld);
        for (const frame::ShadowMap& m : sh.maps) {
            gpu::ShadowData d;
            d.clipFromView = toMat4(m.clipFromWorld * worldFromView);
            d.params = {float(m.texel), m.perspective ? 1.0f : 0.0f, float(m.margin), float(m.lightSize)};
            d.depth = {float(m.depthScale), float(m.depthOffset), 0.0f, 0.0f};
            c.lookups.push_back(d);
        }
        gpu::ViewCommands& v = list.views[vi];
        v.frame.shadowMaps = std::uint32_t(sh.maps.size());
        v.frame.shadowParams = {1.0f / float(o.shadows.resolution), float(kernel),
                                float(o.shadows.normalOffset), 0.0f};
        for (std::size_t li = 0; li < v.lights.size() && li < sh.firstMap.size(); ++li) {
            const int first = sh.firstMap[li];
            if (first < 0) continue;
            v.lights[li].info.z = std::uint32_t(first) + 1u;
            v.lights[li].info.w = std::uint32_t(sh.mapCount[li]);
        }
    }
}

} // namespace lantern::render
