// Feature resolution: the lighting switches after the options' overrides, what a frame's
// lights need, and the lines --explain prints. A draw's own features are resolved where the
// draw is built (Frame.cpp, drawFeatures); render/ maps all of them to pipeline variants.
#include "frame/Frame.h"

namespace lantern::frame {

const char* toString(Program p) noexcept {
    switch (p) {
    case Program::Phong: return "phong";
    case Program::Gouraud: return "gouraud";
    case Program::Flat: return "flat";
    case Program::GlFlat: return "gl-flat";
    case Program::Floor: return "floor";
    }
    return "?";
}

bool twoSidedLighting(const Lighting& lighting, const Material& material) noexcept {
    return lighting.model.twoSided.value_or(material.doubleSided);
}

std::uint32_t materialMaps(const Material& m) noexcept {
    std::uint32_t bits = 0;
    auto add = [&](const TextureMap& map, std::uint32_t bit) {
        if (map.texture < 0) return;
        bits |= bit;
        if (map.secondSet) bits |= bit << kMapSecondSetShift;
    };
    if (m.pbr) add(m.metallicRoughnessMap, kMapMetallicRoughness);
    add(m.normalMap, kMapNormal);
    add(m.occlusionMap, kMapOcclusion);
    add(m.emissiveMap, kMapEmissive);
    return bits;
}

Lighting resolveLighting(const Scene& scene, int root, const RenderOptions& o) {
    Lighting r;
    const int ri = root < 0 ? scene.defaultRoot : root;
    const bool sceneChooses = ri >= 0 && ri < int(scene.roots.size()) &&
                              scene.roots[std::size_t(ri)].lighting.has_value();
    if (sceneChooses) r.model = *scene.roots[std::size_t(ri)].lighting;
    if (o.shading) r.model.shading = *o.shading;
    if (o.specular) r.model.specular = *o.specular;
    if (o.localViewer) r.model.localViewer = *o.localViewer;
    if (o.twoSided) r.model.twoSided = *o.twoSided;
    // GL's default shading is GL_SMOOTH: with --gl-compat a scene that does not choose a mode
    // (no LANTERN_lighting) is shaded per vertex, as OpenGL would.
    if (o.glCompat && !o.shading && !sceneChooses) r.model.shading = ShadingMode::Gouraud;
    r.glCompat = o.glCompat;
    r.clamp = o.glCompat ? Clamp::Gl : o.clamp ? Clamp::Fragment : Clamp::None;
    switch (r.model.shading) {
    case ShadingMode::Phong: r.program = Program::Phong; break;
    case ShadingMode::Gouraud: r.program = Program::Gouraud; break;
    case ShadingMode::Flat: r.program = o.glCompat ? Program::GlFlat : Program::Flat; break;
    }
    if (o.features == FeatureMode::Floor) r.program = Program::Floor;
    // Exact colours: the material's colour read per fragment, never interpolated or clamped.
    if (o.unlitExact) {
        r.clamp = Clamp::None;
        if (r.program != Program::Floor) r.program = Program::Phong;
    }
    return r;
}

namespace {

void addCount(std::vector<std::string>& f, const char* what, std::size_t n) {
    if (n) f.push_back(std::string("light:") + what + " x" + std::to_string(n));
}

// Features the draws use (any draw of any view).
DrawFeatures anyDraw(const Frame& frame) {
    DrawFeatures any;
    for (const View& v : frame.views)
        for (const Draw& d : v.draws) {
            any.specular |= d.features.specular;
            any.vertexColor |= d.features.vertexColor;
            any.texture |= d.features.texture;
            any.alphaMask |= d.features.alphaMask;
            any.blend |= d.features.blend;
            any.unlit |= d.features.unlit;
        }
    return any;
}

} // namespace

std::vector<std::string> describeFeatures(const Frame& frame, const RenderOptions& o) {
    std::vector<std::string> f;
    const LightFeatures& lf = frame.lightFeatures;
    const Lighting& lit = frame.lighting;
    if (lf.glDefault) f.push_back("light:gl-default (headlight, directional)");
    addCount(f, "directional", lf.directional);
    addCount(f, "point", lf.point);
    addCount(f, "spot", lf.spot);
    if (lf.glAttenuation) f.push_back("attenuation:gl");
    if (lf.glSpot) f.push_back("spot-cone:gl");
    if (lf.gltfFalloff) f.push_back("falloff:gltf");
    f.push_back(std::string("shading:") + toString(lit.model.shading) +
                (lit.program == Program::GlFlat ? " (provoking vertex)" : ""));
    if (lit.model.localViewer) f.push_back("local-viewer");
    if (lit.model.twoSided.value_or(false)) f.push_back("two-sided");
    if (lit.clamp == Clamp::Gl) f.push_back("clamp:gl (per vertex)");
    if (lit.clamp == Clamp::Fragment) f.push_back("clamp");
    if (o.aovs.any()) f.push_back("aov");
    if (o.msaa > 1) f.push_back("msaa:" + std::to_string(o.msaa));
    if (o.lightsViewFromWorld) f.push_back("lights-follow-camera");
    const DrawFeatures any = anyDraw(frame);
    // The specular model only matters when some draw has a specular term at all.
    f.push_back(any.specular ? std::string("specular:") + toString(lit.model.specular)
                             : std::string("specular:none (no specular light on a specular "
                                           "material)"));
    if (any.vertexColor) f.push_back("vertex-colors");
    if (any.texture) f.push_back("texture");
    if (any.alphaMask) f.push_back("alpha-mask");
    if (any.blend) f.push_back("alpha-blend");
    if (any.unlit) f.push_back("unlit");
    std::size_t deformed = 0;
    for (const View& v : frame.views)
        for (const Draw& d : v.draws) deformed += d.deformed ? 1 : 0;
    if (deformed > 0) f.push_back("deform:skin/morph x" + std::to_string(deformed));
    return f;
}

} // namespace lantern::frame
