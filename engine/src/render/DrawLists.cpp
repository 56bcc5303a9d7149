// frame::Frame -> gpu::DrawList: packing in the shaders' layouts and the draws' variants.
#include "render/DrawLists.h"

#include "render/Variants.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <iterator>
#include <map>
#include <tuple>

namespace lantern::render {
namespace {

gpu::Vec4 vec4(const glm::dvec3& v, double w = 0.0) {
    return {float(v.x), float(v.y), float(v.z), float(w)};
}
gpu::Vec4 vec4(const glm::dvec4& v) { return {float(v.x), float(v.y), float(v.z), float(v.w)}; }

std::uint32_t lightType(LightType t) {
    switch (t) {
    case LightType::Directional: return LANTERN_LIGHT_DIRECTIONAL;
    case LightType::Point: return LANTERN_LIGHT_POINT;
    case LightType::Spot: return LANTERN_LIGHT_SPOT;
    }
    return LANTERN_LIGHT_POINT;
}

gpu::MaterialSideData packSide(const MaterialSide& s) {
    gpu::MaterialSideData d;
    d.ambient = vec4(s.ambient);
    d.diffuse = vec4(s.diffuse);
    d.specular = vec4(s.specular, s.shininess);
    d.emission = vec4(s.emission);
    return d;
}

gpu::DrawBlock packDraw(const frame::Draw& d) {
    gpu::DrawBlock b;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) b.viewFromModel[c * 4 + r] = float(d.viewFromModel[c][r]);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) b.normalMatrix[c * 4 + r] = float(d.normalMatrix[c][r]);
    b.materialIndex = d.material;
    b.drawIndex = d.index;
    b.flags = d.hasColors ? gpu::kDrawFlagVertexColor : 0u;
    return b;
}

// What the draws of one instanced draw share besides their pipeline.
auto instanceKey(const gpu::DrawCommand& c) {
    return std::tuple{c.mesh, c.primitive, c.textureSet, c.cullBack, c.frontClockwise,
                      c.block.materialIndex, c.block.flags};
}

gpu::ViewCommands packView(const frame::Frame& frame, std::size_t vi, const RenderOptions& o) {
    const frame::View& v = frame.views[vi];
    gpu::ViewCommands out;
    out.x = v.x, out.y = v.y, out.width = v.width, out.height = v.height;
    out.frame.clipFromView = toMat4(v.camera.clipFromView);
    out.frame.globalAmbient = vec4(frame.lighting.model.globalAmbient);
    out.frame.viewIndex = std::uint32_t(vi);
    out.frame.pointSize = float(o.pointSize);
    for (const frame::EyeLight& l : v.lights) out.lights.push_back(packLight(l));
    out.frame.lightCount = std::uint32_t(out.lights.size());
    for (const frame::Draw& d : v.draws) {
        gpu::DrawCommand c;
        c.pipeline = pipelineKey(frame, d, o);
        c.mesh = d.mesh;
        c.primitive = d.primitive;
        c.textureSet = (d.texture >= 0 || d.features.maps != 0) ? int(d.material) : -1;
        c.cullBack = d.cullBack;
        c.frontClockwise = d.mirrored;
        c.block = packDraw(d);
        out.draws.push_back(c);
    }
    // Opaque draws grouped by variant (fewer pipeline binds), then by what an instanced draw
    // shares (so the draws one can cover are neighbours, and merging them changes no order),
    // order otherwise kept (stable, so frames are deterministic); the frame keeps blended draws
    // last, far to near.
    const auto firstBlended = std::stable_partition(
        out.draws.begin(), out.draws.end(), [](const gpu::DrawCommand& c) { return !c.pipeline.blend; });
    std::stable_sort(out.draws.begin(), firstBlended,
                     [](const gpu::DrawCommand& a, const gpu::DrawCommand& b) {
                         if (a.pipeline.program != b.pipeline.program)
                             return a.pipeline.program < b.pipeline.program;
                         if (a.pipeline.topology != b.pipeline.topology)
                             return a.pipeline.topology < b.pipeline.topology;
                         if (a.pipeline.constants != b.pipeline.constants)
                             return a.pipeline.constants < b.pipeline.constants;
                         return instanceKey(a) < instanceKey(b);
                     });
    return out;
}

// Whether a draw may be one instance of an instanced draw: opaque (blended draws keep their
// own far-to-near places), undeformed (each pose has its own streams) and not flat (flat
// shading's per-triangle pass lights each draw's triangles on their own: gpu/FlatLight.h).
bool instanceable(const frame::Frame& frame, const gpu::DrawCommand& c) {
    if (c.pipeline.blend || c.pipeline.program == frame::Program::Flat) return false;
    const frame::Draw* d = frame.draw(c.block.drawIndex);
    return d && !d->deformed;
}

gpu::InstanceData instanceData(const gpu::DrawBlock& b) {
    gpu::InstanceData i;
    std::copy(std::begin(b.viewFromModel), std::end(b.viewFromModel), i.viewFromModel);
    std::copy(std::begin(b.normalMatrix), std::end(b.normalMatrix), i.normalMatrix);
    return i;
}

// Neighbouring draws of one primitive that differ only in their transforms become one
// instanced draw (shaders/include/instance.glsl): EXT_mesh_gpu_instancing's instances, and any
// nodes that share a mesh. Their order is kept, so the picture is the one the separate draws
// make.
void mergeInstances(const frame::Frame& frame, std::vector<gpu::DrawCommand>& draws,
                    std::vector<gpu::InstanceData>& instances) {
    std::vector<gpu::DrawCommand> merged;
    merged.reserve(draws.size());
    for (std::size_t i = 0; i < draws.size();) {
        std::size_t end = i + 1;
        if (instanceable(frame, draws[i]))
            while (end < draws.size() && draws[end].pipeline == draws[i].pipeline &&
                   instanceKey(draws[end]) == instanceKey(draws[i]) && instanceable(frame, draws[end]))
                ++end;
        gpu::DrawCommand c = draws[i];
        if (end - i > 1) {
            c.pipeline.constants[LANTERN_SC_INSTANCED] = 1;
            c.firstInstance = std::uint32_t(instances.size());
            c.instanceCount = std::uint32_t(end - i);
            for (std::size_t k = i; k < end; ++k) instances.push_back(instanceData(draws[k].block));
        }
        merged.push_back(c);
        i = end;
    }
    draws = std::move(merged);
}

// The deformation pre-pass: one command per (node, primitive, flat) that a draw deforms, with
// the pose's joint matrices (world from bind space) and morph weights as floats.
void addDeforms(const Scene& scene, const frame::Frame& frame, gpu::DrawList& list) {
    std::map<std::tuple<std::uint32_t, std::uint32_t, bool>, int> made;
    for (gpu::ViewCommands& v : list.views)
        for (gpu::DrawCommand& c : v.draws) {
            const frame::Draw* d = frame.draw(c.block.drawIndex);
            if (!d || !d->deformed) continue;
            const bool flat = c.pipeline.program == frame::Program::Flat;
            const auto key = std::tuple{d->node, d->primitive, flat};
            auto it = made.find(key);
            if (it == made.end()) {
                gpu::DeformCommand job;
                job.mesh = d->mesh;
                job.primitive = d->primitive;
                job.flat = flat;
                const Primitive& prim = scene.meshes[d->mesh].primitives[d->primitive];
                if (isSkinned(scene, int(d->node), prim))
                    for (const glm::dmat4& m :
                         frame.pose.jointMatrices[std::size_t(scene.nodes[d->node].skin)])
                        job.joints.push_back(toMat4(m));
                if (!prim.targets.empty())
                    for (double w : frame.pose.morphWeights[d->node]) job.weights.push_back(float(w));
                list.deforms.push_back(std::move(job));
                it = made.emplace(key, int(list.deforms.size()) - 1).first;
            }
            c.deform = it->second;
        }
}

} // namespace

gpu::Mat4 toMat4(const glm::dmat4& m) {
    gpu::Mat4 r;
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) r.m[c * 4 + k] = float(m[c][k]);
    return r;
}

gpu::LightData packLight(const frame::EyeLight& l) {
    gpu::LightData d;
    d.position = l.type == LightType::Directional ? vec4(l.toLight, 0.0) : vec4(l.position, 1.0);
    d.ambient = vec4(l.ambient);
    d.diffuse = vec4(l.diffuse);
    d.specular = vec4(l.specular);
    d.spotDirection = vec4(l.spotAxis, l.oneMinusCosCutoff);
    d.attenuation = vec4(glm::dvec4(l.attenuation, l.invRange));
    d.spot = vec4(glm::dvec4(l.exponent, l.cosOuter, l.coneScale, 0.0));
    d.info.x = lightType(l.type);
    d.info.y = l.falloff == LightFalloff::Gl ? LANTERN_FALLOFF_GL : LANTERN_FALLOFF_GLTF;
    return d;
}

gpu::MaterialData packMaterial(const Material& m) {
    gpu::MaterialData d;
    d.front = packSide(m.front);
    d.back = m.back ? packSide(*m.back) : d.front;
    // A cutoff of -1 never discards: the all-features pipeline runs the mask test everywhere.
    d.params.x = m.alphaMode == AlphaMode::Mask ? float(m.alphaCutoff) : -1.0f;
    auto rows = [](const glm::dmat3& t, gpu::Vec4& row0, gpu::Vec4& row1) {
        // column-major: t[column][row]
        row0 = {float(t[0][0]), float(t[1][0]), float(t[2][0]), 0.0f};
        row1 = {float(t[0][1]), float(t[1][1]), float(t[2][1]), 0.0f};
    };
    rows(m.baseColorUvTransform, d.uvRow0, d.uvRow1);
    const TextureMap* maps[4] = {&m.metallicRoughnessMap, &m.normalMap, &m.occlusionMap, &m.emissiveMap};
    for (int k = 0; k < 4; ++k) rows(maps[k]->uvTransform, d.mapUv[2 * k], d.mapUv[2 * k + 1]);
    d.params.y = float(frame::materialMaps(m));
    if (m.pbr) {
        d.pbrBase = vec4(m.pbr->baseColor);
        d.pbrParams = {float(m.pbr->metallic), float(m.pbr->roughness), 0.0f, 0.0f};
        d.params.z = float(m.pbr->dielectricF0);
    }
    d.pbrParams.z = float(m.normalScale);
    d.pbrParams.w = float(m.occlusionStrength);
    return d;
}

gpu::TargetDesc targetFor(const RenderOptions& o) {
    gpu::TargetDesc t;
    t.width = std::uint32_t(std::max(o.width, 0));
    t.height = std::uint32_t(std::max(o.height, 0));
    t.samples = std::uint32_t(std::max(o.msaa, 0));
    t.aovs = o.aovs;
    t.reversedZ = o.depth == DepthMode::ReversedZ;
    t.transparency = effectiveTransparency(o);  // buildDrawList: sorted without blended draws
    t.clear = o.background;
    t.pointSize = float(o.pointSize);
    t.lineWidth = float(o.lineWidth);
    return t;
}

gpu::Overlays overlaysFor(const Scene& scene, const frame::Frame& frame, const RenderOptions& o) {
    gpu::Overlays ov;
    ov.wireframe = o.wireframe;
    ov.normals = o.normals;
    if (o.normals) {
        double length = o.normalLength;
        if (!(length > 0.0)) {
            const Bounds b = computeBounds(scene, frame.pose);
            length = b.empty() ? 0.0 : 0.03 * b.radius();
        }
        ov.normalLength = float(length);
    }
    return ov;
}

gpu::DrawList buildDrawList(const Scene& scene, const frame::Frame& frame,
                            const RenderOptions& o) {
    gpu::DrawList list;
    list.target = targetFor(o);
    for (const Material& m : frame.materials) list.materials.push_back(packMaterial(m));
    list.overlays = overlaysFor(scene, frame, o);
    // Frames that read the draw ids back (the probe, id AOVs, Cryptomatte) or draw the overlays
    // (which follow each draw's transform) keep one draw per instance.
    const bool instancing = o.instancing && !list.target.readIds() && !list.overlays.any();
    for (std::size_t vi = 0; vi < frame.views.size(); ++vi) {
        list.views.push_back(packView(frame, vi, o));
        if (instancing) mergeInstances(frame, list.views.back().draws, list.instances);
    }
    addDeforms(scene, frame, list);
    list.clusterCulling = o.culling;
    list.lodError = list.clusterCulling ? float(o.lodError) : 0.0f;
    packShadows(scene, frame, o, list);
    // A frame without blended draws records no transparency pass and allocates nothing for it.
    bool blended = false;
    for (const gpu::ViewCommands& v : list.views)
        for (const gpu::DrawCommand& d : v.draws) blended |= d.pipeline.blend;
    if (!blended) list.target.transparency = TransparencyMethod::Sorted;
    return list;
}

} // namespace lantern::render
