// Features -> specialisation constants, and their description for --explain.
#include "render/Variants.h"

#include <algorithm>
#include <sstream>
#include <utility>

namespace lantern::render {
namespace {

static_assert(frame::kMapMetallicRoughness == LANTERN_MAP_METALLIC_ROUGHNESS &&
              frame::kMapNormal == LANTERN_MAP_NORMAL && frame::kMapOcclusion == LANTERN_MAP_OCCLUSION &&
              frame::kMapEmissive == LANTERN_MAP_EMISSIVE && frame::kMapAll == LANTERN_MAP_ALL &&
              frame::kMapSecondSetShift == LANTERN_MAP_SECOND_SET_SHIFT &&
              frame::kMapSecondSets == LANTERN_MAP_SECOND_SETS);

std::uint32_t lightTypeBits(const frame::LightFeatures& l) {
    std::uint32_t bits = 0;
    if (l.directional) bits |= LANTERN_LIGHT_BIT_DIRECTIONAL;
    if (l.point) bits |= LANTERN_LIGHT_BIT_POINT;
    if (l.spot) bits |= LANTERN_LIGHT_BIT_SPOT;
    return bits;
}

// A light's kind as the unrolled lighting reads it (shaders/include/lighting.glsl): the type
// and falloff that render/DrawLists.cpp packs into its LightData.info.
std::uint32_t lightKind(LightType type, LightFalloff falloff) {
    const std::uint32_t t = type == LightType::Directional ? LANTERN_LIGHT_DIRECTIONAL
                            : type == LightType::Point     ? LANTERN_LIGHT_POINT
                                                           : LANTERN_LIGHT_SPOT;
    const std::uint32_t f = falloff == LightFalloff::Gl ? LANTERN_FALLOFF_GL : LANTERN_FALLOFF_GLTF;
    return t | f << 2;
}

std::uint32_t clampMode(frame::Clamp c) {
    switch (c) {
    case frame::Clamp::None: return LANTERN_CLAMP_NONE;
    case frame::Clamp::Fragment: return LANTERN_CLAMP_FRAGMENT;
    case frame::Clamp::Gl: return LANTERN_CLAMP_GL;
    }
    return LANTERN_CLAMP_NONE;
}

} // namespace

TransparencyMethod effectiveTransparency(const RenderOptions& o) {
    return o.transparency.value_or(o.glCompat ? TransparencyMethod::Sorted : TransparencyMethod::Exact);
}

gpu::PipelineKey pipelineKey(const frame::Frame& frame, const frame::Draw& d,
                             const RenderOptions& o) {
    const frame::Lighting& lit = frame.lighting;
    const frame::LightFeatures& lights = frame.lightFeatures;
    const frame::DrawFeatures& f = d.features;
    const bool all = o.features == FeatureMode::AllFeatures;
    gpu::PipelineKey k;
    k.program = lit.program;
    k.topology = d.topology;
    k.blend = f.blend;
    if (f.blend) {
        const TransparencyMethod t = effectiveTransparency(o);
        k.blendPath = t == TransparencyMethod::Exact      ? gpu::BlendPath::List
                      : t == TransparencyMethod::Weighted ? gpu::BlendPath::Weighted
                                                          : gpu::BlendPath::Over;
    }
    k.aov = o.aovs.any();
    k.aovSurface = o.aovs.anySurface();
    k.samples = std::uint32_t(o.msaa);
    k.reversedZ = o.depth == DepthMode::ReversedZ;
    auto& sc = k.constants;
    const std::uint32_t model = lit.model.specular == SpecularModel::Blinn ? LANTERN_SPECULAR_BLINN
                                                                           : LANTERN_SPECULAR_PHONG;
    sc[LANTERN_SC_LIGHT_TYPES] = all ? 7u : lightTypeBits(lights);
    sc[LANTERN_SC_GL_ATTENUATION] = all || lights.glAttenuation;
    sc[LANTERN_SC_GL_SPOT] = all || lights.glSpot;
    sc[LANTERN_SC_GLTF_FALLOFF] = all || lights.gltfFalloff;
    sc[LANTERN_SC_SPECULAR] = (all || f.specular) ? model : LANTERN_SPECULAR_NONE;
    sc[LANTERN_SC_LOCAL_VIEWER] = lit.model.localViewer;
    sc[LANTERN_SC_TWO_SIDED] = f.twoSided;
    sc[LANTERN_SC_VERTEX_COLOR] = all || f.vertexColor;
    sc[LANTERN_SC_TEXTURE] = all || f.texture;
    sc[LANTERN_SC_ALPHA_MASK] = all || f.alphaMask;
    sc[LANTERN_SC_CLAMP] = clampMode(lit.clamp);
    sc[LANTERN_SC_UNLIT] = f.unlit;
    sc[LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE] = f.ambientFollowsDiffuse;
    sc[LANTERN_SC_OPAQUE] = !f.blend;
    sc[LANTERN_SC_MAPS] = all ? LANTERN_MAP_ALL | LANTERN_MAP_SECOND_SETS : f.maps;
    // Shadows only where a light casts them (frame/Shadows.cpp): other frames keep their variants.
    if (frame.shadows.any() && !f.unlit)
        sc[LANTERN_SC_SHADOWS] = o.shadows.filter == ShadowFilter::Pcf    ? LANTERN_SHADOW_PCF
                                 : o.shadows.filter == ShadowFilter::Pcss ? LANTERN_SHADOW_PCSS
                                                                          : LANTERN_SHADOW_HARDWARE;
    // A loop over up to LANTERN_UNIFORM_LIGHTS lights reads them from a uniform buffer, which
    // llvmpipe reads faster at an index that differs between lanes; unrolled lights (read at
    // constant indices, where the storage buffer is the faster on llvmpipe), more lights and
    // the all-features variant read the storage buffer (docs/performance.md).
    sc[LANTERN_SC_LIGHTS_UNIFORM] = !all && lights.kinds.size() > LANTERN_MAX_UNROLLED_LIGHTS &&
                                    lights.kinds.size() <= LANTERN_UNIFORM_LIGHTS;
    // A few lights are unrolled, each for its kind; more (and the all-features variant) loop.
    if (!all && lights.kinds.size() <= LANTERN_MAX_UNROLLED_LIGHTS) {
        sc[LANTERN_SC_UNROLLED_LIGHTS] = std::uint32_t(lights.kinds.size());
        for (std::size_t i = 0; i < lights.kinds.size(); ++i)
            sc[LANTERN_SC_LIGHT_KINDS] |= lightKind(lights.kinds[i].first, lights.kinds[i].second)
                                          << (LANTERN_LIGHT_KIND_BITS * i);
    }
    return k;
}

std::string describe(const gpu::PipelineKey& k) {
    std::ostringstream s;
    s << frame::toString(k.program) << ": lights=";
    const std::uint32_t t = k.constants[LANTERN_SC_LIGHT_TYPES];
    bool any = false;
    for (auto [bit, name] : {std::pair{LANTERN_LIGHT_BIT_DIRECTIONAL, "directional"},
                             std::pair{LANTERN_LIGHT_BIT_POINT, "point"},
                             std::pair{LANTERN_LIGHT_BIT_SPOT, "spot"}})
        if (t & std::uint32_t(bit)) {
            s << (any ? "+" : "") << name;
            any = true;
        }
    if (!any) s << "none";
    if (const std::uint32_t n = k.constants[LANTERN_SC_UNROLLED_LIGHTS]) s << " unrolled=" << n;
    const char* spec[] = {"none", "blinn", "phong"};
    s << " specular=" << spec[std::min<std::uint32_t>(k.constants[LANTERN_SC_SPECULAR], 2)];
    auto flag = [&](int id, const char* name) {
        if (k.constants[std::size_t(id)]) s << " " << name;
    };
    flag(LANTERN_SC_GL_ATTENUATION, "attenuation");
    flag(LANTERN_SC_GL_SPOT, "gl-spot");
    flag(LANTERN_SC_GLTF_FALLOFF, "gltf-falloff");
    flag(LANTERN_SC_LOCAL_VIEWER, "local-viewer");
    flag(LANTERN_SC_TWO_SIDED, "two-sided");
    flag(LANTERN_SC_VERTEX_COLOR, "vertex-color");
    flag(LANTERN_SC_TEXTURE, "texture");
    flag(LANTERN_SC_ALPHA_MASK, "alpha-mask");
    flag(LANTERN_SC_UNLIT, "unlit");
    flag(LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE, "ambient=diffuse");
    flag(LANTERN_SC_LIGHTS_UNIFORM, "uniform-lights");
    flag(LANTERN_SC_INSTANCED, "instanced");
    if (const std::uint32_t sh = k.constants[LANTERN_SC_SHADOWS])
        s << (sh == LANTERN_SHADOW_PCF    ? " shadows=pcf"
              : sh == LANTERN_SHADOW_PCSS ? " shadows=pcss"
                                          : " shadows=hardware");
    const std::uint32_t maps = k.constants[LANTERN_SC_MAPS];
    for (auto [bit, name] : {std::pair{LANTERN_MAP_METALLIC_ROUGHNESS, "metallic-roughness-map"},
                             std::pair{LANTERN_MAP_NORMAL, "normal-map"},
                             std::pair{LANTERN_MAP_OCCLUSION, "occlusion-map"},
                             std::pair{LANTERN_MAP_EMISSIVE, "emissive-map"}})
        if (maps & bit) s << " " << name;
    if (maps & LANTERN_MAP_SECOND_SETS) s << " second-uv-set";
    const char* clamps[] = {"", " clamp", " gl-clamp"};
    s << clamps[std::min<std::uint32_t>(k.constants[LANTERN_SC_CLAMP], 2)];
    s << (k.constants[LANTERN_SC_OPAQUE] ? " opaque" : "");
    if (k.topology == Topology::Lines) s << " lines";
    if (k.topology == Topology::Points) s << " points";
    if (k.blend)
        s << (k.blendPath == gpu::BlendPath::List       ? " blend=fragment-list"
              : k.blendPath == gpu::BlendPath::Weighted ? " blend=weighted"
                                                        : " blend");
    if (k.aov) s << (k.aovSurface ? " aov+surface" : " aov");
    if (k.samples > 1) s << " msaa=" << k.samples;
    if (!k.reversedZ) s << " standard-z";
    return s.str();
}

} // namespace lantern::render
